// Many-particle verification: the paper's column settling against the
// linear-spring closed form, energy conservation without damping, and
// bitwise reproducibility across thread counts.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>

#include "darcydem/generation/generators.hpp"
#include "dem_setup.hpp"
#include "scene_loading.hpp"

namespace darcydem {
namespace {

// examples/column_settling/column.toml: 50 discs, d = 1 mm, k_n = 1e5 N/m,
// 2650 kg/m^3, frictionless walls. In equilibrium the contact k-th from the
// top (the floor is the 50th) carries k disc weights, so the top centre
// sinks by (m g / k_n) (1 + ... + 50) = 1275 m g / k_n. The statics are
// exact for linear springs; the run stops at an unbalanced-force ratio of
// 1e-6, so the residual is far below the 0.5%, which we assert.
TEST(ColumnSettling, MatchesLinearSpringClosedForm) {
  auto scene = testing::load_scene<2>("examples/column_settling/column.toml");
  auto& sim = scene.simulation;
  ASSERT_EQ(sim.particles.size(), 50U);
  const double r = 5e-4;
  const double m = 2650.0 * std::numbers::pi * r * r * 1.0;
  const double g = 9.80665;
  const double expected = 1275.0 * m * g / 1e5;
  const double top0 = sim.particles.position[49].y();
  testing::run_stages(scene);
  const double settlement = top0 - sim.particles.position[49].y();
  EXPECT_NEAR(settlement, expected, 0.005 * expected);
  // The floor carries the whole weight (force balance), 0.5% as well.
  EXPECT_NEAR(-sim.walls[0].force.y(), 50.0 * m * g, 0.005 * 50.0 * m * g);
}

// Undamped, frictionless discs bouncing in a box under gravity: velocity
// Verlet conserves the total energy (kinetic + gravitational + elastic) up to
// an O((w dt)^2) error made each time a contact opens or closes mid-step.
// Measured worst relative error over 1e5 steps: 2.0e-5 at dt = 0.01 sqrt(m/k),
// 5.1e-6 at 0.005 (second order, as expected), so dt = 0.002 sqrt(m/k) keeps
// it under the 1e-6 the issue asks for, with margin.
TEST(EnergyConservation, UndampedBouncingDiscs) {
  ContactSpec spec;
  spec.normal_stiffness = 1e3;
  spec.restitution = 1.0;
  auto sim = testing::single_material<2>(2650.0, spec);
  const double r = 1e-3;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 4; ++j) {
      sim.particles.add(Vec<2>(2e-3 + 4e-3 * i + 1e-4 * j, 2e-3 + 3e-3 * j), r, 2650.0, 0, false,
                        Vec<2>(0.05 * (i - 2), 0.03 * (j - 1)));
    }
  }
  sim.walls.push_back(testing::plane<2>(Vec<2>(0, 0), Vec<2>(0, 1)));
  sim.walls.push_back(testing::plane<2>(Vec<2>(0, 0), Vec<2>(1, 0)));
  sim.walls.push_back(testing::plane<2>(Vec<2>(0.02, 0), Vec<2>(-1, 0)));
  sim.gravity = Vec<2>(0, -1.0);
  const double m = 2650.0 * std::numbers::pi * r * r;
  sim.time_step = 0.002 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  auto energy = [&] { return sim.kinetic_energy() + sim.gravitational_energy() + sim.elastic_energy(); };
  const double e0 = energy();
  const double scale = sim.kinetic_energy() + std::abs(sim.gravitational_energy());
  double worst = 0.0;
  std::size_t contacts_seen = 0;
  for (int s = 0; s < 100000; ++s) {
    sim.step();
    if (s % 100 == 0) {
      worst = std::max(worst, std::abs(energy() - e0) / scale);
      contacts_seen += sim.contact_count();
    }
  }
  EXPECT_GT(contacts_seen, 100U) << "the test must exercise contacts";
  EXPECT_LT(worst, 1e-6);
}

/// A dense 3D settling: 3000 spheres dropped into a box under strong gravity,
/// with friction and the given rolling resistance (0: the linear contacts go
/// through the vectorised batches, else pair by pair), two force blocks,
/// particles reordered at every list build.
Simulation<3> settling_packing(double rolling_friction) {
  ContactSpec spec;
  spec.normal_stiffness = 1e3;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  spec.rolling_friction = rolling_friction;
  auto sim = testing::single_material<3>(2650.0, spec);
  RadiusDistribution d;
  d.kind = RadiusDistribution::Kind::uniform;
  d.min = 4e-4;
  d.max = 6e-4;
  auto pk = random_packing<3>(Vec<3>(0, 0, 0), Vec<3>(0.015, 0.015, 0.045), 3000, d, 7, 1000);
  for (std::size_t k = 0; k < pk.position.size(); ++k) {
    sim.particles.add(pk.position[k], pk.radius[k], 2650.0, 0, false);
  }
  sim.walls.push_back(testing::plane<3>(Vec<3>(0, 0, 0), Vec<3>(0, 0, 1)));
  sim.walls.push_back(testing::plane<3>(Vec<3>(0, 0, 0), Vec<3>(1, 0, 0)));
  sim.walls.push_back(testing::plane<3>(Vec<3>(0.015, 0, 0), Vec<3>(-1, 0, 0)));
  sim.walls.push_back(testing::plane<3>(Vec<3>(0, 0, 0), Vec<3>(0, 1, 0)));
  sim.walls.push_back(testing::plane<3>(Vec<3>(0, 0.015, 0), Vec<3>(0, -1, 0)));
  sim.gravity = Vec<3>(0, 0, -500.0);  // strong, so the bed forms within the test
  sim.damping.local = 0.3;
  sim.time_step = 0.2 * sim.critical_time_step();
  sim.sort_threshold = 1000;
  return sim;
}

// The same dense settling gives bitwise identical states with 1, 2 and 3
// threads: each contact is computed once and each particle sums its
// contacts in a fixed order. The 3000 particles make two force blocks, so
// pairs across blocks are exercised: with two threads the second block
// waits for the first one's cross pairs, with one thread it does not, and
// with three one thread has no block. The particles are reordered along the
// cells at every list build (sort_threshold lowered for the test). Both
// contact paths: pair by pair (with rolling resistance) and batched; single
// steps and advance() (each step's pass 2 then also takes the next step's
// first kick and drift).
class Reproducibility : public ::testing::TestWithParam<double> {};

TEST_P(Reproducibility, BitwiseIdenticalForAnyThreadCount) {
  auto run = [&](int threads, bool single_steps) {
    omp_set_num_threads(threads);
    auto sim = settling_packing(GetParam());
    sim.prepare();
    for (int s = 0; s < 4000; s += 10) {
      if (single_steps) {
        for (int k = 0; k < 10; ++k) sim.step();
      } else {
        sim.advance(10);
      }
    }
    return sim;
  };
  const int saved = omp_get_max_threads();
  const auto a = run(1, true);
  const auto b = run(2, false);
  const auto c = run(3, false);
  omp_set_num_threads(saved);
  ASSERT_GT(a.contact_count(), 1000U) << "the packing must be in contact";
  ASSERT_GT(a.list_builds(), 2U) << "the particles must have been reordered";
  bool reordered = false;
  for (std::size_t i = 0; i < a.particles.size(); ++i) reordered = reordered || a.particles.id[i] != i;
  ASSERT_TRUE(reordered) << "the particles must have been reordered";
  ASSERT_GT(a.pair_list().cross_count(), 0U) << "pairs across force blocks must be exercised";
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(a.particles.position[i][k], b.particles.position[i][k]) << "particle " << i;
      ASSERT_EQ(b.particles.position[i][k], c.particles.position[i][k]) << "particle " << i;
      ASSERT_EQ(a.particles.angular_velocity[i][k], b.particles.angular_velocity[i][k]);
    }
  }
}

// advance(n) fuses each step's second half kick with the next step's first
// half kick and drift; per particle the operations are those of n calls of
// step(), so the states must agree bitwise (list rebuilds and reordering
// happen inside the run).
INSTANTIATE_TEST_SUITE_P(ContactPaths, Reproducibility, ::testing::Values(0.1, 0.0));

TEST(Advance, EqualsRepeatedSteps) {
  auto a = settling_packing(0.0);
  auto b = settling_packing(0.0);
  a.prepare();
  b.prepare();
  for (int s = 0; s < 1500; ++s) a.step();
  b.advance(1000);
  b.advance(500);
  ASSERT_EQ(a.steps, b.steps);
  ASSERT_GT(a.list_builds(), 2U) << "rebuilds must happen inside the run";
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(a.particles.position[i][k], b.particles.position[i][k]) << "particle " << i;
      ASSERT_EQ(a.particles.velocity[i][k], b.particles.velocity[i][k]) << "particle " << i;
      ASSERT_EQ(a.particles.angular_velocity[i][k], b.particles.angular_velocity[i][k]) << "particle " << i;
    }
  }
  for (std::size_t w = 0; w < a.walls.size(); ++w) ASSERT_EQ(a.walls[w].force, b.walls[w].force);
}

}  // namespace
}  // namespace darcydem
