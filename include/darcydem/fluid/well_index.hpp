#pragma once
// A source of water with a radius, a well (Peaceman 1978, 1983): its
// cell's pressure is the continuous solution's at the cell's equivalent
// radius r_e from it, so the pressure at the well's own radius r_w differs
// from the cell's by the continuous drop between r_w and r_e, and the
// well index WI = Q / (p_w - p_cell) joins the two.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "darcydem/core/vec.hpp"
#include "darcydem/fluid/fluid_boundary.hpp"
#include "darcydem/fluid/fluid_grid.hpp"
#include "darcydem/fluid/fluid_laws.hpp"

namespace darcydem {

/// The simple cubic lattice's Green's function at its origin: G0 = W_S / 2,
/// W_S Watson's integral (1/pi^3) iiint dk / (3 - cos k1 - cos k2 - cos k3)
/// over [0, pi]^3 = sqrt(6) / (96 pi^3) Gamma(1/24) Gamma(5/24) Gamma(7/24)
/// Gamma(11/24) = 0.505462: the pressure of a unit source on the seven-point
/// stencil of unit conductances, in its own cell.
inline double simple_cubic_green_at_origin() {
  const double pi3 = std::numbers::pi * std::numbers::pi * std::numbers::pi;
  return 0.5 * std::sqrt(6.0) / (96.0 * pi3) * std::tgamma(1.0 / 24.0) * std::tgamma(5.0 / 24.0) *
         std::tgamma(7.0 / 24.0) * std::tgamma(11.0 / 24.0);
}

/// The widths of the cell holding x, m.
template <int D>
[[nodiscard]] Vec<D> cell_widths_at(const FluidGrid<D>& grid, const Vec<D>& x) {
  const auto at = grid.coords(grid.cell_holding(x));
  Vec<D> widths;
  for (int k = 0; k < D; ++k) widths[k] = grid.width(k, at[k]);
  return widths;
}

/// The permeability's proportions along the axes, all the equivalent
/// radius needs of it: a constant one's, or Kozeny-Carman's anisotropy.
template <int D>
[[nodiscard]] Vec<D> permeability_shape(const PermeabilitySpec<D>& spec) {
  return spec.model == PermeabilityModel::constant ? spec.intrinsic : spec.anisotropy;
}

/// A cell's equivalent radius, m, for a source at its centre: in 2D
/// Peaceman's (1983), (e^-gamma / 2) sqrt(sqrt(ky / kx) hx^2 + sqrt(kx / ky)
/// hy^2) / ((ky / kx)^(1/4) + (kx / ky)^(1/4)), h e^-gamma / (2 sqrt 2) =
/// 0.1985 h for a square cell and isotropic permeability (exact for it:
/// the square lattice's Green's function's constant); in 3D, for a cubic
/// cell of side h and isotropic permeability, where Q mu / (4 pi kappa r)
/// equals the seven-point stencil's G0 Q mu / (kappa h): h / (4 pi G0) =
/// 0.31487 h (other cells in 3D: see the scene reader, which refuses them).
template <int D>
[[nodiscard]] double equivalent_radius(const Vec<D>& widths, const Vec<D>& kappa) {
  if constexpr (D == 2) {
    const double a = std::sqrt(kappa[1] / kappa[0]);  // sqrt(ky / kx)
    return 0.5 * std::exp(-std::numbers::egamma) *
           std::sqrt(a * widths[0] * widths[0] + widths[1] * widths[1] / a) /
           (std::sqrt(a) + 1.0 / std::sqrt(a));
  } else {
    return widths[0] / (4.0 * std::numbers::pi * simple_cubic_green_at_origin());
  }
}

/// The well index, m^3/(s Pa) (2D: m^2/(s Pa), per metre): the inflow per
/// unit of the well's pressure over its cell's, for a well of radius
/// `radius` < equivalent_radius in a cell of these widths and intrinsic
/// permeabilities, water of viscosity mu. 2D: 2 pi sqrt(kx ky) / (mu
/// ln(r_e / r_w)); 3D: 4 pi kappa / (mu (1 / r_w - 1 / r_e)).
template <int D>
[[nodiscard]] double well_index(const Vec<D>& widths, const Vec<D>& kappa, double mu, double radius) {
  const double r_e = equivalent_radius<D>(widths, kappa);
  if constexpr (D == 2) {
    return 2.0 * std::numbers::pi * std::sqrt(kappa[0] * kappa[1]) / (mu * std::log(r_e / radius));
  } else {
    return 4.0 * std::numbers::pi * kappa[0] / (mu * (1.0 / radius - 1.0 / r_e));
  }
}

/// A cell a source draws from: its index and, for a screened well, the
/// length of the screen in it, m (0 for a point source's one cell).
struct SourceCell {
  std::size_t cell = 0;
  double length = 0.0;
};

/// The cells source draws from: a point source's one cell, the one holding
/// its position; a screened well's (3D), every cell of the row along its
/// axis through its position that the screen passes through for a length
/// (more than 1e-9 of the cell's width: a screen that ends on a face does
/// not reach beyond it), in order along the axis.
template <int D>
[[nodiscard]] std::vector<SourceCell> source_cells(const FluidGrid<D>& grid, const FluidSource<D>& source) {
  const std::size_t holding = grid.cell_holding(source.position);
  if (!source.screened()) return {{holding, 0.0}};
  const int z = source.screen_axis;
  auto at = grid.coords(holding);
  std::vector<SourceCell> cells;
  for (int k = 0; k < grid.cells[z]; ++k) {
    const double lo = grid.face_at(z, k);
    const double hi = grid.face_at(z, k + 1);
    const double length = std::min(hi, source.screen[1]) - std::max(lo, source.screen[0]);
    if (length <= 1e-9 * (hi - lo)) continue;
    at[z] = k;
    cells.push_back({grid.index(at), length});
  }
  return cells;
}

/// The components of v across `axis` (3D), in order: (y, z), (x, z) or (x, y).
[[nodiscard]] inline Vec<2> across(int axis, const Vec<3>& v) {
  return axis == 0 ? Vec<2>(v[1], v[2]) : axis == 1 ? Vec<2>(v[0], v[2]) : Vec<2>(v[0], v[1]);
}

/// The well index of one cell of a screened well along `axis` (3D),
/// m^3/(s Pa): the flow across the axis to a line well through the cell,
/// Peaceman's 2D index with the cell's widths and permeabilities across
/// it, times the screen's length in it: for a vertical well 2 pi sqrt(kx
/// ky) L / (mu ln(r_e / r_w)).
[[nodiscard]] inline double screen_well_index(int axis, const Vec<3>& widths, const Vec<3>& kappa, double mu,
                                              double radius, double length) {
  return length * well_index<2>(across(axis, widths), across(axis, kappa), mu, radius);
}

}  // namespace darcydem
