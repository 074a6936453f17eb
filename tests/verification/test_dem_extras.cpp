// DEM cases left from issue 2: rolling resistance against its closed form,
// a wall moving at a prescribed velocity, and the random and CSV generators.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "darcydem/generation/generators.hpp"
#include "dem_setup.hpp"

namespace darcydem {
namespace {

using testing::particle_on_floor;
using testing::plane;
using testing::single_material;

// A particle rolling on a floor with rolling friction mu_r: the resisting
// moment mu_r r F_n (F_n = m g) decelerates it at a = mu_r g / (1 + I/(m r^2)),
// i.e. 5/7 mu_r g for spheres and 2/3 mu_r g for discs, while it keeps
// rolling without slip. Measured over the middle of the roll (away from the
// start, where the rolling spring loads up, and from the stop); 1 %.
template <int D>
void rolling_deceleration() {
  const double r = 1e-3;
  const double g = 9.81;
  const double v0 = 0.05;
  ContactSpec spec;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  spec.rolling_friction = 0.1;
  auto sim = particle_on_floor<D>(spec, r, v0, g);
  // Rolling without slip from the start: omega = v / r about the axis that
  // turns +x motion on a floor normal to the last axis.
  if constexpr (D == 2) {
    sim.particles.angular_velocity[0][0] = -v0 / r;
  } else {
    sim.particles.angular_velocity[0][1] = v0 / r;
  }
  sim.prepare();
  const double a = spec.rolling_friction * g / (1.0 + inertia_factor<D>);
  const double stop = v0 / a;
  while (sim.time < 0.2 * stop) sim.step();
  const double t1 = sim.time;
  const double v1 = sim.particles.velocity[0][0];
  while (sim.time < 0.7 * stop) sim.step();
  const double measured = (v1 - sim.particles.velocity[0][0]) / (sim.time - t1);
  EXPECT_NEAR(measured, a, 0.01 * a);
  // Still rolling, not sliding: contact-point velocity small against v.
  const double w = D == 2 ? -sim.particles.angular_velocity[0][0] : sim.particles.angular_velocity[0][1];
  EXPECT_NEAR(w * r, sim.particles.velocity[0][0], 0.01 * sim.particles.velocity[0][0]);
}

TEST(RollingResistance, SphereDeceleratesAtFiveSeventhsMuRG) { rolling_deceleration<3>(); }
TEST(RollingResistance, DiscDeceleratesAtTwoThirdsMuRG) { rolling_deceleration<2>(); }

// A floor rising at a prescribed speed carries a disc resting on it under
// gravity: the wall is where v t puts it (exactly), the disc rises with it,
// and the contact carries m g once the start-up transient has died (0.5 %).
TEST(VelocityWall, LiftsARestingParticle) {
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  spec.restitution = 0.3;
  auto sim = single_material<2>(2650.0, spec);
  const double r = 5e-4;
  const double m = 2650.0 * particle_volume<2>(r);
  const double g = 9.81;
  sim.particles.add(Vec<2>(0, r - m * g / spec.normal_stiffness), r, 2650.0, 0, false);
  auto floor = plane<2>(Vec<2>(0, 0), Vec<2>(0, 1), "floor");
  floor.motion = WallMotion::velocity;
  floor.velocity = Vec<2>(0.0, 0.01);
  sim.walls.push_back(floor);
  sim.gravity = Vec<2>(0, -g);
  sim.damping.local = 0.7;
  sim.time_step = 0.1 * sim.critical_time_step();
  sim.prepare();
  while (sim.time < 0.05) sim.step();
  EXPECT_NEAR(sim.walls[0].point.y(), 0.01 * sim.time, 1e-12);
  EXPECT_NEAR(sim.particles.velocity[0].y(), 0.01, 0.005 * 0.01);
  EXPECT_NEAR(sim.walls[0].load(), m * g, 0.005 * m * g);
}

TEST(Generators, RandomPackingIsInsideAndDoesNotOverlap) {
  RadiusDistribution d;
  d.kind = RadiusDistribution::Kind::uniform;
  d.min = 0.4e-3;
  d.max = 0.6e-3;
  const Vec<3> lo(0, 0, 0), hi(0.01, 0.01, 0.01);
  const auto pk = random_packing<3>(lo, hi, 300, d, 5, 1000);
  ASSERT_EQ(pk.position.size(), 300U);
  for (std::size_t i = 0; i < pk.position.size(); ++i) {
    const double r = pk.radius[i];
    EXPECT_GE(r, d.min);
    EXPECT_LE(r, d.max);
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(pk.position[i][k] - r, lo[k] - 1e-15);
      EXPECT_LE(pk.position[i][k] + r, hi[k] + 1e-15);
    }
    for (std::size_t j = 0; j < i; ++j) {
      EXPECT_GE((pk.position[i] - pk.position[j]).norm(), r + pk.radius[j] - 1e-15);
    }
  }
  // Same seed, same packing; another seed, another.
  const auto again = random_packing<3>(lo, hi, 300, d, 5, 1000);
  EXPECT_EQ(again.position[123], pk.position[123]);
  const auto other = random_packing<3>(lo, hi, 300, d, 6, 1000);
  EXPECT_NE(other.position[123], pk.position[123]);
}

TEST(Generators, RandomPackingFollowsTheSizeTable) {
  // 4000 draws with fractions 0.3 / 0.7: the count of small ones is binomial,
  // sigma = sqrt(4000 * 0.3 * 0.7) = 29; allow 4 sigma.
  RadiusDistribution d;
  d.kind = RadiusDistribution::Kind::table;
  d.radii = {0.1e-3, 0.2e-3};
  d.fractions = {0.3, 0.7};
  const auto pk = random_packing<2>(Vec<2>(0, 0), Vec<2>(0.05, 0.05), 4000, d, 9, 1000);
  int small = 0;
  for (double r : pk.radius) small += r == 0.1e-3 ? 1 : 0;
  EXPECT_NEAR(small, 1200, 4 * 29);
}

TEST(Generators, RandomPackingThatCannotFitSaysSo) {
  RadiusDistribution d;
  d.value = 1e-3;
  EXPECT_THROW(random_packing<2>(Vec<2>(0, 0), Vec<2>(0.01, 0.01), 1000, d, 1, 50), std::runtime_error);
}

TEST(Generators, CsvRoundTripAndBadRow) {
  const auto path =
      std::filesystem::temp_directory_path() / ("darcydem_packing_" + std::to_string(getpid()) + ".csv");
  {
    std::ofstream f(path);
    f << "x,y,z,radius\n0.001,0.002,0.003,0.0005\n-1e-3,0,2.5e-3,4e-4\n";
  }
  const auto pk = read_packing_csv<3>(path.string());
  ASSERT_EQ(pk.position.size(), 2U);
  EXPECT_EQ(pk.position[1], Vec<3>(-1e-3, 0.0, 2.5e-3));
  EXPECT_EQ(pk.radius[0], 0.0005);
  {
    std::ofstream f(path);
    f << "x,y,z,radius\n0.001,0.002,0.003,0.0005\n0.001,oops,0.003,0.0005\n";
  }
  try {
    read_packing_csv<3>(path.string());
    ADD_FAILURE() << "a bad row was accepted";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find(":3"), std::string::npos) << msg;  // the line
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace darcydem
