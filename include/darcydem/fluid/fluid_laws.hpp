#pragma once
// Constitutive laws of the pore fluid: permeability and drag.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

/// g used to convert hydraulic conductivity k (m/s) to intrinsic
/// permeability kappa = k mu / (rho_f g) (m^2), as in soil mechanics.
inline constexpr double standard_gravity = 9.80665;  // m/s^2

struct FluidProperties {
  double density = 1000.0;                                                         ///< rho_f, kg/m^3
  double viscosity = 1.0e-3;                                                       ///< mu, Pa s
  double bulk_modulus = 2e9;                                                       ///< K_f, Pa
  [[nodiscard]] double unit_weight() const { return density * standard_gravity; }  ///< gamma_w, N/m^3
};

enum class PermeabilityModel { constant, kozeny_carman };

template <int D>
struct PermeabilitySpec {
  PermeabilityModel model = PermeabilityModel::kozeny_carman;
  Vec<D> intrinsic = Vec<D>::Ones();   ///< kappa per axis, m^2 (constant model)
  double diameter = 1e-3;              ///< d, m (Kozeny-Carman)
  Vec<D> anisotropy = Vec<D>::Ones();  ///< factor on kappa per axis (Kozeny-Carman)
  double max_porosity = 0.9;           ///< porosity used at most (near-empty cells)
  double min_porosity = 0.05;          ///< porosity used at least
};

/// Kozeny-Carman (the paper's Eq. 15 without rho_f g / mu): intrinsic
/// permeability d^2 n^3 / (150 (1 - n)^2), m^2.
inline double kozeny_carman(double diameter, double n) {
  return diameter * diameter * n * n * n / (150.0 * (1.0 - n) * (1.0 - n));
}

/// Kozeny-Carman's d for grains of several sizes: the diameter of equal
/// grains with the same specific surface (solid surface over solid volume:
/// 6/d for spheres, 4/d for discs), sum d^3 / sum d^2 in 3D (the Sauter
/// mean; Carrier's 2003 "effective diameter", the harmonic mean of the
/// sizes weighted by volume) and sum d^2 / sum d in 2D. For equal grains it
/// is their diameter; 0 without grains.
template <int D>
double specific_surface_diameter(const std::vector<double>& radius) {
  static_assert(D == 2 || D == 3);
  double volume_like = 0.0;   // sum d^D
  double surface_like = 0.0;  // sum d^(D-1)
  for (double r : radius) {
    const double d = 2.0 * r;
    const double surface = D == 3 ? d * d : d;
    surface_like += surface;
    volume_like += surface * d;
  }
  return surface_like > 0.0 ? volume_like / surface_like : 0.0;
}

/// The d of Kozeny-Carman that Ergun's viscous drag balances when each
/// grain takes its own diameter: the drag goes as V_p / d_p^2 grain by
/// grain, Kozeny-Carman's pressure drop as 1 / d^2, so d^2 = sum V_p /
/// sum (V_p / d_p^2): sqrt(sum d^3 / sum d) for spheres, sqrt(sum d^2 / N)
/// for discs. It is below the specific-surface diameter for unequal grains;
/// 0 without grains.
template <int D>
double ergun_balance_diameter(const std::vector<double>& radius) {
  static_assert(D == 2 || D == 3);
  double volume_like = 0.0;  // sum d^D
  double drag_like = 0.0;    // sum d^(D-2)
  for (double r : radius) {
    const double d = 2.0 * r;
    drag_like += D == 3 ? d : 1.0;
    volume_like += D == 3 ? d * d * d : d * d;
  }
  return drag_like > 0.0 ? std::sqrt(volume_like / drag_like) : 0.0;
}

enum class DragLaw {
  darcy,  ///< beta = n^2 mu / kappa from the cell's own permeability
  ergun,  ///< Ergun (n < 0.8) blended into Wen-Yu (n > 0.8)
};

/// Which cells a grain's drag takes its porosity, permeability and solid
/// velocity from.
enum class DragCells {
  centre,    ///< the cell that holds the grain's centre (the paper, PFC)
  overlaps,  ///< every cell the grain overlaps, weighted by the overlap volumes
};

/// Ergun's beta (the paper's Eq. 9): 150 mu (1-n)^2 / (d^2 n) + 1.75 rho_f (1-n) |slip| / d.
inline double ergun_beta(double n, double d, double slip, const FluidProperties& f) {
  return 150.0 * f.viscosity * (1.0 - n) * (1.0 - n) / (d * d * n) + 1.75 * f.density * (1.0 - n) * slip / d;
}

/// C_d Re of Wen and Yu: 24 (1 + 0.15 Re^0.687), 0.44 Re above Re = 1000.
inline double wen_yu_cd_re(double re) {
  if (re <= 0.0) return 24.0;
  return re < 1000.0 ? 24.0 * (1.0 + 0.15 * std::pow(re, 0.687)) : 0.44 * re;
}

/// The drag of a grain alone in water, per unit of its volume and of its
/// slip speed (N s/m^4): 3/4 C_d Re mu / d^2 with Wen and Yu's C_d Re at
/// n = 1 and Re = rho_f d |slip| / mu, so that the force on a sphere is
/// Schiller and Naumann's 3 pi mu d |slip| (1 + 0.15 Re^0.687) (0.44 C_d
/// above Re = 1000).
inline double lone_grain_drag(double d, double speed, const FluidProperties& f) {
  return 0.75 * wen_yu_cd_re(f.density * d * speed / f.viscosity) * f.viscosity / (d * d);
}

/// Wen and Yu's beta: 3/4 C_d rho_f n (1-n) |slip| n^-2.65 / d, with
/// C_d = 24/Re (1 + 0.15 Re^0.687) (0.44 above Re = 1000), Re = rho_f n d |slip| / mu.
inline double wen_yu_beta(double n, double d, double slip, const FluidProperties& f) {
  const double re = f.density * n * d * slip / f.viscosity;
  return 0.75 * wen_yu_cd_re(re) * f.viscosity * (1.0 - n) * std::pow(n, -2.65) / (d * d);
}

/// Ergun below n = 0.8 and Wen-Yu above, switched continuously by the
/// blending function of Huilin and Gidaspow (2003),
/// phi = 1/2 + atan(262.5 ((1-n) - 0.2)) / pi. The parts that depend on the
/// porosity alone are computed once per cell (`of`), the rest per grain.
struct ErgunWenYu {
  double n = 0.4;
  double phi = 1.0;             ///< weight of Ergun
  double ergun_viscous = 0.0;   ///< 150 mu (1-n)^2 / n
  double ergun_inertial = 0.0;  ///< 1.75 rho_f (1-n)
  double wen_yu = 0.0;          ///< 3/4 mu (1-n) n^-2.65

  static ErgunWenYu of(double n, const FluidProperties& f) {
    return with(n, std::atan(blend_argument(n)), std::pow(n, wen_yu_exponent), f);
  }
  /// The argument of the blending function's atan.
  static double blend_argument(double n) { return 262.5 * ((1.0 - n) - 0.2); }
  static constexpr double wen_yu_exponent = -2.65;
  /// `of` with atan(blend_argument(n)) and n^wen_yu_exponent given (so that
  /// a caller can compute them for many cells at once).
  static ErgunWenYu with(double n, double blend_atan, double n_power, const FluidProperties& f) {
    ErgunWenYu c;
    c.n = n;
    c.phi = 0.5 + blend_atan / std::numbers::pi;
    c.ergun_viscous = 150.0 * f.viscosity * (1.0 - n) * (1.0 - n) / n;
    c.ergun_inertial = 1.75 * f.density * (1.0 - n);
    c.wen_yu = 0.75 * f.viscosity * (1.0 - n) * n_power;
    return c;
  }
  /// beta for a grain of diameter d at slip speed |v_f - v_p|, kg/(m^3 s).
  [[nodiscard]] double beta(double d, double slip, const FluidProperties& f) const {
    const double ergun = ergun_viscous / (d * d) + ergun_inertial * slip / d;
    const double re = f.density * n * d * slip / f.viscosity;
    return phi * ergun + (1.0 - phi) * wen_yu_cd_re(re) * wen_yu / (d * d);
  }
};

inline double ergun_wen_yu_beta(double n, double d, double slip, const FluidProperties& f) {
  return ErgunWenYu::of(n, f).beta(d, slip, f);
}

}  // namespace darcydem
