// Inlets of clumps ([[inlet]] with `clump`, PFC's clump generation in a
// cycle loop): each clump placed whole in the box where none of its members
// touches a particle or a wall, its mass that of its members' union (checked
// against the union's volume by inclusion-exclusion, worked by hand), its
// shape rigid, its fall velocity Verlet's parabola from where and when it
// was placed, its kinetic energy in the budget; a bed of them rests on its
// walls with its whole weight.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "darcydem/generation/inlet.hpp"
#include "darcydem/output/probes.hpp"
#include "darcydem/simulation/runner.hpp"
#include "rain_into_water.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
using darcydem::testing::read_probes;
using darcydem::testing::scene_from_text;
using darcydem::testing::temp_dir;

namespace {

constexpr double g = 9.81;

/// The volume of the lens two spheres of radii R and r, d apart, share
/// (R - r < d < R + r).
double lens_volume(double R, double r, double d) {
  const double h = R + r - d;
  return std::numbers::pi * h * h *
         (d * d + 2.0 * d * r - 3.0 * r * r + 2.0 * d * R + 6.0 * r * R - 3.0 * R * R) / (12.0 * d);
}

// The pour example's trimer: three spheres in a bent row, the middle one
// overlapping each end one, the end ones apart (2.72 > 1.6).
const char* trimer_scene = R"(
[simulation]
dimension = 3
time_step = "auto"
safety_factor = 0.2

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e3
restitution = 0.3
friction = 0.5

[[clump_template]]
name = "trimer"
spheres = [[-1.4, 0.0, 0.0, 0.8], [0.0, 0.0, 0.0, 1.0], [1.2, 0.8, 0.0, 0.8]]

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[inlet]]
name = "rain"
material = "sand"
clump = "trimer"
min = [-0.01, -0.01, 0.02]
max = [0.01, 0.01, 0.04]
radius_min = 0.0008
radius_max = 0.0011
velocity = [0.05, 0.0, 0.0]
rate = 800.0
count = 24
interval = 0.01
seed = 5

[[stage]]
duration = 0.2
gravity = [0.0, 0.0, -9.81]
)";

}  // namespace

TEST(InletClumps, AddsClumpsWhereTheyFitAndTheyFallFreelyAsRigidBodies) {
  const std::string dir = temp_dir("inlet_clumps");
  Scene<3> scene = scene_from_text<3>(dir, "rain.toml", trimer_scene);
  auto& sim = scene.simulation;
  auto& rain = scene.inlets.at(0);
  ASSERT_TRUE(rain.clump.has_value());
  EXPECT_EQ(sim.particles.size(), 0U);
  sim.gravity = Vec<3>(0.0, 0.0, -g);
  sim.track_energy = true;
  sim.prepare();
  // The template's union by inclusion-exclusion: the end spheres are apart,
  // so only the two lenses with the middle one are counted twice.
  const std::vector<Vec<3>> c = {Vec<3>(-1.4, 0.0, 0.0), Vec<3>(0.0, 0.0, 0.0), Vec<3>(1.2, 0.8, 0.0)};
  const std::vector<double> rad = {0.8, 1.0, 0.8};
  auto ball = [](double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; };
  const double union_volume = ball(0.8) + ball(1.0) + ball(0.8) -
                              lens_volume(1.0, 0.8, (c[1] - c[0]).norm()) -
                              lens_volume(1.0, 0.8, (c[2] - c[1]).norm());
  struct Placed {
    std::size_t clump;
    Vec<3> x0;
    double t0;
  };
  std::vector<Placed> placed;
  double brought = 0.0;
  double mass = 0.0;
  for (int event = 0; event < 4; ++event) {
    const std::size_t before = sim.clumps.size();
    const double t0 = sim.time;
    const auto result = insert_due(rain, sim);
    // 8 due each time: 8, 8, 8, then none (the count's limit).
    EXPECT_EQ(result.added, event < 3 ? 8U : 0U) << "insertion " << event;
    EXPECT_FALSE(result.short_of_room);
    ASSERT_EQ(sim.clumps.size(), before + result.added);
    sim.clumps.refresh(sim.particles);
    const auto& p = sim.particles;
    for (std::size_t k = before; k < sim.clumps.size(); ++k) {
      const auto& cl = sim.clumps;
      ASSERT_EQ(cl.first[k + 1] - cl.first[k], 3U);
      const std::size_t m0 = cl.member_index[cl.first[k]];
      // The members are the template scaled by one factor (their radii)
      // and moved rigidly (their distances), to round-off.
      const double scale = p.radius[m0] / rad[0];
      // The sphere about its centre of mass that holds it: a size the
      // inlet's distribution draws.
      double reach = 0.0;
      for (std::uint32_t a = cl.first[k]; a < cl.first[k + 1]; ++a) {
        const std::size_t i = cl.member_index[a];
        reach = std::max(reach, (p.position[i] - cl.position[k]).norm() + p.radius[i]);
      }
      EXPECT_GE(reach, 0.0008 * (1.0 - 1e-12));
      EXPECT_LE(reach, 0.0011 * (1.0 + 1e-12));
      for (std::size_t a = 0; a < 3; ++a) {
        const std::size_t i = cl.member_index[cl.first[k] + a];
        EXPECT_NEAR(p.radius[i], scale * rad[a], 1e-15);
        for (std::size_t b = 0; b < a; ++b) {
          const std::size_t j = cl.member_index[cl.first[k] + b];
          EXPECT_NEAR((p.position[i] - p.position[j]).norm(), scale * (c[a] - c[b]).norm(), 1e-15);
        }
        // Whole in the box (the sphere that holds the clump is), touching
        // no particle of another clump and not the floor.
        for (int d = 0; d < 3; ++d) {
          EXPECT_GE(p.position[i][d] - p.radius[i], rain.lower[d] - 1e-15);
          EXPECT_LE(p.position[i][d] + p.radius[i], rain.upper[d] + 1e-15);
        }
        for (std::size_t j = 0; j < p.size(); ++j) {
          if (cl.clump_of[j] == static_cast<std::int32_t>(k)) continue;
          EXPECT_GE((p.position[j] - p.position[i]).norm(), p.radius[i] + p.radius[j]) << i << " and " << j;
        }
        EXPECT_EQ(p.velocity[i], Vec<3>(0.05, 0.0, 0.0));
      }
      // Its mass: the union's volume at its scale, 1e-12 (the 3D union's
      // accuracy, ball_union.hpp). Proportional shares of the spheres' own
      // volumes, lenses counted twice, would be 11 % heavier.
      const double expected = 2650.0 * union_volume * scale * scale * scale;
      EXPECT_NEAR(cl.mass[k], expected, 1e-12 * expected);
      // Its force is its weight with no moment: a first evaluation's.
      EXPECT_NEAR(cl.force[k][2], -cl.mass[k] * g, 1e-14 * cl.mass[k] * g);
      double weight = 0.0;
      for (std::uint32_t a = cl.first[k]; a < cl.first[k + 1]; ++a) weight += p.force[cl.member_index[a]][2];
      EXPECT_NEAR(weight, -cl.mass[k] * g, 1e-14 * cl.mass[k] * g);
      // The budget starts at the first step: the first insertion's clumps
      // are in its starting kinetic energy, the later ones brought in.
      if (event > 0) brought += 0.5 * cl.mass[k] * 0.05 * 0.05;
      mass += cl.mass[k];
      placed.push_back({k, cl.position[k], t0});
    }
    sim.advance(static_cast<std::uint64_t>(std::round(0.01 / sim.time_step)));
  }
  EXPECT_EQ(rain.inserted, 24U);
  EXPECT_TRUE(rain.exhausted());
  EXPECT_EQ(sim.inserted_count, 72U) << "three members each";
  EXPECT_EQ(sim.particles.size(), 72U);
  EXPECT_NEAR(rain.inserted_mass, mass, 1e-14 * mass);
  EXPECT_NEAR(sim.inserted_mass, mass, 1e-14 * mass);
  EXPECT_NEAR(sim.energy.inserted_kinetic, brought, 1e-14 * brought);
  // Until 40 ms every clump falls freely: the box's bottom is 20 mm up (64
  // ms of fall), and placed apart, moving alike, no two meet. Velocity
  // Verlet under a constant force is exact: x = x0 + v0 t - g t^2 / 2 to
  // round-off, 1e-12 m; the weight puts no moment on a clump, so none
  // spins (1e-12 rad/s). A clump given no force at its placing would lag by
  // g dt / 2 x t.
  for (const auto& pl : placed) {
    const double t = sim.time - pl.t0;
    const Vec<3>& x = sim.clumps.position[pl.clump];
    EXPECT_NEAR(x[0], pl.x0[0] + 0.05 * t, 1e-12) << "clump " << pl.clump;
    EXPECT_NEAR(x[1], pl.x0[1], 1e-12) << "clump " << pl.clump;
    EXPECT_NEAR(x[2], pl.x0[2] - 0.5 * g * t * t, 1e-12) << "clump " << pl.clump;
    EXPECT_LT(sim.clumps.angular_velocity[pl.clump].norm(), 1e-12) << "clump " << pl.clump;
  }
  // Turned at random: the row's direction (end sphere to end sphere) of
  // the 24 clumps averages to a short vector (about 1/sqrt(24) = 0.2 for
  // uniform directions; 1 if all stood alike).
  Vec<3> mean = Vec<3>::Zero();
  sim.clumps.refresh(sim.particles);
  for (std::size_t k = 0; k < sim.clumps.size(); ++k) {
    const auto& cl = sim.clumps;
    const Vec<3> row = sim.particles.position[cl.member_index[cl.first[k] + 2]] -
                       sim.particles.position[cl.member_index[cl.first[k]]];
    mean += row.normalized() / 24.0;
  }
  EXPECT_LT(mean.norm(), 0.6);
  // They land and tumble on the floor; the budget closes over it all (the
  // clumps' kinetic energy brought in counted) to round-off of its sums,
  // 1e-10 of gravity's work as for a clump dropped alone.
  while (sim.time < 0.15) sim.advance(200);
  EXPECT_GT(sim.contact_dissipation(), 0.1 * sim.energy.gravity_work) << "they hit the floor";
  const double scale = std::abs(sim.energy.gravity_work) + 0.5 * mass * 0.05 * 0.05;
  std::printf("inlet clumps: unaccounted %.3g of gravity's work and the kinetic energy brought in\n",
              sim.unaccounted_energy() / scale);
  EXPECT_LT(std::abs(sim.unaccounted_energy()), 1e-10 * scale);
  std::filesystem::remove_all(dir);
}

namespace {

// examples/dem_cases/clump_pluviation.toml: 0.8 kg/m of 2D "peanuts" (two
// overlapping discs) rained into a box, each turned at random or, here,
// standing as the template gives it.
std::string clump_pluviation(const std::string& orientation) {
  return darcydem::testing::scene_variant(
      "examples/dem_cases/clump_pluviation.toml",
      {{"orientation = \"random\"", "orientation = \"" + orientation + "\""}});
}

}  // namespace

TEST(InletClumps, AlignedClumpsStandAsTheirTemplate2D) {
  const std::string dir = temp_dir("inlet_clumps_aligned");
  Scene<2> scene = scene_from_text<2>(dir, "rain.toml", clump_pluviation("aligned"));
  auto& sim = scene.simulation;
  auto& hopper = scene.inlets.at(0);
  sim.prepare();
  const auto result = insert_due(hopper, sim);
  ASSERT_GT(result.added, 5U) << "30 g/m due: about 10 peanuts";
  sim.clumps.refresh(sim.particles);
  const auto& p = sim.particles;
  for (std::size_t k = 0; k < sim.clumps.size(); ++k) {
    const std::size_t a = sim.clumps.member_index[sim.clumps.first[k]];
    const std::size_t b = sim.clumps.member_index[sim.clumps.first[k] + 1];
    // Along x, as the template has it, to round-off; a radius 0.8 / 1.4 of
    // the holding circle's (the peanut's members reach 0.6 + 0.8).
    const Vec<2> row = p.position[b] - p.position[a];
    EXPECT_NEAR(row[1], 0.0, 1e-15) << "clump " << k;
    EXPECT_GT(row[0], 0.0) << "clump " << k;
    const double size = 0.5 * row[0] / 0.6 * 1.4;
    EXPECT_NEAR(p.radius[a], size * 0.8 / 1.4, 1e-15);
    EXPECT_GE(size, 0.0008 * (1.0 - 1e-12));
    EXPECT_LE(size, 0.0012 * (1.0 + 1e-12));
  }
  std::filesystem::remove_all(dir);
}

TEST(InletClumps, PluviatedClumpsRestOnTheWallsWithTheirWholeWeight2D) {
  const std::string dir = temp_dir("inlet_clumps_pluviation");
  Scene<2> scene = scene_from_text<2>(dir, "rain.toml", clump_pluviation("random"));
  RunOptions options;
  options.out_dir = dir;
  const RunSummary summary = run_scene<2>(scene, options);
  ASSERT_FALSE(summary.interrupted);
  ASSERT_EQ(summary.stages_completed.size(), 2U);
  const auto& sim = scene.simulation;
  const auto& hopper = scene.inlets.at(0);
  // Each peanut's mass: its union's area (two discs of radius 0.8 whose
  // centres are 1.2 apart, less their lens, in the template's unit) at its
  // scale; the largest, of holding radius 1.2 mm, bounds the overshoot.
  const double d = 1.2;
  const double R = 0.8;
  const double lens = 2.0 * R * R * std::acos(d / (2.0 * R)) - 0.5 * d * std::sqrt(4.0 * R * R - d * d);
  const double area = 2.0 * std::numbers::pi * R * R - lens;
  const double heaviest = 2650.0 * area * std::pow(0.0012 / 1.4, 2);
  EXPECT_GE(hopper.inserted_mass, 0.8);
  EXPECT_LT(hopper.inserted_mass, 0.8 + heaviest);
  EXPECT_EQ(sim.clumps.size(), hopper.inserted);
  EXPECT_EQ(sim.particles.size(), 2 * hopper.inserted);
  EXPECT_EQ(hopper.short_events, 0U);
  double mass = 0.0;
  for (std::size_t k = 0; k < sim.clumps.size(); ++k) {
    // Each clump's mass from its members' radius (size = 1.4 / 0.8 of it).
    const double size = sim.particles.radius[sim.clumps.member_index[sim.clumps.first[k]]] * 1.4 / 0.8;
    const double expected = 2650.0 * area * std::pow(size / 1.4, 2);
    EXPECT_NEAR(sim.clumps.mass[k], expected, 1e-13 * expected) << "clump " << k;
    mass += sim.clumps.mass[k];
  }
  EXPECT_NEAR(mass, hopper.inserted_mass, 1e-12 * mass);
  // Statics, as for the discs: at rest the floor and the side walls carry
  // the whole weight rained, within 1e-3 of it (a quarter of one peanut's
  // share, about 1/150: one lost, counted twice or still falling fails it;
  // measured 1.9e-4).
  const double weight = hopper.inserted_mass * 9.80665;
  double load = 0.0;
  for (const auto& w : sim.walls) load += w.force[1];
  std::printf("clump pluviation: %llu peanuts, weight %.6g N/m, carried %.6g N/m (%.2e)\n",
              static_cast<unsigned long long>(hopper.inserted), weight, -load, -load / weight - 1.0);
  EXPECT_NEAR(-load, weight, 1e-3 * weight);
  for (std::size_t k = 0; k < sim.clumps.size(); ++k) {
    const auto& x = sim.clumps.position[k];
    EXPECT_TRUE(x[0] > 0.0 && x[0] < 0.06 && x[1] > 0.0 && x[1] < 0.09) << "clump " << k;
  }
  const std::string json = darcydem::testing::file_contents(dir + "/run.json");
  EXPECT_NE(
      json.find(fmt::format("\"clumps\": {}, \"particles\": {},", hopper.inserted, 2 * hopper.inserted)),
      std::string::npos)
      << json;
  std::filesystem::remove_all(dir);
}

// Inlet.GrainsRainedIntoWaterKeepItsVolumeBalance with peanuts: 20 clumps
// of two overlapping discs (holding circles of 0.7 mm) rained into the
// water over the bed. Each member brings its share of the union's area
// into the grid's solid, so the pore water loses the union's area per
// peanut, the lens counted once.
TEST(InletClumps, ClumpsRainedIntoWaterKeepItsVolumeBalance) {
  const std::string dir = temp_dir("inlet_clumps_water");
  const std::string text = darcydem::testing::text_variant(
      darcydem::testing::kRainIntoWater,
      {{"[[inlet]]",
        "[[clump_template]]\nname = \"peanut\"\ncircles = [[-0.6, 0.0, 0.8], [0.6, 0.0, 0.8]]\n\n"
        "[[inlet]]\nclump = \"peanut\""},
       {"radius = 0.00049\nvelocity", "radius = 0.0007\nvelocity"},
       {"count = 40", "count = 20"}});
  Scene<2> scene = scene_from_text<2>(dir, "water.toml", text);
  const Vec<2> lo(0.0, 0.0);
  const Vec<2> hi(0.01, 0.01);
  auto solid_in_grid = [&] { return (1.0 - box_porosity<2>(scene.simulation.particles, lo, hi)) * 1e-4; };
  const double solid_before = solid_in_grid();
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<2>(scene, options).interrupted);
  const auto& sim = scene.simulation;
  ASSERT_EQ(sim.clumps.size(), 20U);
  for (std::size_t k = 0; k < sim.clumps.size(); ++k)
    EXPECT_LT(sim.clumps.position[k][1], 0.01 - 0.0007) << "clump " << k << " wholly in the water";
  // The water's balance holds to round-off of the gross flow, and the pore
  // change is minus the solid that came into the grid (exact overlaps, the
  // members' shares), as for discs.
  const auto& b = scene.fluid->total_balance();
  EXPECT_LT(std::abs(b.imbalance()), 1e-9 * b.gross);
  const double came_in = solid_in_grid() - solid_before;
  EXPECT_NEAR(-b.pore_change, came_in, 1e-9 * came_in);
  // That is 20 unions: two discs of 0.4 mm, 0.6 mm apart, less their lens
  // (by its closed form), within 1e-3, what the bed pressed out of the grid
  // (1.2e-4 with discs). Two whole discs each, the lens counted twice, would
  // be 7.8 % more.
  const double R = 0.8 / 1.4 * 0.0007;
  const double d = 1.2 / 1.4 * 0.0007;
  const double lens = 2.0 * R * R * std::acos(d / (2.0 * R)) - 0.5 * d * std::sqrt(4.0 * R * R - d * d);
  const double peanut = 2.0 * std::numbers::pi * R * R - lens;
  std::printf("clumps rained into water: %.6g m^2 came in, 20 peanuts %.6g m^2 (%.2e)\n", came_in,
              20.0 * peanut, came_in / (20.0 * peanut) - 1.0);
  EXPECT_NEAR(came_in, 20.0 * peanut, 1e-3 * came_in);
  std::filesystem::remove_all(dir);
}
