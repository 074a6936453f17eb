#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "darcydem/contact/restitution.hpp"

namespace darcydem {
namespace {

// Without the zero-force clamp the linear oscillator has the closed form
// e = exp(-pi zeta / sqrt(1 - zeta^2)), gamma = 2 zeta. With the clamp the
// particle leaves earlier, slower than that, so e(gamma) must lie below the
// closed form and approach it for light damping.
TEST(Restitution, LinearLightDampingApproachesClosedForm) {
  const double gamma = 0.02;
  const double zeta = gamma / 2.0;
  const double closed = std::exp(-std::numbers::pi * zeta / std::sqrt(1 - zeta * zeta));
  const double e = restitution_of_damping(NormalLaw::linear, gamma);
  EXPECT_GT(e, closed - 1e-9);
  EXPECT_NEAR(e, closed, 1e-3);
}

TEST(Restitution, ElasticImpactKeepsAllEnergy) {
  EXPECT_NEAR(restitution_of_damping(NormalLaw::linear, 0.0), 1.0, 1e-8);
  EXPECT_NEAR(restitution_of_damping(NormalLaw::hertz_mindlin, 0.0), 1.0, 1e-8);
}

TEST(Restitution, CalibrationInvertsTheMap) {
  for (auto law : {NormalLaw::linear, NormalLaw::hertz_mindlin}) {
    for (double e : {0.1, 0.5, 0.95}) {
      const double g = damping_for_restitution(law, e);
      EXPECT_NEAR(restitution_of_damping(law, g), e, 1e-8);
    }
  }
}

TEST(Restitution, RejectsImpossibleValues) {
  EXPECT_THROW(damping_for_restitution(NormalLaw::linear, 0.0), std::invalid_argument);
  EXPECT_THROW(damping_for_restitution(NormalLaw::linear, 1.2), std::invalid_argument);
}

}  // namespace
}  // namespace darcydem
