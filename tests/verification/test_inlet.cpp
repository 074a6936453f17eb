// Inlets ([[inlet]], LIGGGHTS's fix insert/rate/region, YADE's BoxFactory):
// grains added to a running simulation at a steady rate. Checked against
// the schedule the rate makes (counted by hand), against free fall (velocity
// Verlet is exact under a constant force, so a new grain's path is known in
// closed form from where and when it was placed), against the statics of
// the bed it builds (the walls carry the weight of exactly what was added),
// and against the same bed run without the inlet: adding grains must not
// touch the others' contact histories.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "darcydem/generation/inlet.hpp"
#include "darcydem/output/probes.hpp"
#include "darcydem/simulation/runner.hpp"
#include "frictional_bed.hpp"
#include "rain_into_water.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
using darcydem::testing::read_probes;
using darcydem::testing::scene_from_text;
using darcydem::testing::temp_dir;

namespace {

constexpr double g = 9.80665;

// Two discs at the start: one 1 mm above the domain's floor (it falls out
// within 15 ms), one resting on a shelf. The inlet adds 400 grains/s, 4 at
// each insertion 10 ms apart, at most 10, in a box high above the shelf,
// each thrown sideways at 0.2 m/s.
const char* schedule_scene = R"(
[simulation]
dimension = 2
time_step = 1e-4
skin = 2e-4

[domain]
min = [-0.1, 0.0]
max = [0.1, 0.5]

[[material]]
name = "glass"
density = 2500.0

[[contact]]
materials = ["glass", "glass"]
law = "linear"
normal_stiffness = 1e4
restitution = 0.5

[[wall]]
name = "shelf"
box = { min = [0.045, 0.05], max = [0.055, 0.06] }
material = "glass"

[[particles]]
generator = "column"
material = "glass"
base = [0.0, 0.0]
count = 1
radius = 0.001

[[particles]]
generator = "column"
material = "glass"
base = [0.05, 0.06]
count = 1
radius = 0.001

[[inlet]]
name = "rain"
material = "glass"
min = [-0.05, 0.3]
max = [0.05, 0.4]
radius_min = 0.001
radius_max = 0.002
velocity = [0.2, 0.0]
rate = 400.0
count = 10
interval = 0.01
seed = 9

[[stage]]
name = "fall"
duration = 0.05
gravity = [0.0, -9.80665]
)";

}  // namespace

TEST(Inlet, AddsTheGrainsDueWhereTheyFitAndTheyFallFreely) {
  const std::string dir = temp_dir("inlet_schedule");
  Scene<2> scene = scene_from_text<2>(dir, "rain.toml", schedule_scene);
  auto& sim = scene.simulation;
  ASSERT_EQ(scene.inlets.size(), 1U);
  auto& rain = scene.inlets[0];
  sim.gravity = Vec<2>(0.0, -g);
  sim.prepare();
  struct Placed {
    std::uint32_t id;
    Vec<2> x0;
    double t0;
  };
  std::vector<Placed> placed;
  // Three insertions 10 ms apart: 4, 4, then 2 (the count's limit), none after.
  const std::vector<std::uint64_t> expected = {4, 4, 2, 0};
  for (std::size_t event = 0; event < expected.size(); ++event) {
    const std::size_t before = sim.particles.size();
    const double t0 = sim.time;
    EXPECT_NEAR(rain.next_time, 0.01 * static_cast<double>(event), 1e-12);
    const auto result = insert_due(rain, sim);
    EXPECT_EQ(result.added, expected[event]) << "insertion " << event;
    EXPECT_FALSE(result.short_of_room);
    EXPECT_EQ(sim.particles.size(), before + expected[event]);
    for (std::size_t i = before; i < sim.particles.size(); ++i) {
      const auto& p = sim.particles;
      const double r = p.radius[i];
      // Numbered on from every particle made so far, removed ones too (the
      // first disc leaves the domain after 14 ms): 2 from the scene, then
      // the inlet's in order.
      EXPECT_EQ(p.id[i], 2 + placed.size()) << "index " << i;
      EXPECT_GE(r, 0.001);
      EXPECT_LE(r, 0.002);
      // Whole in the box, touching no other grain and no wall.
      for (int k = 0; k < 2; ++k) {
        EXPECT_GE(p.position[i][k] - r, rain.lower[k]);
        EXPECT_LE(p.position[i][k] + r, rain.upper[k]);
      }
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (j != i) {
          EXPECT_GE((p.position[j] - p.position[i]).norm(), r + p.radius[j]) << i << " and " << j;
        }
      }
      EXPECT_GE(sim.walls[0].gap(p.position[i]), r);
      EXPECT_EQ(p.velocity[i], Vec<2>(0.2, 0.0));
      // Its force is its weight, as a first evaluation would give it.
      const double m = 2500.0 * std::numbers::pi * r * r;
      EXPECT_NEAR(p.force[i][1], -m * g, 1e-15 * m * g);
      placed.push_back({p.id[i], p.position[i], t0});
    }
    sim.advance(100);  // 10 ms
  }
  EXPECT_EQ(rain.inserted, 10U);
  EXPECT_TRUE(rain.exhausted());
  EXPECT_EQ(sim.inserted_count, 10U);
  EXPECT_EQ(sim.removed_count, 1U) << "the first disc has left the domain";
  double mass = 0.0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    if (sim.particles.id[i] >= 2) mass += 1.0 / sim.particles.inv_mass[i];
  }
  EXPECT_NEAR(sim.inserted_mass, mass, 1e-14 * mass);
  EXPECT_NEAR(rain.inserted_mass, mass, 1e-14 * mass);
  // Each grain has fallen freely since it was placed (they are 2 mm or more
  // apart and fall alike, so none meets another): velocity Verlet under a
  // constant force is exact, x = x0 + v0 t - g t^2 / 2 to round-off, 1e-12 m
  // over 0.04 s. A grain given no force at its placing would lag by
  // g dt / 2 x t, 2e-5 m.
  for (const auto& pl : placed) {
    const std::size_t i = sim.particles.index_of(pl.id);
    ASSERT_LT(i, sim.particles.size());
    const double t = sim.time - pl.t0;
    EXPECT_NEAR(sim.particles.position[i][0], pl.x0[0] + 0.2 * t, 1e-12) << "grain " << pl.id;
    EXPECT_NEAR(sim.particles.position[i][1], pl.x0[1] - 0.5 * g * t * t, 1e-12) << "grain " << pl.id;
  }
  std::filesystem::remove_all(dir);
}

// examples/dem_cases/pluviation.toml: 2.4 kg/m of sand rained at 3 kg/(s m)
// into a box 60 mm wide, then settled.
TEST(Inlet, PluviatedBedRestsOnTheWallsWithItsWholeWeight) {
  const std::string dir = temp_dir("inlet_pluviation");
  Scene<2> scene = darcydem::testing::load_scene<2>("examples/dem_cases/pluviation.toml");
  RunOptions options;
  options.out_dir = dir;
  const RunSummary summary = run_scene<2>(scene, options);
  ASSERT_FALSE(summary.interrupted);
  ASSERT_EQ(summary.stages_completed.size(), 2U);
  const auto& sim = scene.simulation;
  const auto& hopper = scene.inlets.at(0);
  // The mass: the inlet stops once it has added 2.4 kg/m, so it ends above
  // that by less than its heaviest grain (r = 1.2 mm).
  const double heaviest = 2650.0 * std::numbers::pi * 0.0012 * 0.0012;
  const double lightest = 2650.0 * std::numbers::pi * 0.0008 * 0.0008;
  EXPECT_GE(hopper.inserted_mass, 2.4);
  EXPECT_LT(hopper.inserted_mass, 2.4 + heaviest);
  EXPECT_EQ(sim.particles.size(), hopper.inserted);
  EXPECT_EQ(hopper.short_events, 0U);
  double mass = 0.0;
  for (double inv : sim.particles.inv_mass) mass += 1.0 / inv;
  EXPECT_NEAR(mass, hopper.inserted_mass, 1e-12 * mass);
  // On schedule: the row at t = 0.01 k follows k insertions (the one at
  // 0.01 k comes after it), which made 0.03 k kg/m due; what was added is
  // short of that by less than the next grain, never over it (to the
  // 10 digits of probes.csv), and each grain weighs between the lightest and
  // the heaviest.
  const auto probes = read_probes(dir + "/probes.csv");
  const auto& t = probes.at("time");
  const auto& rained = probes.at("rained");
  const auto& grains = probes.at("grains");
  std::size_t checked = 0;
  for (std::size_t row = 0; row < t.size() && rained[row] < 2.4; ++row) {
    const double due = 0.03 * std::round(t[row] / 0.01);
    EXPECT_LE(rained[row], due * (1.0 + 1e-9)) << "t = " << t[row];
    EXPECT_GT(rained[row], due - heaviest) << "t = " << t[row];
    EXPECT_GE(rained[row], grains[row] * lightest * (1.0 - 1e-9));
    EXPECT_LE(rained[row], grains[row] * heaviest * (1.0 + 1e-9));
    ++checked;
  }
  EXPECT_GE(checked, 80U) << "2.4 kg/m at 3 kg/(s m) takes 80 insertions";
  // Statics: at rest (kinetic energy below 1e-9 J) the floor and the side
  // walls carry the bed's whole weight. Measured: the sum is the weight to
  // 4e-6 of it. The bound, 1e-3, is a quarter of one grain's share (1/282):
  // a grain lost, counted twice, or still falling fails it.
  const double weight = hopper.inserted_mass * g;
  double load = 0.0;
  for (const auto& w : sim.walls) load += w.force[1];
  EXPECT_NEAR(-load, weight, 1e-3 * weight);
  EXPECT_NEAR(
      -(probes.at("floor_load").back() + probes.at("left_load").back() + probes.at("right_load").back()),
      weight, 1e-3 * weight);
  // Every grain is in the box below the hopper.
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    const auto& x = sim.particles.position[i];
    EXPECT_TRUE(x[0] > 0.0 && x[0] < 0.06 && x[1] > 0.0 && x[1] < 0.09) << "grain " << sim.particles.id[i];
  }
  const std::string json = darcydem::testing::file_contents(dir + "/run.json");
  EXPECT_NE(json.find(fmt::format("\"inserted\": {{\"particles\": {},", hopper.inserted)), std::string::npos)
      << json;
  std::filesystem::remove_all(dir);
}

namespace {

// The bed of frictional_bed.hpp; with the inlet, 60 grains rained beside it
// that fall past it out of the domain.
std::string bed_scene(bool with_inlet) {
  const std::string inlet = R"(
[[inlet]]
name = "beside"
material = "sand"
min = [0.04, 0.05]
max = [0.06, 0.1]
radius = 0.0008
rate = 400.0
count = 60
interval = 0.005
)";
  return darcydem::testing::frictional_bed_scene("", with_inlet ? inlet : "");
}

/// The bed's final positions, by id.
std::vector<Vec<2>> settle_bed(const std::string& dir, bool with_inlet, std::size_t sort_threshold,
                               std::uint64_t* inserted) {
  Scene<2> scene = scene_from_text<2>(dir, with_inlet ? "with.toml" : "without.toml", bed_scene(with_inlet));
  scene.simulation.sort_threshold = sort_threshold;
  RunOptions options;
  options.out_dir = dir + (with_inlet ? "/with" : "/without");
  std::filesystem::remove_all(options.out_dir);
  EXPECT_FALSE(run_scene<2>(scene, options).interrupted);
  const auto& p = scene.simulation.particles;
  std::vector<Vec<2>> x(120);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.id[i] < 120) x[p.id[i]] = p.position[i];
  }
  *inserted = scene.simulation.inserted_count;
  return x;
}

}  // namespace

TEST(Inlet, AddingGrainsLeavesTheOthersContactHistories) {
  const std::string dir = temp_dir("inlet_bed");
  // Without reordering the bed's grains keep their indices and meet the
  // same contacts in the same order, so the runs must agree to the last
  // bit. A history lost when the lists are rebuilt for the new grains
  // changes the frictional bed's course (checked by dropping the carried
  // histories at a build with new grains: the bed then differs by up to
  // 7.1e-3 m).
  std::uint64_t inserted = 0;
  const auto alone = settle_bed(dir, false, 1'000'000, &inserted);
  EXPECT_EQ(inserted, 0U);
  const auto with = settle_bed(dir, true, 1'000'000, &inserted);
  EXPECT_EQ(inserted, 60U);
  for (std::size_t i = 0; i < alone.size(); ++i) {
    ASSERT_EQ(with[i][0], alone[i][0]) << "bed grain " << i;
    ASSERT_EQ(with[i][1], alone[i][1]) << "bed grain " << i;
  }
  // With a reordering at every list build, insertion and reordering
  // compose; the order of the sums differs, and a settling bed amplifies
  // round-off, so the bound is on its scale (as for a removal,
  // Domain.RemovingGrainsLeavesTheOthersContactHistories): 1e-9 m (measured
  // 8.8e-13 m).
  const auto sorted = settle_bed(dir, true, 0, &inserted);
  double worst = 0.0;
  for (std::size_t i = 0; i < alone.size(); ++i) worst = std::max(worst, (sorted[i] - alone[i]).norm());
  EXPECT_LT(worst, 1e-9);
  std::filesystem::remove_all(dir);
}

namespace {

// An empty box and an inlet that waits for the second stage: 100 grains/s,
// one at each insertion 10 ms apart, once a stage sets it active.
std::string waiting_scene(bool with_rain) {
  std::string text = R"(
[simulation]
dimension = 2
time_step = 1e-4

[[material]]
name = "glass"
density = 2500.0

[[contact]]
materials = ["glass", "glass"]
law = "linear"
normal_stiffness = 1e4
restitution = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "glass"

[[inlet]]
name = "rain"
material = "glass"
min = [0.0, 0.1]
max = [0.05, 0.11]
radius = 0.001
rate = 100.0
active = false

[output]
probe_interval = 0.005

[[probe]]
name = "added"
quantity = "inserted_particles"

[[probe]]
name = "first_y"
quantity = "particle_position"
particle = 0
component = "y"

[[stage]]
name = "wait"
duration = 0.05
gravity = [0.0, -9.80665]
)";
  if (with_rain) text += "\n[[stage]]\nname = \"rain\"\nduration = 0.05\ninlets.rain = { active = true }\n";
  return text;
}

}  // namespace

TEST(Inlet, WaitsForTheStageThatSetsItActive) {
  const std::string dir = temp_dir("inlet_waiting");
  {
    // The first stage alone: no grain at all, and the output still written
    // (the end-of-run packing used to take the smallest radius of none).
    Scene<2> scene = scene_from_text<2>(dir, "wait.toml", waiting_scene(false));
    RunOptions options;
    options.out_dir = dir + "/wait";
    ASSERT_FALSE(run_scene<2>(scene, options).interrupted);
    EXPECT_EQ(scene.simulation.particles.size(), 0U);
    const std::string csv = darcydem::testing::file_contents(dir + "/wait/particles_final.csv");
    EXPECT_NE(csv.find("\nx,y,radius\n"), std::string::npos) << csv;
    EXPECT_EQ(csv.substr(csv.find("x,y,radius\n")), "x,y,radius\n") << "no rows";
    const std::string json = darcydem::testing::file_contents(dir + "/wait/run.json");
    EXPECT_NE(json.find("\"inserted\": {\"particles\": 0,"), std::string::npos) << json;
    EXPECT_NE(json.find("\"status\": \"completed\""), std::string::npos) << json;
  }
  Scene<2> scene = scene_from_text<2>(dir, "rain.toml", waiting_scene(true));
  RunOptions options;
  options.out_dir = dir + "/rain";
  ASSERT_FALSE(run_scene<2>(scene, options).interrupted);
  // Insertions at 0.05, 0.06, ..., 0.09 s (the one due at 0.10 s, the run's
  // end, never comes): a row at t has those before it, the one due at t
  // itself coming after the row. Particle 0 is nowhere (nan) until placed.
  const auto probes = read_probes(dir + "/rain/probes.csv");
  const auto& t = probes.at("time");
  const auto& added = probes.at("added");
  const auto& first_y = probes.at("first_y");
  // Every 5 ms from 0 to 0.1 s, and a row at each stage's end (0.05 and
  // 0.1 s again).
  ASSERT_EQ(t.size(), 23U);
  for (std::size_t row = 0; row < t.size(); ++row) {
    // The ticks k = 5 ... 9 with 0.01 k < t.
    const double ticks = std::clamp(std::ceil((t[row] - 1e-9) / 0.01) - 5.0, 0.0, 5.0);
    EXPECT_EQ(added[row], ticks) << "t = " << t[row];
    EXPECT_EQ(std::isnan(first_y[row]), added[row] == 0.0) << "t = " << t[row];
  }
  EXPECT_EQ(added.back(), 5.0);
  EXPECT_EQ(scene.simulation.particles.size(), 5U);
  std::filesystem::remove_all(dir);
}

// In 3D, by mass: spheres of 1-2 mm at 0.05 kg/s, inserted every 20 ms into
// a box 40 mm on a side above a floor.
TEST(Inlet, AddsSpheresByMassIn3D) {
  const std::string dir = temp_dir("inlet_3d");
  Scene<3> scene = scene_from_text<3>(dir, "rain3d.toml", R"(
[simulation]
dimension = 3
time_step = "auto"

[[material]]
name = "sand"
density = 2650.0
youngs_modulus = 1e8
poisson_ratio = 0.25

[[contact]]
materials = ["sand", "sand"]
law = "hertz_mindlin"
restitution = 0.5
friction = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[inlet]]
name = "rain"
material = "sand"
min = [0.0, 0.0, 0.05]
max = [0.04, 0.04, 0.09]
radius_min = 0.001
radius_max = 0.002
mass_rate = 0.05
interval = 0.02
seed = 4

[[stage]]
duration = 0.06
gravity = [0.0, 0.0, -9.80665]
)");
  auto& sim = scene.simulation;
  auto& rain = scene.inlets.at(0);
  sim.gravity = *scene.stages.at(0).gravity;
  sim.prepare();
  const double heaviest = 2650.0 * 4.0 / 3.0 * std::numbers::pi * 0.008e-6;
  for (int event = 1; event <= 3; ++event) {
    const std::size_t before = sim.particles.size();
    insert_due(rain, sim);
    // 1 g due at each insertion: added short of the total due by less than
    // the next grain (at most the heaviest), never over it.
    const double due = 1e-3 * event;
    EXPECT_LE(rain.inserted_mass, due * (1.0 + 1e-12));
    EXPECT_GT(rain.inserted_mass, due - heaviest);
    const auto& p = sim.particles;
    for (std::size_t i = before; i < p.size(); ++i) {
      const double r = p.radius[i];
      EXPECT_NEAR(1.0 / p.inv_mass[i], 2650.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r, 1e-15);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p.position[i][k] - r, rain.lower[k]);
        EXPECT_LE(p.position[i][k] + r, rain.upper[k]);
      }
      for (std::size_t j = 0; j < i; ++j) EXPECT_GE((p.position[j] - p.position[i]).norm(), r + p.radius[j]);
    }
    sim.advance(static_cast<std::uint64_t>(std::round(0.02 / sim.time_step)));
  }
  EXPECT_GT(sim.particles.size(), 30U) << "3 g of 1-2 mm spheres: about 50";
  std::filesystem::remove_all(dir);
}

// Grains rained into water: a bed of 40 discs under water in a grid of 5 x 5
// cells of 2 mm, drained at the top; an inlet above the grid rains 40 more,
// which fall into the water and onto the bed.
TEST(Inlet, GrainsRainedIntoWaterKeepItsVolumeBalance) {
  const std::string dir = temp_dir("inlet_water");
  Scene<2> scene = scene_from_text<2>(dir, "water.toml", darcydem::testing::kRainIntoWater);
  // The grains' volume in the grid (exact ball-box overlaps, per metre).
  const Vec<2> lo(0.0, 0.0);
  const Vec<2> hi(0.01, 0.01);
  auto solid_in_grid = [&] { return (1.0 - box_porosity<2>(scene.simulation.particles, lo, hi)) * 1e-4; };
  const double solid_before = solid_in_grid();
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<2>(scene, options).interrupted);
  const auto& sim = scene.simulation;
  EXPECT_EQ(sim.inserted_count, 40U);
  // All 40 have fallen into the grid (its top at 10 mm).
  std::size_t in_water = 0;
  for (const auto& x : sim.particles.position) in_water += x[1] < 0.01 ? 1 : 0;
  EXPECT_EQ(in_water, 80U);
  // The water's volume balance holds as grains enter the grid from outside
  // (inflow = stored + pore change), to round-off relative to the gross
  // flow, as for the scene's own grains (FluidScenes).
  const auto& b = scene.fluid->total_balance();
  EXPECT_GT(b.gross, 0.0);
  EXPECT_LT(std::abs(b.imbalance()), 1e-9 * b.gross);
  // The pore change is minus the grains' volume that came into the grid:
  // the 40 discs, less what the bed's grains pressed further into the
  // floor and the sides now hold outside it (measured: 1.2e-4 of the 40
  // discs' volume); from the grains' exact overlaps with the grid's box, to
  // round-off.
  const double came_in = solid_in_grid() - solid_before;
  EXPECT_NEAR(-b.pore_change, came_in, 1e-9 * came_in);
  EXPECT_NEAR(came_in, 40.0 * std::numbers::pi * 0.00049 * 0.00049, 1e-3 * came_in);
  std::filesystem::remove_all(dir);
}
