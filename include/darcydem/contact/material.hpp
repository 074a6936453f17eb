#pragma once
// Materials and the contact parameters of each pair of materials.
#include <cstdint>
#include <string>
#include <vector>

namespace darcydem {

struct Material {
  std::string name;
  double density = 0.0;         ///< kg/m^3
  double youngs_modulus = 0.0;  ///< Pa (Hertz-Mindlin only)
  double poisson_ratio = 0.0;   ///< - (Hertz-Mindlin only)
};

enum class NormalLaw { linear, hertz_mindlin };

/// What a scene says about the contact between two materials.
struct ContactSpec {
  NormalLaw law = NormalLaw::linear;
  double normal_stiffness = 0.0;            ///< N/m (linear)
  double tangential_stiffness_ratio = 1.0;  ///< k_t / k_n (linear)
  double restitution = 1.0;                 ///< normal coefficient of restitution
  double friction = 0.0;                    ///< Coulomb coefficient
  double rolling_friction = 0.0;            ///< mu_r, dimensionless (0: off)
  /// Contact bond (PFC's linear contact bond, YADE's cohesive contact), made
  /// by Simulation::make_bonds: the strengths in tension and in shear, N
  /// (2D: per metre of thickness). Both 0: the pair is never bonded.
  double bond_tensile_strength = 0.0;
  double bond_shear_strength = 0.0;
  /// A bond that also carries a moment (YADE's cohesive moment law, PFC's
  /// parallel bond): the relative rotation of the grains bends it, with
  /// k_b = ratio x k_n x R*^2 (R* = r_i r_j / (r_i + r_j)), and in 3D twists it
  /// (about the normal), with k_tw = ratio x k_n x R*^2; it breaks when the
  /// moment passes the strength, N m (2D: per metre). Ratio 0: a pin.
  double bond_bending_stiffness_ratio = 0.0;
  double bond_bending_strength = 0.0;
  double bond_twisting_stiffness_ratio = 0.0;
  double bond_twisting_strength = 0.0;
  /// Bond strengths that vary from bond to bond (PFC's strength scatter):
  /// Weibull's modulus m of a factor, mean 1, that scales all of a bond's
  /// strengths, drawn from the two grains' ids and the seed. 0: every bond
  /// has the strengths given.
  double bond_strength_weibull_modulus = 0.0;
  std::uint64_t bond_strength_seed = 1;
};

}  // namespace darcydem
