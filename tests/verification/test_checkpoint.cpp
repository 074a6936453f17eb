// Checkpoint and resume (`darcydem run --resume`): a run stopped part way
// and resumed from its checkpoint must write exactly the files, byte for
// byte, that the same run writes when it never stops. The expectation is
// the uninterrupted run itself, so no tolerance is needed: any state the
// checkpoint forgets (a contact history, a held fluid force, the pore
// pressure of the last step, the analysis' samples, the output counters)
// changes the floating-point history and so the files.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "darcydem/output/checkpoint_archive.hpp"
#include "darcydem/simulation/runner.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("darcydem_ckpt_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  return dir;
}

/// Runs the scene at `path` into `out`; sort_threshold 0 makes every list
/// build reorder the grains (as in a large run).
template <int D>
RunSummary run(const std::string& path, const fs::path& out, std::uint64_t stop_at_step, bool resume) {
  Scene<D> scene = darcydem::testing::load_scene_file<D>(path);
  scene.simulation.sort_threshold = 0;
  RunOptions options;
  options.out_dir = out.string();
  options.stop_at_step = stop_at_step;
  options.resume = resume;
  return run_scene<D>(scene, options);
}

std::string contents(const fs::path& file) { return darcydem::testing::file_contents(file.string()); }

/// Every file of a run's output but run.json (which holds wall times).
std::map<std::string, std::string> output_files(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name != "run.json") files[name] = contents(e.path());
  }
  return files;
}

void expect_same_files(const fs::path& expected, const fs::path& actual) {
  const auto a = output_files(expected);
  const auto b = output_files(actual);
  ASSERT_GT(a.size(), 5U);
  for (const auto& [name, bytes] : a) {
    const auto it = b.find(name);
    ASSERT_NE(it, b.end()) << name << " missing from the resumed run";
    EXPECT_TRUE(it->second == bytes) << name << " differs from the uninterrupted run";
  }
  for (const auto& [name, bytes] : b)
    EXPECT_TRUE(a.count(name) == 1) << "the resumed run also wrote " << name;
}

// The paper's column, K_f = 1e4 (216 777 steps, 168 604 of settling), stopped in the settling
// stage and again during the inflow, the last part on one thread (the
// results do not depend on the thread count). uplift.csv, pressure.csv,
// report.md, probes, snapshots and series must come out the same.
TEST(Checkpoint, ResumedSeepageColumnWritesTheSameFilesBitForBit) {
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/seepage_column/kf_1e4.toml";
  const fs::path whole = fresh_dir("column_whole");
  const fs::path parts = fresh_dir("column_parts");
  const RunSummary a = run<2>(scene, whole, 0, false);
  ASSERT_TRUE(a.seepage_column && a.seepage_column->passed);
  EXPECT_FALSE(fs::exists(whole / "checkpoint.bin")) << "a finished run leaves no checkpoint";

  const RunSummary first = run<2>(scene, parts, 60000, false);
  ASSERT_TRUE(first.interrupted);
  ASSERT_TRUE(first.checkpoint_written && fs::exists(parts / "checkpoint.bin"));
  EXPECT_TRUE(first.stages_completed.empty());
  const RunSummary second = run<2>(scene, parts, 190000, true);
  ASSERT_TRUE(second.interrupted);
  EXPECT_GE(second.resumed_at_step, 60000U);
  EXPECT_LT(second.resumed_at_step, 60256U);
  EXPECT_EQ(second.stages_completed.size(), 1U) << "the second part ends in the inflow stage";
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const RunSummary last = run<2>(scene, parts, 0, true);
  omp_set_num_threads(threads);
  EXPECT_FALSE(last.interrupted);
  EXPECT_EQ(last.steps, a.steps);
  EXPECT_EQ(last.stages_completed, a.stages_completed);
  ASSERT_TRUE(last.seepage_column);
  EXPECT_EQ(last.seepage_column->uplift_rms_error, a.seepage_column->uplift_rms_error);
  EXPECT_EQ(last.seepage_column->pressure_max_error, a.seepage_column->pressure_max_error);
  expect_same_files(whole, parts);
  EXPECT_FALSE(fs::exists(parts / "checkpoint.bin"));
  EXPECT_NE(contents(parts / "run.json").find("\"resumes\": 2"), std::string::npos);
  fs::remove_all(whole);
  fs::remove_all(parts);
}

/// A 3D bed with what a checkpoint must carry besides the column: friction
/// and rolling-resistance histories with walls, a servo-controlled lid, a
/// stage that changes the coupling interval with forces held, permeability
/// from the porosity, an inflow ramp that counts from its stage's start,
/// a boundary patch (a vent in a side) that a stage opens with a ramp of
/// its own, and a stop condition checked on the unbalanced force.
constexpr const char* bed_scene = R"(
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
normal_stiffness = 1e4
restitution = 0.3
friction = 0.5
rolling_friction = 0.1

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[wall]]
name = "lid"
point = [0.0, 0.0, 0.012]
normal = [0.0, 0.0, -1.0]
material = "sand"

[[wall]]
name = "x_low"
point = [0.0, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
material = "sand"

[[wall]]
name = "x_high"
point = [0.006, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
material = "sand"

[[wall]]
name = "y_low"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]
material = "sand"

[[wall]]
name = "y_high"
point = [0.0, 0.006, 0.0]
normal = [0.0, -1.0, 0.0]
material = "sand"

[[particles]]
generator = "random"
material = "sand"
min = [0.0, 0.0, 0.0]
max = [0.006, 0.006, 0.011]
count = 150
radius_min = 0.0004
radius_max = 0.0005
seed = 7

[fluid]
density = 1000.0
viscosity = 1.0e-3
bulk_modulus = 1e6
drag = "ergun"
solver = "cg"
steps_per_update = 3
hold_forces = true

[fluid.grid]
origin = [0.0, 0.0, 0.0]
cells = [3, 3, 6]
size = [0.002, 0.002, 0.002]

[fluid.permeability]
model = "kozeny_carman"

[fluid.boundary]
z_max = { type = "drained", pressure = 0.0 }
vent = { side = "x_max", from = [0.0, 0.006], to = [0.006, 0.012], type = "no_flow" }

[output]
probe_interval = 0.001
snapshot_interval = 0.01

[[probe]]
name = "lid"
quantity = "wall_position"
wall = "lid"
component = "z"

[[probe]]
name = "bottom_pressure"
quantity = "pore_pressure"
position = [0.003, 0.003, 0.001]

[[probe]]
name = "unbalanced"
quantity = "unbalanced_force"

[[probe]]
name = "balance"
quantity = "fluid_balance"

[[probe]]
name = "vent"
quantity = "fluid_inflow"
side = "vent"

[[stage]]
name = "settle"
duration = 0.02
gravity = [0.0, 0.0, -9.80665]
local_damping = 0.3
walls.lid = { servo = { target_force = 0.002, gain = 0.5, max_speed = 0.05 } }

[[stage]]
name = "seepage"
duration = 0.02
stop_when = { unbalanced_force_below = 1e-9, check_interval = 50 }
fluid.steps_per_update = 1
fluid.hold_forces = false
[stage.fluid.boundary]
z_min = { type = "flux", inflow = { times = [0.0, 0.01], values = [0.0, 0.005] } }
vent = { type = "drained", pressure = { times = [0.0, 0.015], values = [0.0, -2.0] } }
)";

TEST(Checkpoint, ResumedBedWithServoLidAndHeldForcesWritesTheSameFiles) {
  const fs::path dir = fresh_dir("bed");
  fs::create_directories(dir);
  const std::string scene = (dir / "bed.toml").string();
  std::ofstream(scene) << bed_scene;
  const fs::path whole = dir / "whole";
  const fs::path parts = dir / "parts";
  const RunSummary a = run<3>(scene, whole, 0, false);
  ASSERT_EQ(a.stages_completed.size(), 2U);
  // The vent opened in stage 2 (its probe is the last column).
  const std::string probes = contents(whole / "probes.csv");
  const auto last_line = probes.substr(probes.rfind('\n', probes.size() - 2) + 1);
  EXPECT_NE(std::stod(last_line.substr(last_line.rfind(',') + 1)), 0.0) << last_line;
  // Stopped inside a fluid interval of stage 1 (at step 512, two steps into
  // an interval of 3, with the forces held)
  // and again in stage 2.
  const std::uint64_t total = a.steps;
  ASSERT_GT(total, 2000U);
  const RunSummary first = run<3>(scene, parts, 500, false);
  ASSERT_TRUE(first.interrupted);
  const RunSummary second = run<3>(scene, parts, total - 300, true);
  ASSERT_TRUE(second.interrupted);
  const RunSummary last = run<3>(scene, parts, 0, true);
  EXPECT_FALSE(last.interrupted);
  EXPECT_EQ(last.steps, a.steps);
  expect_same_files(whole, parts);
  fs::remove_all(dir);
}

/// Runs `scene` whole into dir/whole (its stages all `stages`), then into
/// dir/parts stopped at step `stop` (with `stages_before` stages done) and
/// resumed: the two must write the same files. Removes dir.
template <int D>
void expect_resumed_run_writes_the_same_files(const std::string& scene, const fs::path& dir,
                                              std::size_t stages, std::uint64_t stop,
                                              std::size_t stages_before) {
  const fs::path whole = dir / "whole";
  const fs::path parts = dir / "parts";
  const RunSummary a = run<D>(scene, whole, 0, false);
  ASSERT_EQ(a.stages_completed.size(), stages);
  const RunSummary first = run<D>(scene, parts, stop, false);
  ASSERT_TRUE(first.interrupted);
  ASSERT_EQ(first.stages_completed.size(), stages_before);
  const RunSummary last = run<D>(scene, parts, 0, true);
  EXPECT_FALSE(last.interrupted);
  EXPECT_EQ(last.steps, a.steps);
  expect_same_files(whole, parts);
  fs::remove_all(dir);
}

TEST(Checkpoint, ResumedPileWritesTheSameFiles) {
  // examples/fluid_cases/pile_penetration.toml, shortened: 0.03 s of
  // settling, 0.05 s of push (the rod's tip in the grid after 0.025 s of
  // it) and 0.01 s of rest. Stopped with the rod in the grid and moving: the
  // walls' volume per cell at the last fluid step must come back, or the
  // next Biot source takes the whole rod as new.
  const fs::path dir = fresh_dir("pile");
  fs::create_directories(dir);
  const std::string text = darcydem::testing::scene_variant(
      "examples/fluid_cases/pile_penetration.toml",
      {{"name = \"settle\"\nduration = 0.1", "name = \"settle\"\nduration = 0.03"},
       {"name = \"push\"\nduration = 0.125", "name = \"push\"\nduration = 0.05"},
       {"name = \"rest\"\nduration = 0.075", "name = \"rest\"\nduration = 0.01"}});
  const std::string scene = (dir / "pile.toml").string();
  std::ofstream(scene) << text;
  // Settling takes 25 900 steps, the tip reaches the grid 21 600 steps
  // later and the push ends at 69 100.
  expect_resumed_run_writes_the_same_files<3>(scene, dir, 3, 60000, 1);
}

TEST(Checkpoint, ResumedSealedPistonWritesTheSameFiles) {
  // examples/fluid_cases/consolidation_sealed_piston.toml with the piston
  // impermeable (it then seals the drained top itself, as
  // FluidScenes.ConsolidationUnderAnImpermeablePiston runs it), stopped
  // 0.02 s into the load stage (step 169 000 of 278 339: the settling takes
  // 167 003): the servo's direction and the water's thrust on the piston,
  // which its next speed reads, and the faces the piston closes must come
  // back.
  const fs::path dir = fresh_dir("sealed_piston");
  fs::create_directories(dir);
  const std::string text =
      darcydem::testing::scene_variant("examples/fluid_cases/consolidation_sealed_piston.toml",
                                       {{"displaces_fluid = true", "impermeable = true"},
                                        {"[stage.fluid.boundary]\ny_max = { type = \"no_flow\" }\n", ""}});
  const std::string scene = (dir / "impermeable_piston.toml").string();
  std::ofstream(scene) << text;
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, 169000, 1);
}

TEST(Checkpoint, ResumedHopperOfFacetsWritesTheSameFiles) {
  // examples/dem_cases/conical_hopper.toml with 150 spheres, 0.1 s of
  // filling (they land on the cone's facets and the gate) and 0.05 s of
  // discharge (71 800 steps), stopped at step 50 000, the gate sliding
  // open: the grains' contacts with the mesh's facets, each with its
  // springs, must come back with the facet they are on.
  const fs::path dir = fresh_dir("mesh_hopper");
  fs::create_directories(dir);
  const std::string text = darcydem::testing::scene_variant(
      "examples/dem_cases/conical_hopper.toml",
      {{"file = \"conical_hopper.stl\"",
        "file = \"" + std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/conical_hopper.stl\""},
       {"count = 550", "count = 150"},
       {"name = \"fill\"\nduration = 0.4", "name = \"fill\"\nduration = 0.1"},
       {"name = \"discharge\"\nduration = 0.8", "name = \"discharge\"\nduration = 0.05"}});
  const std::string scene = (dir / "hopper.toml").string();
  std::ofstream(scene) << text;
  expect_resumed_run_writes_the_same_files<3>(scene, dir, 2, 50000, 1);
}

TEST(Checkpoint, ResumedClumpPourWritesTheSameFiles) {
  // examples/dem_cases/clump_pour.toml for 0.05 s (29 500 steps), stopped
  // at step 20 000 when the lowest clumps have landed and turn: each
  // clump's place, orientation, velocities and last force and moment must
  // come back, and its members be found again by their numbers.
  const fs::path dir = fresh_dir("clump_pour");
  fs::create_directories(dir);
  const std::string text = darcydem::testing::scene_variant(
      "examples/dem_cases/clump_pour.toml",
      {{"name = \"settle\"\nduration = 1.5", "name = \"settle\"\nduration = 0.05"}});
  const std::string scene = (dir / "clump_pour.toml").string();
  std::ofstream(scene) << text;
  expect_resumed_run_writes_the_same_files<3>(scene, dir, 1, 20000, 0);
}

TEST(Checkpoint, ResumedSiloWritesTheSameFilesAfterGrainsLeftTheDomain) {
  // examples/dem_cases/silo_discharge.toml with 300 discs, 0.2 s of filling
  // and 0.3 s of discharge (19 306 steps), stopped at step 15 000 (0.39 s),
  // when some grains have left the domain and others are on their way: the
  // removed count and mass, and the lists of the grains left (their indices
  // moved down), must come back, and the header's particle count is the
  // scene's, removed ones included.
  const fs::path dir = fresh_dir("silo");
  fs::create_directories(dir);
  const std::string text = darcydem::testing::scene_variant(
      "examples/dem_cases/silo_discharge.toml",
      {{"count = 1400", "count = 300"},
       {"name = \"fill\"\nduration = 0.6", "name = \"fill\"\nduration = 0.2"},
       {"name = \"discharge\"\nduration = 1.5", "name = \"discharge\"\nduration = 0.3"}});
  const std::string scene = (dir / "silo.toml").string();
  std::ofstream(scene) << text;
  const std::uint64_t stop = 15000;
  {
    // Grains have gone by the stop, and more go after it.
    const fs::path probe_run = dir / "probe_run";
    const RunSummary a = run<2>(scene, probe_run, 0, false);
    const std::string probes = contents(probe_run / "probes.csv");
    std::istringstream rows(probes);
    std::string line;
    std::getline(rows, line);  // time,discharged,discharged_count,in_silo,kinetic_energy
    double at_stop = -1.0;
    double at_end = -1.0;
    while (std::getline(rows, line)) {
      std::istringstream cells(line);
      std::string time, mass, count;
      std::getline(cells, time, ',');
      std::getline(cells, mass, ',');
      std::getline(cells, count, ',');
      if (std::stod(time) <= static_cast<double>(stop) * a.simulated_time / static_cast<double>(a.steps))
        at_stop = std::stod(count);
      at_end = std::stod(count);
    }
    ASSERT_GT(at_stop, 0.0);
    ASSERT_GT(at_end, at_stop);
    fs::remove_all(probe_run);
  }
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, stop, 1);
}

TEST(Checkpoint, ResumedPluviationWritesTheSameFilesWhileGrainsAreAdded) {
  // examples/dem_cases/pluviation.toml, stopped at step 20 000 of the rain's
  // 37 518 (0.53 s, half the grains in): the inlet's counts, its budget,
  // the next grain's size and its random numbers must come back, or the
  // grains added after the resume differ; and the header's particle count
  // is the scene's, the inlet's grains not counted.
  const fs::path dir = fresh_dir("pluviation");
  fs::create_directories(dir);
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/pluviation.toml";
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, 20000, 0);
}

TEST(Checkpoint, ResumedClumpPluviationWritesTheSameFilesWhileClumpsAreAdded) {
  // examples/dem_cases/clump_pluviation.toml, stopped at step 8000 (0.136 s,
  // half the peanuts in): the clumps added so far must come back with
  // their members' numbers, and the inlet's random numbers, which turn the
  // clumps as well as place them, must go on as they would have.
  const fs::path dir = fresh_dir("clump_pluviation");
  fs::create_directories(dir);
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/clump_pluviation.toml";
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, 8000, 0);
}

TEST(Checkpoint, ResumedSlidingSphereKeepsItsEnergyBudget) {
  // examples/dem_cases/slip_to_roll.toml, whose probes track the energy
  // budget, stopped at step 10 000 of 115 624, mid-slide: the works done so
  // far and the springs' energy at the start must come back, or the
  // budget's probes after the resume start again from zero.
  const fs::path dir = fresh_dir("slip_to_roll");
  fs::create_directories(dir);
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/slip_to_roll.toml";
  expect_resumed_run_writes_the_same_files<3>(scene, dir, 1, 10000, 0);
}

TEST(Checkpoint, ResumedCementedChainKeepsItsBonds) {
  // examples/dem_cases/cemented_chain.toml, stopped at step 3000 of stage
  // "hang" (bonds made, the chain still settling): the bonds and the count
  // of broken ones must come back, or the overload stage breaks a different
  // number (an unbonded chain simply falls apart).
  const fs::path dir = fresh_dir("cemented_chain");
  fs::create_directories(dir);
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/cemented_chain.toml";
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, 3000, 0);
}

/// expect_resumed_run_writes_the_same_files on a variant of an example
/// (testing::scene_variant's `swaps`), written as dir/scene.toml.
template <int D>
void expect_resumed_variant_writes_the_same_files(
    const std::string& example, const std::vector<std::pair<std::string, std::string>>& swaps,
    const std::string& name, std::size_t stages, std::uint64_t stop, std::size_t stages_before) {
  const fs::path dir = fresh_dir(name);
  fs::create_directories(dir);
  const fs::path scene = dir / "scene.toml";
  std::ofstream(scene) << darcydem::testing::scene_variant(example, swaps);
  const fs::path out = dir / "out";
  fs::create_directories(out);
  expect_resumed_run_writes_the_same_files<D>(scene.string(), out, stages, stop, stages_before);
}

TEST(Checkpoint, ResumedBondedCantileverKeepsItsBondsBending) {
  // examples/dem_cases/bonded_cantilever.toml, stopped at step 3000 of stage
  // "sag" (the cantilever still bending): each bond's turn must come back,
  // or its spring would start unbent and the cantilever sag further.
  const fs::path dir = fresh_dir("bonded_cantilever");
  fs::create_directories(dir);
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/dem_cases/bonded_cantilever.toml";
  expect_resumed_run_writes_the_same_files<2>(scene, dir, 2, 3000, 0);
}

TEST(Checkpoint, ResumedRotatingDrumKeepsTurning) {
  // examples/dem_cases/rotating_drum.toml with 150 spheres, 0.1 s of
  // settling (about 11 400 steps) and 0.1 s of turning, stopped at step 17 000,
  // the drum turning: its spin and the torque its probe reads must come
  // back, or the grains after the resume meet a still drum.
  expect_resumed_variant_writes_the_same_files<3>("examples/dem_cases/rotating_drum.toml",
                                                  {{"count = 450", "count = 150"},
                                                   {"duration = 0.6", "duration = 0.1"},
                                                   {"duration = 3.0", "duration = 0.1"}},
                                                  "rotating_drum", 2, 17000, 1);
}

TEST(Checkpoint, ResumedStageKeepsItsFriction) {
  // examples/dem_cases/slip_to_roll.toml whose stages slide the sphere at
  // mu = 0.1 for 20 ms, then at 0.2 (the [[contact]]'s is 0.3), stopped
  // in the second at step 26 000 (about 22 ms), still sliding: its
  // friction must come back with the checkpoint, or the sphere slows at
  // the first stage's or the scene's friction after the resume.
  expect_resumed_variant_writes_the_same_files<3>(
      "examples/dem_cases/slip_to_roll.toml",
      {{"[[stage]]\nname = \"roll\"\nduration = 0.1\n",
        "[[stage]]\nname = \"slide\"\nduration = 0.02\ncontacts = [{ materials = [\"glass\", \"glass\"], "
        "friction = 0.1 }]\ngravity = [0.0, 0.0, -9.81]\n\n[[stage]]\nname = \"roll\"\nduration = 0.02\n"
        "contacts = [{ materials = [\"glass\", \"glass\"], friction = 0.2 }]\n"}},
      "stage_friction", 2, 26000, 1);
}

TEST(Checkpoint, ResumedCellKeepsItsServosRadius) {
  // examples/dem_cases/triaxial_cell.toml with 150 spheres, 0.03 s of
  // compaction and 0.01 s of shear, stopped at step 30 000 (about 20 ms),
  // the cell closing at its max_speed: its radius must come back, and the
  // list's mark of it, or the resumed run's grains meet another cell.
  expect_resumed_variant_writes_the_same_files<3>("examples/dem_cases/triaxial_cell.toml",
                                                  {{"count = 500", "count = 150"},
                                                   {"duration = 0.15", "duration = 0.03"},
                                                   {"duration = 0.3", "duration = 0.01"}},
                                                  "triaxial_cell", 2, 30000, 0);
}

TEST(Checkpoint, ResumedTiltingTableKeepsTurning) {
  // examples/dem_cases/tilting_table.toml, its tilt cut to 2 s, stopped at
  // step 200 000 (about 1.6 s into the tilt, 0.16 rad): the table's turn
  // (its axes, the point it turns about, its spin) must come back, or the
  // block would sit on a level table after the resume.
  expect_resumed_variant_writes_the_same_files<2>("examples/dem_cases/tilting_table.toml",
                                                  {{"duration = 4.5", "duration = 2.0"}}, "tilting_table", 2,
                                                  200000, 1);
}

TEST(Checkpoint, ResumedVibratedBedKeepsShaking) {
  // examples/dem_cases/vibrated_bed.toml stopped at step 100 000, 0.125 s
  // into the shaking (70 569 steps settle it): the floor's oscillation (its
  // amplitude, frequency, phase and the time it began) must come back, or
  // the floor would stand still, or start its sine again, after the resume.
  expect_resumed_variant_writes_the_same_files<2>("examples/dem_cases/vibrated_bed.toml", {}, "vibrated_bed",
                                                  2, 100000, 1);
}

TEST(Checkpoint, ResumedCyclicPistonKeepsItsSchedule) {
  // examples/fluid_cases/consolidation_sealed_piston.toml with the load
  // stage's servo on a schedule (0.26 to 0.3 N over 0.5 s) and a cycle
  // (0.25 N at 1.5 Hz from its lowest), stopped at step 200 000, 0.3 s into
  // the stage (the settling takes 167 003): the schedule, the cycle and the
  // time they count from (the stage's start) must come back, or the target
  // would stand still, or start its cycle again, after the resume.
  expect_resumed_variant_writes_the_same_files<2>(
      "examples/fluid_cases/consolidation_sealed_piston.toml",
      {{"servo = { target_force = 0.51, gain = 0.1",
        "servo = { target_force = { times = [0.0, 0.5], values = [0.26, 0.3] }, cycle = { amplitude = 0.25, "
        "frequency = 1.5, phase = -90.0 }, gain = 0.1"}},
      "cyclic_piston", 2, 200000, 1);
}

TEST(Checkpoint, ResumedPumpingWellKeepsItsSourcesSeries) {
  // examples/fluid_cases/pumping_well.toml with the recovery stage's well
  // on a ramp (pumping 2e-6 m^2/s down to injecting 1e-6 over 0.1 s, from
  // the stage's start), stopped at step 1500, halfway down the ramp: the
  // series and the time it counts from must come back, and the last step's
  // flow the probe reads.
  expect_resumed_variant_writes_the_same_files<2>(
      "examples/fluid_cases/pumping_well.toml",
      {{"well = { inflow = 0.0 }", "well = { inflow = { times = [0.0, 0.1], values = [-2e-6, 1e-6] } }"}},
      "pumping_well", 2, 1500, 1);
}

TEST(Checkpoint, ResumedPumpingWellKeepsTheHeadItHolds) {
  // The same with the recovery stage's well holding a pressure that rises
  // from -10 to 0 Pa over 0.1 s: the source's kind (a held pressure, not
  // an inflow) must come back with its series.
  expect_resumed_variant_writes_the_same_files<2>(
      "examples/fluid_cases/pumping_well.toml",
      {{"well = { inflow = 0.0 }", "well = { pressure = { times = [0.0, 0.1], values = [-10.0, 0.0] } }"}},
      "held_well", 2, 1500, 1);
}

TEST(Checkpoint, ResumedScreenedWellWritesTheSameFiles) {
  // examples/fluid_cases/screened_well.toml, 0.03 s of pumping and of
  // recovery, stopped while it pumps (the runner looks every 256 steps):
  // its bore's pressure is found by superposition at every step.
  expect_resumed_variant_writes_the_same_files<3>(
      "examples/fluid_cases/screened_well.toml",
      {{"name = \"pump\"\nduration = 0.1", "name = \"pump\"\nduration = 0.03"},
       {"name = \"recover\"\nduration = 0.1", "name = \"recover\"\nduration = 0.03"}},
      "screened_well", 2, 256, 0);
}

TEST(Checkpoint, ResumedDrainKeepsItsState) {
  // The pumping test's well made a drain held at -5 Pa, stopped while it
  // stands open, then held at 20 Pa, where it shuts. (A resumed drain
  // that had lost its state would only take one more pass to find it
  // again: the files would be the same; the checkpoint keeps it all the
  // same, so the passes are as in the run that never stopped.)
  expect_resumed_variant_writes_the_same_files<2>(
      "examples/fluid_cases/pumping_well.toml",
      {{"inflow = -2e-6   # m^2/s per metre: pumped out", "pressure = -5.0\ndrain = true"},
       {"well = { inflow = 0.0 }", "well = { pressure = 20.0 }"}},
      "drain_well", 2, 700, 0);
}

TEST(Checkpoint, ResumedCantileverKeepsItsBondsScatteredStrengths) {
  // The same cantilever with strengths scattered from bond to bond
  // (strength_weibull_modulus), stopped in stage "sag": each bond's factor
  // must come back with it, or the overload would break other bonds.
  const fs::path dir = fresh_dir("scattered_cantilever");
  fs::create_directories(dir);
  const std::string text = darcydem::testing::scene_variant(
      "examples/dem_cases/bonded_cantilever.toml",
      {{"bending_strength = 0.011",
        "bending_strength = 0.011, strength_weibull_modulus = 4.0, strength_seed = 5"}});
  const fs::path scene = dir / "scattered.toml";
  std::ofstream(scene) << text;
  const fs::path out = dir / "out";
  fs::create_directories(out);
  expect_resumed_run_writes_the_same_files<2>(scene.string(), out, 2, 3000, 0);
}

// What is refused, with the file and the reason: no checkpoint (the run
// finished), a changed scene, a damaged file.
TEST(Checkpoint, RefusesAMissingForeignOrDamagedCheckpoint) {
  const std::string scene = std::string(DARCYDEM_SOURCE_DIR) + "/examples/seepage_column/kf_1e4.toml";
  const fs::path dir = fresh_dir("refuse");
  auto message_of = [&](const std::string& scene_path) {
    try {
      run<2>(scene_path, dir, 0, true);
    } catch (const CheckpointError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  fs::create_directories(dir);
  const std::string missing = message_of(scene);
  EXPECT_NE(missing.find("checkpoint.bin: no checkpoint to resume from"), std::string::npos) << missing;

  ASSERT_TRUE(run<2>(scene, dir, 1000, false).interrupted);
  const std::string bin = (dir / "checkpoint.bin").string();
  const std::string good = contents(bin);

  // The same scene with one number changed (a longer inflow).
  const fs::path changed = dir / "changed.toml";
  std::string text = contents(scene);
  const auto at = text.find("duration = ");
  ASSERT_NE(at, std::string::npos);
  // (Not std::string::insert: GCC 12 warns about it, a known false -Wrestrict.)
  text = text.substr(0, at + 11) + "1" + text.substr(at + 11);
  std::ofstream(changed) << text;
  const std::string foreign = message_of(changed.string());
  EXPECT_NE(foreign.find("written for a scene with hash"), std::string::npos) << foreign;
  EXPECT_NE(foreign.find(changed.string()), std::string::npos) << foreign;

  std::ofstream(bin, std::ios::binary | std::ios::trunc) << good.substr(0, good.size() / 2);
  const std::string truncated = message_of(scene);
  EXPECT_NE(truncated.find(bin + ": "), std::string::npos) << truncated;
  EXPECT_NE(truncated.find("truncated or damaged"), std::string::npos) << truncated;

  std::ofstream(bin, std::ios::binary | std::ios::trunc) << "time,lid\n0,0.012\n";
  const std::string other = message_of(scene);
  EXPECT_NE(other.find(bin + ": "), std::string::npos) << other;
  EXPECT_TRUE(other.find("not a darcydem checkpoint") != std::string::npos ||
              other.find("truncated or damaged") != std::string::npos)
      << other;
  fs::remove_all(dir);
}

}  // namespace
