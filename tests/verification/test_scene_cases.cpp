// The example scenes under examples/dem_cases, run as a user would, against
// their closed forms.
#include <gtest/gtest.h>

#include <cstdio>

#include "scene_loading.hpp"

namespace darcydem {
namespace {

// Rebound speed = e x impact speed. ~300 steps per contact: the half-step
// velocity in the dashpot errs by O(dt/t_c) ~ 0.3%; tolerance 0.5% (issue).
TEST(SceneCases, NormalImpactReboundsWithSetRestitution) {
  auto scene = testing::load_scene<3>("examples/dem_cases/normal_impact.toml");
  testing::run_stages(scene);
  EXPECT_NEAR(scene.simulation.particles.velocity[0].z(), 0.5 * 0.5, 0.005 * 0.25);
}

// Sliding to rolling: v = 5/7 v0. The sphere starts resting on the floor with
// zero overlap and settles by m g / k_n = 1e-8 m (1e-5 r), so the lever arm
// error is negligible; the residual elastic tangential oscillation is damped.
// Tolerance 0.5%.
TEST(SceneCases, SlipToRollReachesFiveSevenths) {
  auto scene = testing::load_scene<3>("examples/dem_cases/slip_to_roll.toml");
  testing::run_stages(scene);
  EXPECT_NEAR(scene.simulation.particles.velocity[0].x(), 0.2 * 5.0 / 7.0, 0.005 * 0.2 * 5.0 / 7.0);
  // Its probes turned the energy budget on: friction took 2/7 of the
  // launch's kinetic energy (rigid grains' closed form). The dashpots add
  // the settling's m g d / 2, 5e-6 of it, and the slide ends within a step
  // (8.6e-7 s) of the 19 ms it lasts: 4.5e-5 (measured: 2.5e-5 above 2/7);
  // 1e-3 bounds them.
  const double launch = 0.5 * 0.2 * 0.2 / scene.simulation.particles.inv_mass[0];
  EXPECT_NEAR(scene.simulation.contact_dissipation(), 2.0 / 7.0 * launch, 1e-3 * 2.0 / 7.0 * launch);
}

// A bed periodic along x and y settles on a floor: with no side walls to
// carry part of it by friction, the floor carries the whole weight once the
// bed is at rest. The stage stops at an unbalanced-force ratio of 1e-4 (each
// grain's resultant 1e-4 of a contact force of a few weights), so the
// residual is far below the 0.5 % of the column-settling case, which we
// assert (measured: 1.6e-4).
TEST(SceneCases, PeriodicBedRestsOnTheFloorWithItsWholeWeight) {
  auto scene = testing::load_scene<3>("examples/dem_cases/periodic_bed.toml");
  // Its random cloud spans the period along x and y, so it wraps round
  // (docs/SCENE.md): centres fall uniformly, and about 200 x (2 r / L) = 33
  // grains (r 0.4-0.6 mm, L = 6 mm) lie within their radius of x's ends
  // (binomial, sigma 5.3); at least 10 (4 sigma below). Without wrapping,
  // none.
  int straddling = 0;
  for (std::size_t i = 0; i < scene.simulation.particles.size(); ++i) {
    const double x = scene.simulation.particles.position[i].x();
    const double r = scene.simulation.particles.radius[i];
    straddling += (x < r || x > 0.006 - r) ? 1 : 0;
  }
  EXPECT_GE(straddling, 10);
  ASSERT_EQ(scene.notes.size(), 1U);
  EXPECT_EQ(scene.notes[0],
            "[[particles]] #1: the box spans the period along x and y, so the cloud wraps round it: grains "
            "straddle the period's ends");
  testing::run_stages(scene);
  const auto& sim = scene.simulation;
  ASSERT_LT(sim.unbalanced_force_ratio(), 1e-4) << "the bed must have come to rest";
  double weight = 0.0;
  for (double inv_m : sim.particles.inv_mass) weight += 9.81 / inv_m;
  EXPECT_NEAR(-sim.walls[0].force.z(), weight, 0.005 * weight);
  std::printf("periodic bed at rest at t = %.4f s: floor %.6g N against the weight %.6g N (%+.2e)\n",
              sim.time, -sim.walls[0].force.z(), weight, -sim.walls[0].force.z() / weight - 1.0);
}

}  // namespace
}  // namespace darcydem
