// DEM cases left from issue 2: rolling resistance against its closed form,
// a wall moving at a prescribed velocity, and the random and CSV generators.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "darcydem/generation/generators.hpp"
#include "darcydem/simulation/runner.hpp"
#include "dem_setup.hpp"
#include "scene_loading.hpp"

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

// Along an axis marked to wrap, the box is a period: centres anywhere in
// [lo, hi), grains straddling its ends, none overlapping another's nearest
// image. Centres fall uniformly, so the share within a radius of either end
// of x is 2 r / L = 1/6 (binomial; 4 sigma). z keeps its walls.
TEST(Generators, RandomPackingWrapsRoundAPeriod) {
  RadiusDistribution d;
  d.value = 0.5e-3;
  const double L = 6e-3;
  const Vec<3> lo(0, 0, 0), hi(L, L, 0.02);
  const std::int64_t n = 360;  // solid fraction 0.262 of the box
  const auto pk = random_packing<3>(lo, hi, n, d, 3, 100000, {true, true, false});
  ASSERT_EQ(pk.position.size(), static_cast<std::size_t>(n));
  int near_end = 0;
  for (std::size_t i = 0; i < pk.position.size(); ++i) {
    const auto& x = pk.position[i];
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(x[k], 0.0);
      EXPECT_LT(x[k], L);
    }
    EXPECT_GE(x.z() - 0.5e-3, -1e-15);
    EXPECT_LE(x.z() + 0.5e-3, 0.02 + 1e-15);
    near_end += (x.x() < 0.5e-3 || x.x() > L - 0.5e-3) ? 1 : 0;
    for (std::size_t j = 0; j < i; ++j) {
      Vec<3> gap = pk.position[j] - x;
      for (int k = 0; k < 2; ++k) gap[k] -= L * std::round(gap[k] / L);
      EXPECT_GE(gap.norm(), 1e-3 - 1e-15) << i << " and " << j;
    }
  }
  const double mean = n / 6.0;
  EXPECT_NEAR(near_end, mean, 4.0 * std::sqrt(mean * 5.0 / 6.0));
}

// The dense lattices: nearest centres exactly a spacing apart, and a
// particle away from the box's edges has the kissing number of its
// arrangement as neighbours at that distance (6 hexagonal, 12 fcc), none
// closer; every particle inside the box; the 2D count worked out by hand.
template <int D>
void dense_lattice(double box, int kissing, std::size_t expected_count) {
  const double a = 1e-3;
  const double r = 0.5 * a;
  const auto pk = dense_lattice_packing<D>(Vec<D>::Zero(), Vec<D>::Constant(box), a, r);
  if (expected_count > 0) {
    EXPECT_EQ(pk.position.size(), expected_count);
  }
  ASSERT_GT(pk.position.size(), 50U);
  // Round-off of lattice coordinates of order 1e-2 m: 1e-12 of a spacing.
  const double tol = 1e-12 * a;
  int interior = 0;
  for (std::size_t i = 0; i < pk.position.size(); ++i) {
    const auto& x = pk.position[i];
    bool inner = true;
    for (int k = 0; k < D; ++k) {
      EXPECT_GE(x[k] - r, -tol);
      EXPECT_LE(x[k] + r, box + tol);
      inner = inner && x[k] > 1.5 * a && x[k] < box - 1.5 * a;
    }
    int touching = 0;
    for (std::size_t j = 0; j < pk.position.size(); ++j) {
      if (j == i) continue;
      const double dist = (pk.position[j] - x).norm();
      EXPECT_GE(dist, a - tol);
      touching += dist < a + tol ? 1 : 0;
    }
    if (inner) {
      EXPECT_EQ(touching, kissing) << "particle " << i;
      ++interior;
    }
    // In order of height.
    if (i > 0) {
      EXPECT_LE(pk.position[i - 1][D - 1], x[D - 1]);
    }
  }
  EXPECT_GT(interior, 10);
}

TEST(Generators, HexagonalLatticeIsDense) {
  // Box 10 a: 11 rows (pitch a sqrt(3)/2 over 9 a), 10 particles in the 6
  // unshifted rows and 9 in the 5 shifted ones: 105.
  dense_lattice<2>(10e-3, 6, 105);
}
TEST(Generators, FccLatticeIsDense) { dense_lattice<3>(6e-3, 12, 0); }

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

// A csv packing may say each particle's clump (a `clump` column, as
// particles_final.csv has with clumps): read as written; a clump whose rows
// are not consecutive, or a clump that is not an integer >= -1, is refused
// with the file and line.
TEST(Generators, CsvClumpColumn) {
  const auto path =
      std::filesystem::temp_directory_path() / ("darcydem_clumps_" + std::to_string(getpid()) + ".csv");
  auto write = [&](const std::string& text) {
    std::ofstream f(path);
    f << text;
  };
  write("# a comment\nx,y,radius,clump\n0,0,1,0\n2,0,1,0\n5,0,1,-1\n7,0,1,1\n");
  const auto pk = read_packing_csv<2>(path.string());
  EXPECT_EQ(pk.clump, (std::vector<std::int64_t>{0, 0, -1, 1}));
  auto refused = [&](const std::string& text, const std::string& part) {
    write(text);
    try {
      read_packing_csv<2>(path.string());
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(part), std::string::npos) << msg;
      EXPECT_NE(msg.find(path.string()), std::string::npos) << msg;
    }
  };
  refused("x,y,radius,clump\n0,0,1,0\n5,0,1,1\n2,0,1,0\n", ":4: clump 0 began on an earlier row");
  refused("x,y,radius,clump\n0,0,1,0.5\n", ":2: the clump column must be an integer >= 0");
  refused("x,y,radius,clump\n0,0,1,-2\n", ":2: the clump column must be an integer >= 0");
  refused("x,y,radius,clump\n0,0,1\n", ":2: expected 4 comma-separated numbers, got 3");
  refused("x,y,radius,group\n0,0,1,0\n", "the header must be 'x,y,radius' or 'x,y,radius,clump'");
  std::filesystem::remove(path);
}

// A run ends by writing particles_final.csv, which the csv generator reads
// back: the settled column (stopped at an unbalanced-force ratio of 1e-6)
// reloaded into a new scene carries its weight from the first step, so a
// bed settled once can start other runs.
TEST(Generators, CsvWrittenInCreationOrder) {
  // Particles reordered in memory (as list builds do) are written by id.
  ParticleData<3> p;
  for (int i = 0; i < 5; ++i) p.add(Vec<3>(0.1 * i, 1.0 / 3.0, -i * 1e-7), 1e-3 * (i + 1), 2650.0, 0, false);
  p.permute({3, 0, 4, 1, 2});
  const auto path =
      std::filesystem::temp_directory_path() / ("darcydem_written_" + std::to_string(getpid()) + ".csv");
  write_packing_csv<3>(path.string(), p, "two\nlines");
  const auto pk = read_packing_csv<3>(path.string());
  ASSERT_EQ(pk.position.size(), 5U);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(pk.position[i], Vec<3>(0.1 * i, 1.0 / 3.0, -i * 1e-7));
    EXPECT_EQ(pk.radius[i], 1e-3 * (i + 1));
  }
  std::filesystem::remove(path);
}

TEST(Generators, FinalParticlesStartANewSceneSettled) {
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/column_settling/column.toml";
  const auto dir = std::filesystem::temp_directory_path() / ("darcydem_final_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  const std::string text = testing::file_contents(scene);
  Scene<2> first = testing::load_scene_file<2>(scene);
  RunOptions options;
  options.out_dir = (dir / "settle").string();
  ASSERT_FALSE(run_scene<2>(first, options).interrupted);
  const auto& p = first.simulation.particles;
  const std::string csv = (dir / "settle" / "particles_final.csv").string();
  const auto pk = read_packing_csv<2>(csv);
  ASSERT_EQ(pk.position.size(), p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    // 17 significant digits read back to the same double.
    EXPECT_EQ(pk.position[p.id[i]], p.position[i]);
    EXPECT_EQ(pk.radius[p.id[i]], p.radius[i]);
  }

  // The same scene with the column taken from the file.
  const auto from = text.find("[[particles]]");
  const auto to = text.find("[output]");
  ASSERT_TRUE(from != std::string::npos && to != std::string::npos && from < to);
  // The tolerance the file's header asks for.
  const std::string header = testing::file_contents(csv);
  const auto tol_at = header.find("initial_overlap_tolerance >= ");
  ASSERT_NE(tol_at, std::string::npos) << header.substr(0, 400);
  const double tolerance = std::stod(header.substr(tol_at + 29));
  EXPECT_GT(tolerance, 0.0);
  std::string reloaded_text = text.substr(0, from) +
                              "[[particles]]\ngenerator = \"csv\"\nmaterial = \"grain\"\nfile = \"" + csv +
                              "\"\n\n" + text.substr(to);
  const auto sim_at = reloaded_text.find("[simulation]\n");
  ASSERT_NE(sim_at, std::string::npos);
  reloaded_text.insert(sim_at + 13, fmt::format("initial_overlap_tolerance = {}\n", tolerance));
  const std::string reloaded_file = (dir / "reloaded.toml").string();
  std::ofstream(reloaded_file) << reloaded_text;
  Scene<2> second = testing::load_scene_file<2>(reloaded_file);
  auto& sim = second.simulation;
  sim.gravity = Vec<2>(0.0, -9.80665);
  sim.prepare();
  double weight = 0.0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) weight += 9.80665 / sim.particles.inv_mass[i];
  // Settled to an unbalanced-force ratio below 1e-6, the floor carried the
  // weight to about 50 x 1e-6 of it (50 grains, each out of balance by at
  // most that fraction of the column's contact forces); allow 1e-4.
  EXPECT_NEAR(sim.walls[0].force.y(), -weight, 1e-4 * weight);
  const double top_before = sim.particles.position[sim.particles.index_of(49)].y();
  for (int s = 0; s < 2000; ++s) sim.step();
  const double top_after = sim.particles.position[sim.particles.index_of(49)].y();
  // It does not settle again. The first run settled the column by
  // 1275 m g / k_n = 0.26 mm (the top's fall from 49.5 mm); after 2000 steps
  // the reloaded top has moved by less than 1e-5 of that (measured: 2e-7;
  // the first run stopped with its forces balanced to 1e-6).
  const double settlement = 49.5e-3 - first.simulation.particles.position[p.index_of(49)].y();
  EXPECT_GT(settlement, 2e-4);
  EXPECT_LT(std::abs(top_after - top_before), 1e-5 * settlement) << top_after - top_before;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace darcydem
