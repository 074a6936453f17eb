#pragma once
// Closed-form 1D upward seepage through a soil column (Terzaghi's
// consolidation with a constant inflow q at the undrained-for-solids bottom
// and a drained top), the paper's Eqs. 11-13 with the misprints fixed
// (REFERENCE.md). z is the depth below the drained top, t the time since the
// inflow started. With a compressible pore fluid the same series hold with
// the Biot storage m_v + n/K_f in Cv; the final uplift keeps m_v alone.

namespace darcydem {

struct SeepageColumnParameters {
  double height = 0.05;           ///< H, m
  double inflow = 1e-3;           ///< q, m/s (Darcy velocity)
  double conductivity = 1e-3;     ///< k, m/s
  double compressibility = 1e-5;  ///< m_v, 1/Pa
  double fluid_storage = 0.0;     ///< n / K_f, 1/Pa (0: incompressible)
  double unit_weight = 9806.65;   ///< gamma_w, N/m^3

  /// Cv = k / (gamma_w (m_v + n/K_f)), m^2/s.
  [[nodiscard]] double consolidation_coefficient() const {
    return conductivity / (unit_weight * (compressibility + fluid_storage));
  }
  /// B = m_v / (m_v + n/K_f): the share of a load step the pore fluid takes
  /// at once (1 for an incompressible fluid).
  [[nodiscard]] double undrained_share() const { return compressibility / (compressibility + fluid_storage); }
  /// Steady excess pressure at the bottom, H gamma_w q / k, Pa.
  [[nodiscard]] double steady_bottom_pressure() const { return height * unit_weight * inflow / conductivity; }
  /// Final uplift q H^2 m_v gamma_w / (2 k), m.
  [[nodiscard]] double final_uplift() const {
    return inflow * height * height * compressibility * unit_weight / (2.0 * conductivity);
  }
};

/// Excess pore pressure at depth z and time t, Pa.
double seepage_pressure(const SeepageColumnParameters& p, double depth, double time);
/// Rise of the column's top at time t, m.
double seepage_uplift(const SeepageColumnParameters& p, double time);

/// Terzaghi's 1D consolidation of the same column under a load applied at
/// t = 0 (top drained, bottom sealed, drainage path H): the fraction of the
/// final settlement reached at time t,
///   U = 1 - B sum_m 8 / ((2m+1)^2 pi^2) exp(-(2m+1)^2 pi^2 Tv / 4),
/// with B = m_v / (m_v + n/K_f) the share of the load the pore fluid takes
/// at once (1 for an incompressible fluid). `inflow` is not used.
double consolidation_degree(const SeepageColumnParameters& p, double time);
/// The excess pore pressure of the same consolidation at distance z from
/// the drained end (0..H) and time t after a load stress `stress` (Pa),
///   u = B stress sum_m 4 / ((2m+1) pi) sin((2m+1) pi z / (2H)) exp(-(2m+1)^2 pi^2 Tv / 4),
/// B as above. At z = H, the sealed end (under an impermeable loaded
/// piston), the sine is (-1)^m.
double consolidation_pressure(const SeepageColumnParameters& p, double stress, double distance, double time);

}  // namespace darcydem
