#include "darcydem/contact/contact_laws.hpp"

#include <cmath>

#include "darcydem/contact/restitution.hpp"

namespace darcydem {

PairParameters make_pair_parameters(const Material& a, const Material& b, const ContactSpec& spec) {
  PairParameters p;
  p.law = spec.law;
  p.friction = spec.friction;
  p.rolling_friction = spec.rolling_friction;
  p.bond_tensile = spec.bond_tensile_strength;
  p.bond_shear = spec.bond_shear_strength;
  p.bondable = spec.law == NormalLaw::linear && (p.bond_tensile > 0.0 || p.bond_shear > 0.0);
  p.bond_bending_ratio = spec.bond_bending_stiffness_ratio;
  p.bond_bending_strength = spec.bond_bending_strength;
  p.bond_twisting_ratio = spec.bond_twisting_stiffness_ratio;
  p.bond_twisting_strength = spec.bond_twisting_strength;
  p.bond_weibull_modulus = spec.bond_strength_weibull_modulus;
  if (p.bond_weibull_modulus > 0.0)
    p.bond_weibull_scale = 1.0 / std::tgamma(1.0 + 1.0 / p.bond_weibull_modulus);
  p.bond_seed = spec.bond_strength_seed;
  p.normal_stiffness = spec.normal_stiffness;
  p.tangential_ratio = spec.tangential_stiffness_ratio;
  if (spec.law == NormalLaw::hertz_mindlin) {
    const double ea = a.youngs_modulus;
    const double eb = b.youngs_modulus;
    const double na = a.poisson_ratio;
    const double nb = b.poisson_ratio;
    p.hertz_modulus = 1.0 / ((1 - na * na) / ea + (1 - nb * nb) / eb);
    const double ga = ea / (2 * (1 + na));
    const double gb = eb / (2 * (1 + nb));
    p.shear_modulus = 1.0 / ((2 - na) / ga + (2 - nb) / gb);
  }
  p.normal_damping = damping_for_restitution(spec.law, spec.restitution);
  // The tangential dashpot uses the damping ratio of a linear oscillator with
  // the same restitution.
  p.tangential_damping = damping_for_restitution(NormalLaw::linear, spec.restitution);
  p.derive();
  return p;
}

}  // namespace darcydem
