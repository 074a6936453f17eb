#pragma once
// Boundary conditions of the pore fluid on the sides of the grid's box,
// and on patches: parts of a side with a condition of their own (an
// orifice in a floor, a drained strip of a surface).
#include <array>
#include <string>
#include <vector>

namespace darcydem {

/// A value that varies in time: piecewise linear through (times, values),
/// held constant before the first and after the last point. Times count
/// from `start` (the start of the stage that set it).
struct TimeSeries {
  std::vector<double> times{0.0};
  std::vector<double> values{0.0};
  double start = 0.0;  ///< s

  [[nodiscard]] double at(double t) const {
    const double s = t - start;
    if (s <= times.front()) return values.front();
    for (std::size_t i = 1; i < times.size(); ++i) {
      if (s <= times[i]) {
        const double f = (s - times[i - 1]) / (times[i] - times[i - 1]);
        return values[i - 1] + f * (values[i] - values[i - 1]);
      }
    }
    return values.back();
  }
  static TimeSeries constant(double v) { return TimeSeries{{0.0}, {v}, 0.0}; }
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(times, values, start);
  }
};

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

  /// Whether the face centred at `centre` on this patch's side is in it.
  [[nodiscard]] bool holds(const std::array<double, D>& centre) const {
    bool in = true;
    for (int k = 0; k < D; ++k) {
      if (k != side / 2) in = in && centre[k] >= lo[k] && centre[k] <= hi[k];
    }
    return in;
  }
  /// Only the condition changes in a run (stages); where the patch lies
  /// comes from the scene.
  template <class Archive>
  void checkpoint(Archive& ar) {
    condition.checkpoint(ar);
  }
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
