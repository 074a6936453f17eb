#pragma once
// Boundary conditions of the pore fluid on the sides of the grid's box,
// and on patches: parts of a side with a condition of their own (an
// orifice in a floor, a drained strip of a surface).
#include <array>
#include <string>
#include <vector>

#include "darcydem/core/time_series.hpp"
#include "darcydem/core/vec.hpp"

namespace darcydem {

enum class FluidBoundaryType {
  no_flow,  ///< impermeable: zero flux
  drained,  ///< imposed excess pore pressure, Pa
  flux,     ///< imposed inflow (superficial / Darcy velocity into the grid), m/s
};

struct FluidBoundary {
  FluidBoundaryType type = FluidBoundaryType::no_flow;
  TimeSeries value;  ///< Pa for drained, m/s (positive inwards) for flux
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(type, value);
  }
};

enum class FluidSourceType {
  inflow,    ///< imposed inflow, m^3/s (2D: per metre)
  pressure,  ///< imposed excess pore pressure in its cell, Pa
};

/// A source of pore water inside the grid (a well, an injection point, a
/// drain; YADE's imposeFlux and imposePressure at a point, PFC's fluid
/// source) in the cell holding `position`: the water it gives, m^3/s (2D:
/// per metre of thickness), negative where it pumps water out; or the
/// pressure it holds in that cell, giving or taking what water that needs.
template <int D>
struct FluidSource {
  std::string name;
  Vec<D> position = Vec<D>::Zero();
  FluidSourceType type = FluidSourceType::inflow;
  TimeSeries value;  ///< m^3/s into the grid, or Pa
  /// The well's radius r_w, m (0: none): its pressure is then at its bore,
  /// which its well index joins to its cell's (fluid/well_index.hpp); a
  /// held pressure is the bore's.
  double radius = 0.0;
  /// A well screened along axis `screen_axis` (3D; z: a vertical well, x
  /// or y: a horizontal drain), m: from screen[0] to screen[1] through
  /// `position`, whose coordinate along that axis is the screen's middle.
  /// It draws from (or gives to) every cell the screen passes through,
  /// each joined to its bore, at one pressure, by its own well index
  /// (MODFLOW's multi-node well); a given inflow is shared among them as
  /// that pressure has it. Needs a radius. Empty (screen[1] <= screen[0]):
  /// a point source.
  std::array<double, 2> screen{0.0, 0.0};
  int screen_axis = D - 1;
  /// A drain (a relief well, a toe drain; MODFLOW's drain): while it holds
  /// a pressure it only takes water out, open while the water around it
  /// (at its bore, or in its cell) stands above that pressure, shut (giving
  /// nothing; a screened well's bore still joining its cells) otherwise.
  bool drain = false;
  /// Whether it acts as a drain now: a drain holding a pressure (a stage
  /// that gives it an inflow makes it a plain source).
  [[nodiscard]] bool drains() const { return drain && type == FluidSourceType::pressure; }
  [[nodiscard]] bool screened() const { return screen[1] > screen[0]; }
  /// Only the condition changes in a run (stages); where it lies comes
  /// from the scene.
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(type, value);
  }
};

/// A stage's change of a source: its new condition.
struct FluidSourceChange {
  std::size_t source = 0;  ///< index in PoreFluid::sources
  FluidSourceType type = FluidSourceType::inflow;
  TimeSeries value;
};

/// Whether `centre` lies in [lo, hi] along every axis but `skip`: for a
/// face normal to `skip`, the centre of either cell beside it will do
/// (FluidGrid::centre).
template <int D>
[[nodiscard]] bool in_box_across(int skip, const Vec<D>& centre, const std::array<double, D>& lo,
                                 const std::array<double, D>& hi) {
  bool in = true;
  for (int k = 0; k < D; ++k) {
    if (k != skip) in = in && centre[k] >= lo[k] && centre[k] <= hi[k];
  }
  return in;
}

/// A part of one side of the grid with its own condition: the side's
/// boundary faces whose centres lie in the box [lo, hi] (the coordinate
/// along the side's own axis is not used). Elsewhere the side keeps its
/// condition.
template <int D>
struct FluidPatch {
  std::string name;
  int side = 0;  ///< as PoreFluid::sides: x_min, x_max, y_min, ...
  std::array<double, D> lo{};
  std::array<double, D> hi{};
  FluidBoundary condition;

  /// Whether the face beside the cell centred at `centre` on this patch's
  /// side is in it.
  [[nodiscard]] bool holds(const Vec<D>& centre) const { return in_box_across<D>(side / 2, centre, lo, hi); }
  /// Only the condition changes in a run (stages); where the patch lies
  /// comes from the scene.
  template <class Archive>
  void checkpoint(Archive& ar) {
    condition.checkpoint(ar);
  }
};

/// An impermeable wall inside the grid (a sheet pile, a cut-off): the
/// interior faces normal to `axis` on the plane at `at` whose centres lie
/// in [lo, hi] along the other axes carry no Darcy flow, no fluid moved by
/// the skeleton and no pressure gradient (as a no-flow side: the pressure
/// jump across it acts on the wall, not on the grains). It does not stop
/// grains: give a DEM wall where they must not pass.
template <int D>
struct FluidBarrier {
  std::string name;
  int axis = 0;
  double at = 0.0;  ///< m, on a face between two cells
  std::array<double, D> lo{};
  std::array<double, D> hi{};
  /// Whether the face above the cell centred at `centre` along `axis` is in it.
  [[nodiscard]] bool holds(const Vec<D>& centre) const { return in_box_across<D>(axis, centre, lo, hi); }
};

[[nodiscard]] inline std::string to_string(FluidBoundaryType t) {
  switch (t) {
    case FluidBoundaryType::drained:
      return "drained";
    case FluidBoundaryType::flux:
      return "flux";
    default:
      return "no_flow";
  }
}

}  // namespace darcydem
