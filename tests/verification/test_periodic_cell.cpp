// A deforming periodic cell (cell_motion.hpp; a stage's `periodic_cell`):
// its kinematics against the homogeneous field it imposes, its stress
// against the closed form of a square lattice of discs, its servo against
// the lattice spacing that carries the target stress, and a biaxial test of
// a random packing whose lateral stress the servo holds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <fmt/format.h>

#include "periodic_discs.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
using darcydem::testing::read_probes;
using darcydem::testing::scene_from_text;
using darcydem::testing::temp_dir;
using darcydem::testing::text_variant;

namespace {

// 10 x 10 discs of r = 0.5 mm on a square lattice of spacing 1 mm filling a
// 1 cm cell: each touches its four neighbours (across the ends too), with
// no overlap at the start. Restitution 1: no dashpot, so the forces are the
// springs' alone; no friction: the lattice stays square.
const std::string lattice = R"(
[simulation]
dimension = 2
time_step = "auto"
skin = 0.0002

[periodic]
x = [0.0, 0.01]
y = [0.0, 0.01]

[[material]]
name = "m"
density = 2650.0

[[contact]]
materials = ["m", "m"]
law = "linear"
normal_stiffness = 1e5
restitution = 1.0

[[particles]]
generator = "lattice"
material = "m"
min = [0.0, 0.0]
max = [0.01, 0.01]
radius = 0.0005

[output]
probe_interval = 0.01

[[probe]]
name = "Lx"
quantity = "cell_length"
component = "x"

[[probe]]
name = "Ly"
quantity = "cell_length"
component = "y"

[[probe]]
name = "sxx"
quantity = "cell_stress"
component = "xx"

[[probe]]
name = "syy"
quantity = "cell_stress"
component = "yy"

[[probe]]
name = "sxy"
quantity = "cell_stress"
component = "xy"

[[probe]]
name = "x7"
quantity = "particle_position"
particle = 7
component = "x"

[[probe]]
name = "y7"
quantity = "particle_position"
particle = 7
component = "y"

[[probe]]
name = "kinetic"
quantity = "kinetic_energy"

[[stage]]
name = "strain"
duration = 0.2
periodic_cell = { x = { strain_rate = -0.02 }, y = { strain_rate = -0.01 } }
)";

constexpr double k_n = 1e5;      // N/m
constexpr double radius = 5e-4;  // m

/// The lattice's stress along an axis where the spacing is a: one contact
/// per disc along it, force k_n (2r - a) on the branch a, over the area a
/// times the other spacing b per disc: k_n (2r - a) a / (a b).
double lattice_stress(double a, double b) { return a < 2.0 * radius ? k_n * (2.0 * radius - a) / b : 0.0; }

}  // namespace

// A set strain rate: the cell's lengths are (1 + rate dt)^n of the start,
// every disc keeps its place relative to the cell (its fluctuation stays
// zero by symmetry), and the stress is the lattice's closed form.
TEST(PeriodicCell, StrainedLatticeFollowsTheFieldAndItsStressIsTheClosedForm) {
  const std::string dir = temp_dir("cell_lattice");
  Scene<2> scene = scene_from_text<2>(dir, "lattice.toml", lattice);
  const double dt = scene.simulation.time_step;
  RunOptions options;
  options.out_dir = dir + "/out";
  const RunSummary summary = run_scene<2>(scene, options);
  ASSERT_EQ(summary.stages_completed.size(), 1U);
  const auto& sim = scene.simulation;
  const auto n = static_cast<double>(summary.steps);
  // The lengths: n products of (1 + rate dt), to round-off (1e-12: a few
  // thousand multiplications of numbers near 1).
  EXPECT_NEAR(sim.periodic.length[0] / (0.01 * std::pow(1.0 - 0.02 * dt, n)), 1.0, 1e-12);
  EXPECT_NEAR(sim.periodic.length[1] / (0.01 * std::pow(1.0 - 0.01 * dt, n)), 1.0, 1e-12);
  // Disc 7 starts at (7.5, 0.5) mm; relative to the cell's centre
  // (5, 5) mm it scales with the cell (1e-15 m: the drift's round-off over
  // the run, against the 8 um it has moved), wrapped into the cell.
  const double sx = sim.periodic.length[0] / 0.01;
  const double sy = sim.periodic.length[1] / 0.01;
  const Vec<2> x7 = sim.periodic.wrap(sim.particles.position[sim.particles.index_of(7)]);
  EXPECT_NEAR(x7[0], 0.005 + 0.0025 * sx, 1e-15);
  EXPECT_NEAR(x7[1], 0.005 - 0.0045 * sy, 1e-15);
  EXPECT_GT(0.0075 - x7[0], 8e-6);
  // The stress of the spacings the cell has now: relative 1e-9 (the
  // overlaps, 2r - a ~ 4e-6 m, are known to round-off of a, 1e-19 m).
  const double a = sim.periodic.length[0] / 10.0;
  const double b = sim.periodic.length[1] / 10.0;
  const auto stress = sim.cell_stress();
  EXPECT_NEAR(stress(0, 0) / lattice_stress(a, b), 1.0, 1e-9);
  EXPECT_NEAR(stress(1, 1) / lattice_stress(b, a), 1.0, 1e-9);
  EXPECT_NEAR(stress(0, 1), 0.0, 1e-9 * lattice_stress(a, b));
  // Every row of the probes: the same within 1e-6, as probes.csv prints
  // ten digits of the lengths, which leaves 2r - a good to about 3e-7.
  auto probes = read_probes(options.out_dir + "/probes.csv");
  for (std::size_t r = 1; r < probes["time"].size(); ++r) {
    const double ar = probes["Lx"][r] / 10.0;
    const double br = probes["Ly"][r] / 10.0;
    ASSERT_NEAR(probes["sxx"][r], lattice_stress(ar, br), 1e-6 * lattice_stress(ar, br)) << "row " << r;
    ASSERT_NEAR(probes["syy"][r], lattice_stress(br, ar), 1e-6 * lattice_stress(br, ar)) << "row " << r;
    // No fluctuation: the kinetic energy of the motion about the field is
    // round-off (the field's own, 1/2 m (rate L/2)^2 per disc, is 1e-13 J).
    ASSERT_LT(probes["kinetic"][r], 1e-20) << "row " << r;
  }
  // It has been compressed: 0.4 % along x, 0.2 % along y.
  EXPECT_GT(stress(0, 0), 300.0);
  std::filesystem::remove_all(dir);
}

// The cell_strain probe counts from each stage's start: the lattice
// strained at -0.02 and -0.01 /s for 0.2 s, then stretched along x at
// 0.03 /s with y held for 0.1 s. Along each axis it is the integral of
// the set rate over the stage, rate x (t - t_stage) (sum of ln(1 + rate
// dt) over the drifts: the two differ by rate dt / 2, 1e-8 relative, and
// probes.csv prints ten digits: 1e-6 relative); the volumetric strain is
// their sum. Stopped in the second stage and resumed, the run writes the
// same probes byte for byte: the reference comes back from the checkpoint.
TEST(PeriodicCell, CellStrainCountsFromTheStagesStartAndSurvivesAResume) {
  const std::string dir = temp_dir("cell_strain");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/lattice.toml";
  std::ofstream(path) << text_variant(lattice, {{"[[stage]]", R"([[probe]]
name = "ex"
quantity = "cell_strain"
component = "x"

[[probe]]
name = "ey"
quantity = "cell_strain"
component = "y"

[[probe]]
name = "ev"
quantity = "cell_strain"
component = "volumetric"

[[stage]])"}}) + R"(
[[stage]]
name = "stretch"
duration = 0.1
periodic_cell = { x = { strain_rate = 0.03 }, y = { strain_rate = 0.0 } }
)";
  std::ostringstream log;
  auto run = [&](const std::string& out, std::uint64_t stop, bool resume) {
    Scene<2> scene = darcydem::testing::load_scene_file<2>(path);
    RunOptions options;
    options.out_dir = out;
    options.stop_at_step = stop;
    options.resume = resume;
    options.log = &log;
    return run_scene<2>(scene, options);
  };
  const RunSummary whole = run(dir + "/whole", 0, false);
  ASSERT_EQ(whole.stages_completed.size(), 2U);
  auto probes = read_probes(dir + "/whole/probes.csv");
  const auto& t = probes["time"];
  // The first stage ends after its whole steps, round(0.2 / dt); its last
  // row is written before the second begins.
  const double dt = darcydem::testing::load_scene_file<2>(path).simulation.time_step;
  const double t1 = std::round(0.2 / dt) * dt;
  // The run log gives each stage's strains at its end, rate x its length
  // (six digits; the seventh of these is far from a rounding's edge).
  const double t2 = std::round(0.1 / dt) * dt;
  for (const std::string& line :
       {fmt::format("strains {:.6g}, {:.6g} over the stage (volumetric {:.6g})", -0.02 * t1, -0.01 * t1,
                    -0.03 * t1),
        fmt::format("strains {:.6g}, 0 over the stage (volumetric {:.6g})", 0.03 * t2, 0.03 * t2)}) {
    EXPECT_NE(log.str().find(line), std::string::npos) << line << "\n" << log.str();
  }
  std::size_t first = 0;
  std::size_t second = 0;
  for (std::size_t r = 0; r < t.size(); ++r) {
    const bool stretching = t[r] > t1 + 1e-3 * dt;
    const double rx = stretching ? 0.03 : -0.02;
    const double ry = stretching ? 0.0 : -0.01;
    const double since = stretching ? t[r] - t1 : t[r];
    const double ex = rx * since;
    const double ey = ry * since;
    ASSERT_NEAR(probes["ex"][r], ex, 1e-6 * std::abs(ex) + 1e-15) << "t = " << t[r];
    ASSERT_NEAR(probes["ey"][r], ey, 1e-6 * std::abs(ey) + 1e-15) << "t = " << t[r];
    ASSERT_NEAR(probes["ev"][r], ex + ey, 1e-6 * std::abs(ex + ey) + 1e-15) << "t = " << t[r];
    ++(stretching ? second : first);
  }
  EXPECT_GE(first, 20U);
  EXPECT_GE(second, 10U);
  // Half way through the second stage, stopped and resumed.
  const RunSummary part = run(dir + "/parts", whole.steps * 5 / 6, false);
  ASSERT_TRUE(part.interrupted);
  run(dir + "/parts", 0, true);
  EXPECT_EQ(darcydem::testing::file_contents(dir + "/parts/probes.csv"),
            darcydem::testing::file_contents(dir + "/whole/probes.csv"));
  std::filesystem::remove_all(dir);
}

// With dashpots (restitution 0.5) the cell's strain rate is also each
// contact's rate of approach, rate x a along x: the dashpot adds
// gamma sqrt(m_eff k_n) (-rate) a to the spring's force, m_eff = m / 2 (a
// viscous stress, compressive while the cell shrinks), a the spacing.
TEST(PeriodicCell, StrainedLatticeWithDashpotsCarriesTheirViscousStress) {
  const std::string dir = temp_dir("cell_dashpots");
  Scene<2> scene = scene_from_text<2>(dir, "lattice.toml",
                                      text_variant(lattice, {{"restitution = 1.0", "restitution = 0.5"}}));
  RunOptions options;
  options.out_dir = dir + "/out";
  run_scene<2>(scene, options);
  const auto& sim = scene.simulation;
  const double a = sim.periodic.length[0] / 10.0;
  const double b = sim.periodic.length[1] / 10.0;
  const double mass = 2650.0 * M_PI * radius * radius;  // kg per metre
  const auto& pair = sim.contact_table(0, 0);
  const double c = pair.normal_damping * std::sqrt(0.5 * mass * k_n);  // N s/m
  const double viscous_x = c * 0.02 * a / b;
  const double viscous_y = c * 0.01 * b / a;
  const auto stress = sim.cell_stress();
  // Relative 1e-9, as the springs' alone; the dashpots' share is some
  // 2e-4 of it, so a field's share of the wrong sign or left out is 2e-4
  // to 4e-4 off.
  EXPECT_NEAR(stress(0, 0) / (lattice_stress(a, b) + viscous_x), 1.0, 1e-9);
  EXPECT_NEAR(stress(1, 1) / (lattice_stress(b, a) + viscous_y), 1.0, 1e-9);
  EXPECT_GT(viscous_x / lattice_stress(a, b), 1e-4);
  std::filesystem::remove_all(dir);
}

// The energy budget: the cell's work on the contacts is its boundary work.
// Without dashpots it is all stored in the springs (the budget's contact
// dissipation stays zero); with them, the dashpots take
// c (rate a)^2 per contact along each axis, 100 contacts each way.
TEST(PeriodicCell, TheCellsWorkIsStoredInTheSpringsOrTakenByTheDashpots) {
  const std::string with_budget = text_variant(
      lattice, {{"name = \"kinetic\"\nquantity = \"kinetic_energy\"",
                 "name = \"kinetic\"\nquantity = \"kinetic_energy\"\n\n[[probe]]\nname = \"work\"\n"
                 "quantity = \"boundary_work\""}});
  for (const double restitution : {1.0, 0.5}) {
    const std::string dir = temp_dir("cell_energy");
    Scene<2> scene = scene_from_text<2>(
        dir, "lattice.toml",
        text_variant(with_budget, {{"restitution = 1.0", fmt::format("restitution = {}", restitution)}}));
    ASSERT_TRUE(scene.simulation.track_energy);
    RunOptions options;
    options.out_dir = dir + "/out";
    const RunSummary summary = run_scene<2>(scene, options);
    const auto& sim = scene.simulation;
    const double work = sim.energy.boundary_work;
    const double elastic = sim.elastic_energy();
    // The springs hold 1/2 k_n (2r - a)^2 per contact (none at the start).
    const double a = sim.periodic.length[0] / 10.0;
    const double b = sim.periodic.length[1] / 10.0;
    EXPECT_NEAR(elastic, 50.0 * k_n * (std::pow(2.0 * radius - a, 2) + std::pow(2.0 * radius - b, 2)),
                1e-9 * elastic);
    if (restitution == 1.0) {
      // The work over each drift is the field's displacement of each pair
      // times the mean of its force before and after: for a linear spring,
      // exactly the change of its energy, so the two agree to round-off.
      EXPECT_NEAR(work / elastic, 1.0, 1e-9);
      EXPECT_NEAR(sim.contact_dissipation(), 0.0, 1e-9 * work);
    } else {
      const double mass = 2650.0 * M_PI * radius * radius;
      const double c = sim.contact_table(0, 0).normal_damping * std::sqrt(0.5 * mass * k_n);
      const double t = static_cast<double>(summary.steps) * sim.time_step;
      // a^2 and b^2 change by 0.8 % and 0.4 % over the run, linearly to
      // 1e-5: their means are those of the two ends.
      const double a2 = 0.5 * (1e-6 + a * a);
      const double b2 = 0.5 * (1e-6 + b * b);
      const double dissipated = 100.0 * c * t * (0.02 * 0.02 * a2 + 0.01 * 0.01 * b2);
      EXPECT_NEAR(sim.contact_dissipation() / dissipated, 1.0, 1e-4);
    }
    std::filesystem::remove_all(dir);
  }
}

// The servo: held at 2 kPa along x and 1 kPa along y, the lattice closes to
// the spacings whose springs carry them.
TEST(PeriodicCell, ServoBringsTheLatticeToTheSpacingOfItsTargetStress) {
  const std::string dir = temp_dir("cell_servo");
  const std::string text = text_variant(
      lattice,
      {{"duration = 0.2\nperiodic_cell = { x = { strain_rate = -0.02 }, y = { strain_rate = -0.01 } }",
        "duration = 0.6\nperiodic_cell = { x = { stress = 2000.0 }, y = { stress = 1000.0 }, gain = 1e-3, "
        "max_strain_rate = 0.2 }"}});
  Scene<2> scene = scene_from_text<2>(dir, "servo.toml", text);
  RunOptions options;
  options.out_dir = dir + "/out";
  run_scene<2>(scene, options);
  auto probes = read_probes(options.out_dir + "/probes.csv");
  const double a = probes["Lx"].back() / 10.0;
  const double b = probes["Ly"].back() / 10.0;
  // The servo's own measure: the targets reached to 1e-6 (the servo's
  // time constant, 1/(gain k_n / b) ~ 1e-5 s, is far below the run).
  EXPECT_NEAR(lattice_stress(a, b), 2000.0, 2e-3);
  EXPECT_NEAR(lattice_stress(b, a), 1000.0, 1e-3);
  EXPECT_NEAR(probes["sxx"].back(), 2000.0, 2e-3);
  EXPECT_NEAR(probes["syy"].back(), 1000.0, 1e-3);
  // The spacings that carry the targets: k_n (2r - a) = 2000 b and
  // k_n (2r - b) = 1000 a, a linear system in a and b (Cramer's rule).
  const double A11 = k_n, A12 = 2000.0, A21 = 1000.0, A22 = k_n;
  const double det = A11 * A22 - A12 * A21;
  const double a_star = (2.0 * radius * k_n * A22 - A12 * 2.0 * radius * k_n) / det;
  const double b_star = (A11 * 2.0 * radius * k_n - A21 * 2.0 * radius * k_n) / det;
  EXPECT_NEAR(a / a_star, 1.0, 1e-9);
  EXPECT_NEAR(b / b_star, 1.0, 1e-9);
  std::filesystem::remove_all(dir);
}

namespace {

/// The message a scene is refused with ("" if it loads).
std::string refusal(const std::string& text) {
  const std::string dir = temp_dir("cell_refusal");
  try {
    scene_from_text<2>(dir, "bad.toml", text);
  } catch (const std::exception& e) {
    std::filesystem::remove_all(dir);
    return e.what();
  }
  std::filesystem::remove_all(dir);
  return "";
}

}  // namespace

TEST(PeriodicCell, BadCellsAreRefusedWithFileLineAndKey) {
  ASSERT_EQ(refusal(lattice), "");
  const std::string rates = "periodic_cell = { x = { strain_rate = -0.02 }, y = { strain_rate = -0.01 } }";
  auto refused = [&](const std::string& text, const std::string& expected) {
    const std::string msg = refusal(text);
    EXPECT_NE(msg.find("bad.toml:"), std::string::npos) << msg;
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  };
  // Every axis must repeat (here y does not): the stage's refusal, and
  // with the cell's probes theirs, which come first.
  const std::string no_y = text_variant(lattice, {{"y = [0.0, 0.01]\n", ""}});
  refused(
      no_y.substr(0, no_y.find("[[probe]]")) + no_y.substr(no_y.find("[[stage]]")),
      "key 'periodic_cell': deforms the periodic cell, which must repeat along every axis; [periodic] has "
      "no 'y'");
  refused(no_y,
          "key 'quantity': \"cell_length\" reads the periodic cell, which must repeat along every axis: "
          "[periodic] has no 'y'");
  refused(
      text_variant(lattice, {{"x = { strain_rate = -0.02 }", "x = { strain_rate = -0.02, stress = 1.0 }"}}),
      "needs either 'strain_rate' (1/s, negative: the cell shrinks along the axis) or 'stress'");
  refused(text_variant(lattice, {{"x = { strain_rate = -0.02 }", "x = { stress = 2000.0 }"}}), "'gain'");
  refused(text_variant(lattice, {{"x = { strain_rate = -0.02 }", "x = { stress = 2000.0 }, gain = 1e-3"}}),
          "'max_strain_rate'");
  refused(text_variant(lattice, {{"x = { strain_rate = -0.02 }", "x = { strain_rate = -1e6 }"}}),
          "periodic_cell.x key 'strain_rate': must be below 1e-3 / time step");
  refused(text_variant(lattice, {{rates, rates + "\n\n[[stage]]\nduration = 0.1\nperiodic_cell = 3"}}),
          "key 'periodic_cell': must be a table");
  refused(text_variant(lattice, {{rates, "periodic_cell = { z = { strain_rate = 1.0 } }"}}),
          "unknown key 'z'");
  // The total stress needs pore water to add.
  refused(
      text_variant(lattice, {{rates, "periodic_cell = { x = { strain_rate = -0.02 }, load = \"total\" }"}}),
      "periodic_cell key 'load': \"total\" adds the pore water's mean pressure to the contacts' stress, "
      "which needs a [fluid]");
  // cell_strain: an axis the scene has, or volumetric.
  const std::string strain_probe = "[[probe]]\nname = \"ez\"\nquantity = \"cell_strain\"\ncomponent = ";
  refused(text_variant(lattice, {{"[[stage]]", strain_probe + "\"z\"\n\n[[stage]]"}}),
          "key 'component': \"z\" is not allowed; one of \"x\", \"y\", \"volumetric\"");
  // The cell's probes need a cell.
  refused(text_variant(lattice, {{"[periodic]\nx = [0.0, 0.01]\ny = [0.0, 0.01]\n", ""}, {"\n" + rates, ""}}),
          "key 'quantity': \"cell_length\" reads the periodic cell, which must repeat along every axis");
}

namespace {

// 150 discs (r = 0.4-0.6 mm) in a periodic 17 mm square, compressed by the
// servo to 1 kPa with low friction, then sheared biaxially: shortened along
// y at 0.5 /s with x held at 1 kPa. Shared with the checkpoint test.
const std::string biaxial = darcydem::testing::periodic_discs + R"([output]
probe_interval = 0.002

[[probe]]
name = "sxx"
quantity = "cell_stress"
component = "xx"

[[probe]]
name = "syy"
quantity = "cell_stress"
component = "yy"

[[probe]]
name = "p"
quantity = "cell_stress"
component = "mean"

[[probe]]
name = "rate_x"
quantity = "cell_strain_rate"
component = "x"

[[probe]]
name = "rate_y"
quantity = "cell_strain_rate"
component = "y"

[[stage]]
name = "compress"
duration = 0.5
local_damping = 0.3
contacts = [{ materials = ["sand", "sand"], friction = 0.1 }]
periodic_cell = { x = { stress = 1000.0 }, y = { stress = 1000.0 }, gain = 2e-2, max_strain_rate = 5.0 }
stop_when = { probe = "p", above = 990.0 }

[[stage]]
name = "settle"
duration = 0.05

[[stage]]
name = "shear"
duration = 0.1
contacts = [{ materials = ["sand", "sand"], friction = 0.5 }]
periodic_cell = { y = { strain_rate = -0.5 } }
)";

}  // namespace

// A random packing: the servo brings both normal stresses to the target and
// holds the lateral one through a biaxial compression, whose peak has the
// strength of a frictional packing of discs.
TEST(PeriodicCell, ServoHoldsTheLateralStressOfABiaxialTest) {
  const std::string dir = temp_dir("cell_biaxial");
  Scene<2> scene = scene_from_text<2>(dir, "biaxial.toml", biaxial);
  RunOptions options;
  options.out_dir = dir + "/out";
  const RunSummary summary = run_scene<2>(scene, options);
  ASSERT_EQ(summary.stages_completed.size(), 3U);
  auto probes = read_probes(options.out_dir + "/probes.csv");
  const auto& t = probes["time"];
  // The shear stage sets y's rate to -0.5 /s; the row before the first
  // with it is the settled state.
  std::size_t shear = 0;
  while (shear < t.size() && probes["rate_y"][shear] != -0.5) ++shear;
  ASSERT_GT(shear, 1U);
  ASSERT_LT(shear + 20, t.size());
  const std::size_t at_settled = shear - 1;
  // Settled: both stresses at the target within 1 Pa. At rest the
  // servo's error is its rate / gain, and 0.05 s is some hundred of its
  // time constants 1 / (gain x the packing's stiffness, ~1e5 Pa).
  EXPECT_NEAR(probes["sxx"][at_settled], 1000.0, 1.0);
  EXPECT_NEAR(probes["syy"][at_settled], 1000.0, 1.0);
  // Sheared: the lateral stress stays within 12.5 % of its target, while
  // the axial one climbs to nearly three times it. The proportional servo lags by
  // rate / gain, and the sample widens in bursts: 1.1 /s at most in the
  // release build and 1.6 /s in the sanitizers' (their round-off differs and
  // the packing's history with it), 55 and 81 Pa. Bursts up to 2.5 /s fit.
  double peak = 0.0;
  double lateral_at_peak = 0.0;
  for (std::size_t r = shear; r < t.size(); ++r) {
    EXPECT_NEAR(probes["sxx"][r], 1000.0, 125.0) << "t = " << t[r];
    if (probes["syy"][r] > peak) {
      peak = probes["syy"][r];
      lateral_at_peak = probes["sxx"][r];
    }
  }
  // The peak's mobilised friction, sin(phi) = (s1 - s3) / (s1 + s3): for
  // assemblies of discs with a contact friction of 0.5, 20 to 30 degrees
  // (sin 0.34 to 0.5) is what biaxial tests of such packings give (0.45
  // and 0.47 in the two builds); a stress off by the cell's area falls
  // outside.
  const double sin_phi = (peak - lateral_at_peak) / (peak + lateral_at_peak);
  EXPECT_GT(sin_phi, 0.3);
  EXPECT_LT(sin_phi, 0.55);
  EXPECT_GT(peak, 1500.0);
  std::filesystem::remove_all(dir);
}

// The servo's stress, summed pair by pair inside the force pass, against
// the same stress from each pair's recorded force (the path the energy
// budget takes, which the lattice tests check against the closed form):
// a random packing compressed by the servo, and every 500 steps a copy of
// it takes one step with the budget while it takes one without. Each row
// adds its pairs in the same order and the rows are added in the same
// fixed blocks, so the two agree to round-off. Both force passes: the
// batched one of linear contacts, and the general one (rolling resistance).
class ServoStressPaths : public ::testing::TestWithParam<bool> {};

TEST_P(ServoStressPaths, SummedInTheForcePassItIsTheRecordedForcesOne) {
  const std::string dir = temp_dir("cell_row_sums");
  const std::string text =
      GetParam()
          ? text_variant(biaxial, {{"friction = 0.5\n\n", "friction = 0.5\nrolling_friction = 0.1\n\n"}})
          : biaxial;
  Scene<2> scene = scene_from_text<2>(dir, "biaxial.toml", text);
  ASSERT_TRUE(scene.stages.at(0).cell.has_value());
  Simulation<2>& sim = scene.simulation;
  scene.stages[0].cell->apply(sim.cell_motion);
  double largest = 0.0;
  int compared = 0;
  for (int step = 0; step < 20000; ++step) {
    if (step % 500 != 499) {
      sim.advance(1);
      continue;
    }
    Simulation<2> recorded = sim;
    recorded.track_energy = true;
    sim.advance(1);
    recorded.advance(1);
    // A relative 1e-12 of the stress is far above the round-off of a sum
    // of a few hundred terms (1e-14) and far below one pair missed or
    // counted twice (one pair of 300 is some 3e-3). The servo's rate is
    // gain x (stress - target): near the target a small difference, whose
    // round-off is gain x the stress's, so its bound is gain x 1e-12 of
    // the stress. (The release build gives both bit for bit; the
    // sanitizers' build contracts multiply-adds differently in the two
    // sums, and the rates then differed by 5e-15 /s, 2e-16 of gain x
    // stress, while 1e-12 of the rate itself was too tight near the target.)
    const double gain = recorded.cell_motion.gain;
    for (int k = 0; k < 2; ++k) {
      const double s = recorded.cell_motion.stress[k];
      EXPECT_NEAR(sim.cell_motion.stress[k], s, 1e-12 * std::abs(s)) << "axis " << k << " at step " << step;
      const double r = recorded.cell_motion.strain_rate[k];
      EXPECT_NEAR(sim.cell_motion.strain_rate[k], r, 1e-12 * gain * std::abs(s))
          << "axis " << k << " at step " << step;
    }
    largest = std::max(largest, std::abs(recorded.cell_motion.stress.x()));
    ++compared;
  }
  EXPECT_EQ(compared, 40);
  // The servo has had something to do: the packing reached its target's
  // order (1 kPa) and pushed back.
  EXPECT_GT(largest, 500.0);
  std::filesystem::remove_all(dir);
}

INSTANTIATE_TEST_SUITE_P(PeriodicCell, ServoStressPaths, ::testing::Values(false, true),
                         [](const auto& info) { return info.param ? "RollingResistance" : "LinearBatched"; });

// Stopped while the servo compresses the cell and resumed from the
// checkpoint, the run writes the same files byte for byte as the run that
// never stopped: the periods, rates and servo state come back exactly.
TEST(PeriodicCell, ResumedBiaxialTestWritesTheSameFiles) {
  const std::string dir = temp_dir("cell_resume");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/biaxial.toml";
  std::ofstream(path) << text_variant(biaxial, {{"duration = 0.1\ncontacts", "duration = 0.02\ncontacts"}});
  auto run = [&](const std::string& out, std::uint64_t stop, bool resume) {
    Scene<2> scene = darcydem::testing::load_scene_file<2>(path);
    scene.simulation.sort_threshold = 0;  // every build reorders the grains
    RunOptions options;
    options.out_dir = out;
    options.stop_at_step = stop;
    options.resume = resume;
    return run_scene<2>(scene, options);
  };
  const RunSummary whole = run(dir + "/whole", 0, false);
  ASSERT_EQ(whole.stages_completed.size(), 3U);
  const RunSummary first = run(dir + "/parts", whole.steps / 3, false);
  ASSERT_TRUE(first.interrupted);
  const RunSummary last = run(dir + "/parts", 0, true);
  EXPECT_EQ(last.steps, whole.steps);
  std::size_t compared = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/whole")) {
    const std::string name = e.path().filename().string();
    if (name == "run.json") continue;  // wall times
    EXPECT_EQ(darcydem::testing::file_contents(dir + "/parts/" + name),
              darcydem::testing::file_contents(e.path().string()))
        << name;
    ++compared;
  }
  EXPECT_GT(compared, 3U);
  std::filesystem::remove_all(dir);
}

// A cell shrunk below twice the contacts' reach (where a grain would meet
// two images of a neighbour) stops the run with a message, its output kept.
TEST(PeriodicCell, ACellShrunkTooFarStopsTheRunKeepingItsOutput) {
  const std::string dir = temp_dir("cell_shrunk");
  // Four discs 2 mm apart, the cell shrinking at 0.9 /s from 10 mm: below
  // 2 (2 r + skin) = 2.4 mm after ln(10 / 2.4) / 0.9 = 1.59 s.
  Scene<2> scene = scene_from_text<2>(
      dir, "shrink.toml",
      text_variant(lattice, {{"max = [0.01, 0.01]\nradius = 0.0005",
                              "max = [0.004, 0.004]\nradius = 0.0005\n"
                              "spacing = 0.002"},
                             {"particle = 7\ncomponent = \"x\"", "particle = 3\ncomponent = \"x\""},
                             {"particle = 7\ncomponent = \"y\"", "particle = 3\ncomponent = \"y\""},
                             {"duration = 0.2", "duration = 3.0"},
                             {"x = { strain_rate = -0.02 }, y = { strain_rate = -0.01 }",
                              "x = { strain_rate = -0.9 }, y = { strain_rate = -0.9 }"}}));
  RunOptions options;
  options.out_dir = dir + "/out";
  std::string message;
  try {
    run_scene<2>(scene, options);
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  EXPECT_NE(message.find("the periodic cell has shrunk along x to"), std::string::npos) << message;
  EXPECT_NE(message.find("output written so far is kept"), std::string::npos) << message;
  const auto probes = read_probes(options.out_dir + "/probes.csv");
  ASSERT_FALSE(probes.at("time").empty());
  // It stopped at the first list build once the period was below 2.4 mm,
  // at about 1.59 s (the builds come every skin / (2 x 0.9 /s x 1.2 mm),
  // about 0.1 s, apart at the end).
  EXPECT_NEAR(probes.at("time").back(), std::log(10.0 / 2.4) / 0.9, 0.1);
  EXPECT_LT(probes.at("Lx").back(), 2.4e-3);
  std::filesystem::remove_all(dir);
}

namespace {

/// The probes of an example of examples/dem_cases run whole, its shear
/// stopped at `below` of axial strain instead of `stop` (its three stages
/// completed).
auto run_example_shear(const std::string& name, const std::string& stop, const std::string& below) {
  const std::string dir = temp_dir("cell_example");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << darcydem::testing::scene_variant("examples/dem_cases/" + name,
                                                          {{"below = " + stop, "below = " + below}});
  Scene<3> scene = darcydem::testing::load_scene_file<3>(path);
  RunOptions options;
  options.out_dir = dir + "/out";
  const RunSummary summary = run_scene<3>(scene, options);
  EXPECT_EQ(summary.stages_completed.size(), 3U);
  auto probes = read_probes(options.out_dir + "/probes.csv");
  std::filesystem::remove_all(dir);
  return probes;
}

}  // namespace

// examples/dem_cases/periodic_triaxial.toml, its shear cut to 0.01 s (1 %
// of axial strain): compressed to 100 kPa and settled, the three normal
// stresses are the target's; shortened along z, its axial stress climbs
// while the servo holds the lateral ones.
TEST(PeriodicCell, TriaxialExampleReachesItsConfinementAndLoadsAxially) {
  auto probes = run_example_shear("periodic_triaxial.toml", "-0.1", "-0.01");
  ASSERT_GT(probes["time"].size(), 3U);
  const auto& lz = probes["Lz"];
  // The shear takes the last 0.01 s; the last row 0.0105 s before the end
  // is the settled sample, held at 100 kPa for the 0.02 s before.
  std::size_t settled = 0;
  for (std::size_t r = 1; r < lz.size(); ++r) {
    if (probes["time"][r] > probes["time"].back() - 0.0105) break;
    settled = r;
  }
  for (const char* s : {"sxx", "syy", "szz"}) EXPECT_NEAR(probes[s][settled], 1e5, 1e3) << s;
  // 1 % of axial strain later: the axial stress well above the lateral
  // ones (a dense packing's stiffness, some 10 MPa, times 1 %), the
  // lateral within 10 % of the confinement.
  EXPECT_GT(probes["szz"].back(), 1.3e5);
  EXPECT_NEAR(probes["sxx"].back(), 1e5, 1e4);
  EXPECT_NEAR(probes["syy"].back(), 1e5, 1e4);
  // The stage stopped once its axial strain passed -1 % (not at its 0.2 s), at a check
  // (every 100 steps of 0.29 us: 3e-5 of strain at 1 /s), and the strain
  // is the log of the shortening.
  EXPECT_LT(probes["ez"].back(), -0.01);
  EXPECT_GT(probes["ez"].back(), -0.01 - 1e-4);
  EXPECT_NEAR(probes["ez"].back(), std::log(lz.back() / lz[settled]), 1e-8);
}

// The constant-volume (undrained) example, its shear cut to 1 % of axial
// strain: the volume stays put while the cell shortens along z and widens
// along x and y, and the effective stresses take a frictional packing's
// undrained path.
TEST(PeriodicCell, UndrainedExampleShearsAtConstantVolume) {
  auto probes = run_example_shear("periodic_undrained.toml", "-0.05", "-0.01");
  const auto& t = probes["time"];
  // The shear's rows: those after the settled state, where ez has begun
  // to fall (the settle stage's own strains are the servo's, below 1e-4).
  std::size_t shear = t.size();
  for (std::size_t r = t.size(); r-- > 0;) {
    if (probes["ez"][r] > -1e-3) break;
    shear = r;
  }
  ASSERT_LT(shear + 3, t.size());
  // Constant volume through the shear: the rates sum to zero, so each
  // step's volume changes by (1 + 0.5 dt)^2 (1 - dt), -0.75 dt^2, 1e-8
  // over the stage; 1e-7 leaves room for the ten printed digits. A rate
  // off by a tenth along one axis gives 5e-4.
  for (std::size_t r = shear; r < t.size(); ++r) ASSERT_NEAR(probes["ev"][r], 0.0, 1e-7) << "t = " << t[r];
  EXPECT_LT(probes["ez"].back(), -0.01);
  EXPECT_GT(probes["ez"].back(), -0.01 - 1e-4);
  // The lateral axes are strained alike: their stresses within 15 % of
  // each other (400 grains: the fabric is not quite isotropic; 5 % at the
  // end of the measured run).
  const double sxx = probes["sxx"].back();
  const double syy = probes["syy"].back();
  const double szz = probes["szz"].back();
  EXPECT_NEAR(sxx / syy, 1.0, 0.15);
  // The effective stress ratio q / p' has climbed to a frictional
  // packing's: M = 6 sin(phi) / (3 - sin(phi)) is 0.77 to 1.2 for friction
  // angles of 20 to 30 degrees, those of sphere packings with a contact
  // friction of 0.5 (the drained example peaks at 24.5 degrees).
  const double p = (sxx + syy + szz) / 3.0;
  const double q = szz - 0.5 * (sxx + syy);
  EXPECT_GT(q / p, 0.77);
  EXPECT_LT(q / p, 1.2);
}
