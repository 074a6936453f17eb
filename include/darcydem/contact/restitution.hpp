#pragma once
// Damping coefficients that give a prescribed coefficient of restitution.
//
// For both normal laws the impact reduces to one dimensionless equation
//   x'' = -x^a - gamma x^b x',  x(0) = 0, x'(0) = 1,
// with the total force clamped at zero (no attraction): a = 1, b = 0 for the
// linear spring-dashpot (F = k d + c d', c = gamma sqrt(m k)), and a = 3/2,
// b = 1/4 for Hertz with Tsuji's damping (F = K d^1.5 + eta d^0.25 d',
// eta = gamma sqrt(m K)). The restitution depends on gamma alone, so gamma(e)
// is found once per material pair by bisection on an accurate integration.
#include "darcydem/contact/material.hpp"

namespace darcydem {

/// Restitution of the dimensionless impact for damping gamma.
double restitution_of_damping(NormalLaw law, double gamma);

/// The damping gamma that gives restitution e (0 < e <= 1); gamma = 0 for e = 1.
double damping_for_restitution(NormalLaw law, double e);

}  // namespace darcydem
