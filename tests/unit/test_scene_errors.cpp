// Strict scene input: each bad scene is refused with a message that names
// the file, the line, the key and what is allowed.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include <unistd.h>

#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/runner.hpp"
#include "good_scene.hpp"

namespace darcydem {
namespace {

const char* kGood = kGoodScene;

std::string write_scene(const std::string& text) {
  static int counter = 0;
  const auto path = std::filesystem::temp_directory_path() / ("darcydem_scene_" + std::to_string(::getpid()) +
                                                              "_" + std::to_string(counter++) + ".toml");
  std::ofstream(path) << text;
  return path.string();
}

/// Builds the scene and returns the error message ("" if it loaded).
std::string load_error(const std::string& text) {
  const std::string path = write_scene(text);
  try {
    std::string t;
    const auto root = parse_toml_file(path, t);
    if (scene_dimension(root, path) == 2) {
      build_scene<2>(root, path, t);
    } else {
      build_scene<3>(root, path, t);
    }
  } catch (const SceneError& e) {
    std::filesystem::remove(path);
    return e.what();
  }
  std::filesystem::remove(path);
  return "";
}

/// Builds a scene that loads (check it with load_error first), to read what it holds.
template <int D>
Scene<D> built_scene(const std::string& text) {
  const std::string path = write_scene(text);
  std::string t;
  auto scene = build_scene<D>(parse_toml_file(path, t), path, t);
  std::filesystem::remove(path);
  return scene;
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

/// kGood with a stage that bonds the touching grains, its contact's
/// "friction = 0.5" line replaced by `contact` (e.g. with a bond).
std::string bonding_scene(const std::string& contact = "friction = 0.5") {
  const std::string bonding =
      replace(std::string(kGood), "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nmake_bonds = true");
  return replace(bonding, "friction = 0.5", contact);
}

/// kGood (or a variant of it) as a 3D scene: its floor, column and gravity
/// along z.
std::string in_3d(const std::string& scene) {
  std::string text = replace(scene, "dimension = 2", "dimension = 3");
  text = replace(text, "point = [0.0, 0.0]", "point = [0.0, 0.0, 0.0]");
  text = replace(text, "normal = [0.0, 1.0]", "normal = [0.0, 0.0, 1.0]");
  text = replace(text, "base = [0.0, 0.0]", "base = [0.0, 0.0, 0.0]");
  return replace(text, "gravity = [0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]");
}

TEST(SceneErrors, GoodSceneLoads) { EXPECT_EQ(load_error(kGood), ""); }

TEST(SceneErrors, UnknownKeySuggestsTheNearOne) {
  const auto msg = load_error(replace(kGood, "density = 2650.0", "densty = 2650.0"));
  {
    EXPECT_NE(msg.find(":8:10: error"), std::string::npos) << msg;  // file:line:column
    EXPECT_NE(msg.find("unknown key 'densty'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Did you mean 'density'?"), std::string::npos) << msg;
  }
}

TEST(SceneErrors, WrongTypeIsNamed) {
  const auto msg = load_error(replace(kGood, "count = 3", "count = \"three\""));
  EXPECT_NE(msg.find("key 'count': must be an integer, got a string"), std::string::npos) << msg;
  EXPECT_NE(msg.find(":27:9:"), std::string::npos) << msg;
}

TEST(SceneErrors, MissingRequiredValue) {
  const auto msg = load_error(replace(kGood, "restitution = 0.5\n", ""));
  EXPECT_NE(msg.find("missing required key 'restitution'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("[[contact]] #1"), std::string::npos) << msg;
}

// TOML spells nan and inf; a scene key never means either. Before the
// reader refused them, base = [nan, nan] loaded and the run stopped at its
// first step with "a particle position is not finite", naming no file.
TEST(SceneErrors, NonFiniteNumbersAreRefusedWhereTheyStand) {
  auto msg = load_error(replace(kGood, "base = [0.0, 0.0]", "base = [0.0, nan]"));
  EXPECT_NE(
      msg.find(":26:8: error: [[particles]] #1 key 'base': must be an array of 2 finite numbers, got nan "
               "at element 2"),
      std::string::npos)
      << msg;
  msg = load_error(replace(kGood, "radius = 0.0005", "radius = inf"));
  EXPECT_NE(msg.find(":28:10: error: [[particles]] #1 key 'radius': must be a finite number, got inf"),
            std::string::npos)
      << msg;
  msg = load_error(replace(kGood, "duration = 0.01", "duration = -inf"));
  EXPECT_NE(msg.find("key 'duration': must be a finite number, got -inf"), std::string::npos) << msg;
  msg = load_error(replace(kGood, "gravity = [0.0, -9.81]", "gravity = [nan, -9.81]"));
  EXPECT_NE(msg.find("key 'gravity': must be an array of 2 finite numbers, got nan at element 1"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, ParticleCountsNoMemoryCouldHoldAreRefusedBeforeTheyAreMade) {
  // 2e12 particles at 256 bytes each are 512 TB, more than any machine
  // this runs on; `check` used to try to make them (2^31 - 1 ran out of
  // its 60 s under a fuzzer).
  auto msg = load_error(replace(kGood, "count = 3", "count = 2000000000000"));
  EXPECT_NE(
      msg.find(":27:9: error: [[particles]] #1 key 'count': 2e+12 particles would need at least 5.12e+05 GB "
               "(256 bytes each), more than this machine's"),
      std::string::npos)
      << msg;
  // A lattice's sites, from its box and spacing: (0.999 m / 2 um + 1) (1 m / 2 um + 1) = 2.498e11.
  const std::string lattice =
      "generator = \"lattice\"\nmaterial = \"sand\"\nmin = [0.0, 0.001]\nmax = [1.0, 1.0]\nspacing = 2e-6\n"
      "radius = 1e-6\n";
  msg = load_error(
      replace(kGood,
              "generator = \"column\"\nmaterial = \"sand\"\nbase = [0.0, 0.0]\ncount = 3\nradius = "
              "0.0005\n",
              lattice));
  EXPECT_NE(msg.find("key 'spacing': 2.498e+11 particles would need at least"), std::string::npos) << msg;
}

TEST(SceneErrors, ViscousDampingTheExplicitStepCannotTakeIsRefused) {
  // Each half kick scales the velocity by 1 - c dt/2: from c dt = 2 on it
  // reverses it. 1e30 1/s made the run blow up; 1e3 1/s is far below 2/dt.
  const std::string stage = "gravity = [0.0, -9.81]\n";
  ASSERT_EQ(load_error(replace(kGood, stage, stage + "viscous_damping = 1e3\n")), "");
  const auto msg = load_error(replace(kGood, stage, stage + "viscous_damping = 1e30\n"));
  EXPECT_NE(msg.find(":34:19: error: [[stage]] #1 key 'viscous_damping': must be below 2 / time step = "),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("got 1e+30"), std::string::npos) << msg;
}

TEST(SceneErrors, AGeneratorThatPlacesParticlesAtInfinityIsRefused) {
  // Three discs of radius 1e308 in a column: their spacing 2r = 2e308 is
  // beyond double precision, so the centres are. `check` used to stop with
  // "the simulation blew up" (found by scripts/fuzz_scenes.py).
  const auto msg = load_error(replace(kGood, "radius = 0.0005", "radius = 1e308"));
  EXPECT_NE(
      msg.find(":23:1: error: [[particles]] #1: the column generator places its particle 0 at a position "
               "that is not finite"),
      std::string::npos)
      << msg;
}

TEST(SceneErrors, NegativeDensityIsRefused) {
  const auto msg = load_error(replace(kGood, "density = 2650.0", "density = -1.0"));
  EXPECT_NE(msg.find("key 'density': must be > 0 kg/m^3, got -1"), std::string::npos) << msg;
}

TEST(SceneErrors, NegativeFrictionIsRefused) {
  const auto msg = load_error(replace(kGood, "friction = 0.5", "friction = -0.1"));
  EXPECT_NE(msg.find("key 'friction': must be >= 0"), std::string::npos) << msg;
}

TEST(SceneErrors, UnknownChoiceSuggestsTheNearOne) {
  const auto msg = load_error(replace(kGood, "law = \"linear\"", "law = \"linar\""));
  EXPECT_NE(msg.find("did you mean \"linear\"?"), std::string::npos) << msg;
}

TEST(SceneErrors, OverlapWithWallAtStartIsRefused) {
  const auto msg = load_error(replace(kGood, "base = [0.0, 0.0]", "base = [0.0, -0.0002]"));
  EXPECT_NE(msg.find("overlaps wall \"floor\""), std::string::npos) << msg;
  EXPECT_NE(msg.find("initial_overlap_tolerance"), std::string::npos) << msg;
}

TEST(SceneErrors, BoxWallsAreChecked) {
  // A plate (a segment in 2D) beside the column: x = 2 mm, y in [0, 2] mm.
  const std::string plate =
      "\n[[wall]]\nname = \"pile\"\nbox = { min = [0.002, 0.0], max = [0.002, 0.002] }\nmaterial = "
      "\"sand\"\n";
  const std::string good = replace(kGood, "[[particles]]", plate + "\n[[particles]]");
  EXPECT_EQ(load_error(good), "");
  auto msg = load_error(replace(good, "max = [0.002, 0.002]", "max = [0.001, 0.002]"));
  EXPECT_NE(msg.find("[[wall]] #2 box key 'max': must be >= min along every axis (a plate has min = max "
                     "along one); along x min = 0.002 and max = 0.001"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "box = {", "normal = [1.0, 0.0]\nbox = {"));
  EXPECT_NE(msg.find("key 'normal': a box wall is placed by 'box' alone"), std::string::npos) << msg;
  msg =
      load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                         "material = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, max_speed = 1.0 }\n"
                         "\n[[particles]]"));
  EXPECT_NE(msg.find("[[wall]] #2 servo: a box wall's servo needs 'direction' = [2 numbers]: the way the box "
                     "moves to load the grains more"),
            std::string::npos)
      << msg;
  EXPECT_EQ(
      load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                         "material = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, max_speed = 1.0, "
                         "direction = [-1.0, 0.0] }\n\n[[particles]]")),
      "");
  // The pore water's thrust: only on a wall that displaces the fluid (here
  // there is none: no [fluid]).
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, max_speed = 1.0, "
                           "direction = [-1.0, 0.0], load = \"total\" }\n\n[[particles]]"));
  EXPECT_NE(msg.find("servo key 'load': \"total\" adds the pore water's thrust, which only a wall with "
                     "displaces_fluid = true takes"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, max_speed = 1.0, "
                           "direction = [-1.0, 0.0], load = \"all\" }\n\n[[particles]]"));
  EXPECT_NE(msg.find("key 'load'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("grains"), std::string::npos) << msg;
  // A plane's servo moves along its normal.
  msg = load_error(
      replace(kGood, "normal = [0.0, 1.0]\nmaterial = \"sand\"",
              "normal = [0.0, 1.0]\nmaterial = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, "
              "max_speed = 1.0, direction = [0.0, 1.0] }"));
  EXPECT_NE(msg.find("key 'direction': a plane wall's servo moves it along its normal"), std::string::npos)
      << msg;
  msg = load_error(replace(good, "box = { min = [0.002, 0.0], max = [0.002, 0.002] }", ""));
  EXPECT_NE(
      msg.find("a wall needs 'point' and 'normal' (an infinite plane), 'box = { min = [...], max = "
               "[...] }' (a box or plate), 'cylinder = { centre = [...], radius = ... }' (a cylinder; 2D: a "
               "circle) or 'mesh = { file = \"...stl\" }' (3D: a surface of triangles)"),
      std::string::npos)
      << msg;
  msg = load_error(replace(good, "min = [0.002, 0.0]", "min = [0.002, 0.0], size = 1"));
  EXPECT_NE(msg.find("unknown key 'size'"), std::string::npos) << msg;
  // A disc that starts inside the plate is refused like one behind a plane.
  msg = load_error(replace(good, "min = [0.002, 0.0]", "min = [0.0003, 0.0]"));
  EXPECT_NE(msg.find("overlaps wall \"pile\""), std::string::npos) << msg;
  // A stage makes it a servo wall with its direction.
  msg = load_error(replace(good, "gravity = [0.0, -9.81]",
                           "gravity = [0.0, -9.81]\nwalls.pile = { servo = { target_force = 1.0, gain = 1.0, "
                           "max_speed = 1.0 } }"));
  EXPECT_NE(msg.find("walls.pile servo: a box wall's servo needs 'direction'"), std::string::npos) << msg;
  const std::string staged =
      replace(good, "gravity = [0.0, -9.81]",
              "gravity = [0.0, -9.81]\nwalls.pile = { servo = { target_force = 1.0, gain = "
              "1.0, max_speed = 1.0, direction = [-2.0, 0.0] } }");
  EXPECT_EQ(load_error(staged), "");
  const auto scene = built_scene<2>(staged);
  EXPECT_EQ(scene.stages.front().walls.front().servo_axis, Vec<2>(-1.0, 0.0));  // normalised
}

TEST(SceneErrors, StressServosAreChecked) {
  // A lid over the column, between two side walls: its loaded length is
  // the 2 mm between them (x 1 m).
  const std::string sides =
      "\n[[wall]]\nname = \"left\"\npoint = [-0.001, 0.0]\nnormal = [1.0, 0.0]\nmaterial = \"sand\"\n"
      "\n[[wall]]\nname = \"right\"\npoint = [0.001, 0.0]\nnormal = [-1.0, 0.0]\nmaterial = \"sand\"\n";
  const std::string lid =
      "\n[[wall]]\nname = \"lid\"\npoint = [0.0, 0.004]\nnormal = [0.0, -1.0]\nmaterial = \"sand\"\n"
      "servo = { target_stress = 1000.0, gain = 1e-3, max_speed = 0.01 }\n";
  const std::string probe = "\n[[probe]]\nname = \"s\"\nquantity = \"wall_stress\"\nwall = \"lid\"\n";
  const std::string good = replace(kGood, "[[particles]]", lid + sides + probe + "\n[[particles]]");
  EXPECT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  EXPECT_TRUE(scene.simulation.walls[1].servo.by_stress);
  EXPECT_EQ(scene.simulation.walls[1].servo.target_stress, 1000.0);
  // The sides may come after the lid; without one, the lid has no area.
  std::string msg = load_error(replace(kGood, "[[particles]]", lid + "\n[[particles]]"));
  EXPECT_NE(
      msg.find("[[wall]] #2 servo key 'target_stress': loads wall \"lid\" over the sample's "
               "cross-section, and its cross-section is not bounded: the sample's extent along x needs one "
               "plane wall facing +x and one facing -x (or a periodic x); there are 0 and 0; give "
               "'target_force' (N) instead"),
      std::string::npos)
      << msg;
  msg = load_error(replace(good, "target_stress = 1000.0", "target_stress = 1000.0, target_force = 1.0"));
  EXPECT_NE(
      msg.find("a servo needs one of 'target_force' (N, the load wanted on the wall) or 'target_stress'"),
      std::string::npos)
      << msg;
  msg = load_error(replace(good, "target_stress = 1000.0, ", ""));
  EXPECT_NE(msg.find("a servo needs one of 'target_force'"), std::string::npos) << msg;
  msg = load_error(replace(good, "target_stress = 1000.0", "target_stress = -1.0"));
  EXPECT_NE(msg.find("key 'target_stress': must be >= 0 Pa, got -1"), std::string::npos) << msg;
  // A tilted plane's cross-section is not bounded by walls along the axes.
  msg = load_error(replace(good, "normal = [0.0, -1.0]", "normal = [0.6, -0.8]"));
  EXPECT_NE(msg.find("its normal is not along an axis"), std::string::npos) << msg;
  // A box has no loaded area: give it a force.
  msg = load_error(replace(good, "point = [0.0, 0.004]\nnormal = [0.0, -1.0]",
                           "box = { min = [-0.001, 0.004], max = [0.001, 0.005] }"));
  EXPECT_NE(
      msg.find("key 'target_stress': is for a plane wall (its cross-section of the sample) or a "
               "cylinder (its lateral surface), whose loaded area the other walls bound; give a box wall "
               "a 'target_force'"),
      std::string::npos)
      << msg;
  // A stage that makes the floor a stress servo: the side walls bound it;
  // two walls facing +x and none facing -x do not; nor do no side walls.
  // The probe on a plane the walls do not bound is refused.
  const std::string staged =
      replace(good, "gravity = [0.0, -9.81]",
              "gravity = [0.0, -9.81]\nwalls.floor = { servo = { target_stress = 10.0, "
              "gain = 1e-3, max_speed = 0.01 } }");
  EXPECT_EQ(load_error(staged), "");
  msg = load_error(replace(staged, "normal = [-1.0, 0.0]", "normal = [1.0, 0.0]"));
  EXPECT_NE(msg.find("there are 2 and 0"), std::string::npos) << msg;
  msg = load_error(replace(replace(kGood, "gravity = [0.0, -9.81]",
                                   "gravity = [0.0, -9.81]\nwalls.floor = { servo = { target_stress = 10.0, "
                                   "gain = 1e-3, max_speed = 0.01 } }"),
                           "[[particles]]", sides + "\n[[particles]]"));
  EXPECT_EQ(msg, "");
  msg = load_error(
      replace(kGood, "gravity = [0.0, -9.81]",
              "gravity = [0.0, -9.81]\nwalls.floor = { servo = { target_stress = 10.0, gain = 1e-3, "
              "max_speed = 0.01 } }"));
  EXPECT_NE(msg.find("[[stage]] #1 walls.floor servo key 'target_stress': loads wall \"floor\""),
            std::string::npos)
      << msg;
  msg = load_error(replace(kGood, "[[particles]]", probe + "\n[[particles]]"));
  EXPECT_NE(msg.find("no wall named \"lid\""), std::string::npos) << msg;
  msg = load_error(replace(replace(kGood, "[[particles]]", probe + "\n[[particles]]"), "wall = \"lid\"",
                           "wall = \"floor\""));
  EXPECT_NE(msg.find("key 'wall': wall \"floor\" has no loaded area to divide its load by: its cross-section "
                     "is not bounded: the sample's extent along x needs"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "wall = \"lid\"", "wall = \"lid\"\ncomponent = \"y\""));
  EXPECT_NE(msg.find("key 'component': does not apply: the stress is normal to the wall"), std::string::npos)
      << msg;
}

TEST(SceneErrors, StageFrictionIsChecked) {
  const std::string at_stage = "gravity = [0.0, -9.81]\ncontacts = ";
  auto staged = [&](const std::string& contacts) {
    return load_error(replace(kGood, "gravity = [0.0, -9.81]", at_stage + contacts));
  };
  EXPECT_EQ(staged("[{ materials = [\"sand\", \"sand\"], friction = 0.1 }]"), "");
  const auto scene = built_scene<2>(replace(
      kGood, "gravity = [0.0, -9.81]", at_stage + "[{ materials = [\"sand\", \"sand\"], friction = 0.1 }]"));
  ASSERT_EQ(scene.stages.front().frictions.size(), 1U);
  EXPECT_EQ(scene.stages.front().frictions.front().friction, 0.1);
  std::string msg = staged("[{ materials = [\"sand\", \"sand\"], friction = -0.1 }]");
  EXPECT_NE(msg.find("[[stage]] #1 contacts #1 key 'friction': must be >= 0, got -0.1"), std::string::npos)
      << msg;
  msg = staged("[{ materials = [\"sand\", \"snad\"], friction = 0.1 }]");
  EXPECT_NE(msg.find("contacts #1 key 'materials'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("snad"), std::string::npos) << msg;
  msg = staged("[{ materials = [\"sand\"], friction = 0.1 }]");
  EXPECT_NE(msg.find("must name exactly two materials"), std::string::npos) << msg;
  msg = staged("[{ materials = [\"sand\", \"sand\"], friction = 0.1, restitution = 0.2 }]");
  EXPECT_NE(msg.find("unknown key 'restitution'"), std::string::npos) << msg;
  msg = staged("[{ materials = [\"sand\", \"sand\"] }]");
  EXPECT_NE(msg.find("friction"), std::string::npos) << msg;
  msg = staged("[0.1]");
  EXPECT_NE(msg.find("key 'contacts': must be an array of tables"), std::string::npos) << msg;
  // A pair without a [[contact]], and friction where the [[contact]] has
  // none (the time step did not allow for it).
  const std::string steel =
      replace(kGood, "[[contact]]", "[[material]]\nname = \"steel\"\ndensity = 7850.0\n\n[[contact]]");
  msg = load_error(replace(steel, "gravity = [0.0, -9.81]",
                           at_stage + "[{ materials = [\"sand\", \"steel\"], friction = 0.1 }]"));
  EXPECT_NE(msg.find("the pair sand / steel has no [[contact]] whose friction a stage could change"),
            std::string::npos)
      << msg;
  msg = load_error(replace(replace(kGood, "friction = 0.5", "friction = 0.0"), "gravity = [0.0, -9.81]",
                           at_stage + "[{ materials = [\"sand\", \"sand\"], friction = 0.1 }]"));
  EXPECT_NE(
      msg.find("key 'friction': the [[contact]] of sand / sand has no friction, so the time step does not "
               "allow for the grains its tangential spring turns"),
      std::string::npos)
      << msg;
}

// A mesh wall: a square of two facets beside the column (3D), inline or
// from an STL file next to the scene.
TEST(SceneErrors, MeshWallsAreChecked) {
  const std::string square =
      "\n[[wall]]\nname = \"side\"\nmesh = { vertices = [[0.002, -0.002, 0.0], [0.002, 0.002, 0.0], "
      "[0.002, 0.002, 0.004], [0.002, -0.002, 0.004]], triangles = [[0, 1, 2], [0, 2, 3]] }\nmaterial = "
      "\"sand\"\n";
  const std::string good = in_3d(replace(kGood, "[[particles]]", square + "\n[[particles]]"));
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<3>(good);
    const auto& w = scene.simulation.walls.back();
    ASSERT_TRUE(w.is_mesh());
    EXPECT_EQ(w.mesh->triangle.size(), 2u);
    // Its frame is the centre of its bounding box.
    EXPECT_LT((w.point - Vec<3>(0.002, 0.0, 0.002)).norm(), 1e-15);
    EXPECT_NEAR(w.mesh->area(), 0.004 * 0.004, 1e-18);
  }
  {
    // Moved by 1 mm along x and turned a quarter turn about z round the
    // centre of its box: the square now stands across y, at y = 0, centred
    // on x = 3 mm.
    const std::string moved = replace(
        good, "[0, 2, 3]] }",
        "[0, 2, 3]], translate = [0.001, 0.0, 0.0], rotation = { axis = [0.0, 0.0, 1.0], angle = 90.0 } }");
    ASSERT_EQ(load_error(moved), "");
    const auto scene = built_scene<3>(moved);
    const auto& w = scene.simulation.walls.back();
    EXPECT_LT((w.point - Vec<3>(0.003, 0.0, 0.002)).norm(), 1e-15);
    const auto touch = w.touch(Vec<3>(0.0045, 0.0005, 0.001));
    EXPECT_NEAR(touch.gap, 0.0005, 1e-15);
    EXPECT_LT((touch.normal - Vec<3>(0.0, 1.0, 0.0)).norm(), 1e-12);
    EXPECT_NE(load_error(replace(moved, "translate = [0.001, 0.0, 0.0]", "translate = [0.001, 0.0]"))
                  .find("mesh key 'translate'"),
              std::string::npos);
  }
  auto msg = load_error(replace(good, "[0, 2, 3]", "[0, 2, 4]"));
  EXPECT_NE(msg.find("[[wall]] #2 mesh key 'triangles': vertex number 4 is not one of 0 .. 3"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "[0, 2, 3]", "[0, 2, 0]"));
  EXPECT_NE(msg.find("the mesh cannot be used: facet 1 has no area"), std::string::npos) << msg;
  msg = load_error(replace(good, "[0.002, -0.002, 0.0], ", "[0.002, -0.002], "));
  EXPECT_NE(msg.find("mesh key 'vertices': entry 0 (from 0) must be an array of 3 finite numbers"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "mesh = { vertices", "mesh = { file = \"side.stl\", vertices"));
  EXPECT_NE(msg.find("give 'file' (an STL file, ASCII or binary, relative to the scene) or 'vertices'"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "mesh = {", "point = [0.0, 0.0, 0.0]\nmesh = {"));
  EXPECT_NE(msg.find("key 'point': a mesh wall is placed by 'mesh' alone"), std::string::npos) << msg;
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nimpermeable = true\n\n[[particles]]"));
  EXPECT_NE(msg.find("key 'impermeable': a mesh wall lets the pore water through"), std::string::npos) << msg;
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nservo = { target_force = 1.0, gain = 1.0, max_speed = 1.0 "
                           "}\n\n[[particles]]"));
  EXPECT_NE(msg.find("a mesh wall's servo needs 'direction' = [3 numbers]"), std::string::npos) << msg;
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nservo = { target_stress = 1.0, gain = 1.0, max_speed = 1.0, "
                           "direction = [-1.0, 0.0, 0.0] }\n\n[[particles]]"));
  EXPECT_NE(msg.find("give a mesh wall a 'target_force'"), std::string::npos) << msg;
  // 2D: a segment is a box plate.
  msg = load_error(replace(kGood, "[[particles]]",
                           "[[wall]]\nname = \"side\"\nmesh = { file = \"side.stl\" }\nmaterial = "
                           "\"sand\"\n\n[[particles]]"));
  EXPECT_NE(msg.find("key 'mesh': a mesh wall is a surface of triangles, in 3D"), std::string::npos) << msg;
  // From a file: relative to the scene; a missing or bad one is named.
  const std::string from_file = replace(good,
                                        "mesh = { vertices = [[0.002, -0.002, 0.0], [0.002, 0.002, 0.0], "
                                        "[0.002, 0.002, 0.004], [0.002, -0.002, "
                                        "0.004]], triangles = [[0, 1, 2], [0, 2, 3]] }",
                                        "mesh = { file = \"darcydem_side_test.stl\", scale = 0.001 }");
  msg = load_error(from_file);
  EXPECT_NE(msg.find("mesh key 'file': "), std::string::npos) << msg;
  EXPECT_NE(msg.find("darcydem_side_test.stl: cannot open the STL file"), std::string::npos) << msg;
  const auto stl = std::filesystem::temp_directory_path() / "darcydem_side_test.stl";
  std::ofstream(stl)
      << "solid side\n facet normal -1 0 0\n  outer loop\n   vertex 2 -2 0\n   vertex 2 2 0\n"
         "   vertex 2 2 4\n  endloop\n endfacet\n facet normal -1 0 0\n  outer loop\n   vertex 2 "
         "-2 0\n   vertex 2 2 4\n   vertex 2 -2 4\n  endloop\n endfacet\nendsolid side\n";
  ASSERT_EQ(load_error(from_file), "");
  {
    const auto scene = built_scene<3>(from_file);
    const auto& w = scene.simulation.walls.back();
    EXPECT_EQ(w.mesh->vertex.size(), 4u);  // the corners the facets share, once
    EXPECT_NEAR(w.mesh->area(), 0.004 * 0.004, 1e-18);
  }
  // A sliver (corners in a line), as CAD tessellations leave: left out,
  // and the note says so.
  std::ofstream(stl)
      << "solid side\n facet normal -1 0 0\n  outer loop\n   vertex 2 -2 0\n   vertex 2 2 0\n"
         "   vertex 2 2 4\n  endloop\n endfacet\n facet normal 0 0 0\n  outer loop\n   vertex 2 "
         "-2 0\n   vertex 2 0 0\n   vertex 2 2 0\n  endloop\n endfacet\nendsolid side\n";
  ASSERT_EQ(load_error(from_file), "");
  {
    const auto scene = built_scene<3>(from_file);
    EXPECT_EQ(scene.simulation.walls.back().mesh->triangle.size(), 1u);
    bool noted = false;
    for (const auto& n : scene.notes)
      noted = noted || n.find("; 1 facets of no area in the file left out") != std::string::npos;
    EXPECT_TRUE(noted);
  }
  msg = load_error(replace(from_file, "scale = 0.001", "scale = -1.0"));
  EXPECT_NE(msg.find("mesh key 'scale': must be > 0: the file's unit in m"), std::string::npos) << msg;
  std::ofstream(stl) << "solid side\n facet normal -1 0 0\n  outer loop\n   vertex 2 -2 0\n   vertec 2 2 0\n";
  msg = load_error(from_file);
  EXPECT_NE(msg.find("darcydem_side_test.stl:5: 'vertec' is not a word of an ASCII STL file"),
            std::string::npos)
      << msg;
  std::filesystem::remove(stl);
}

TEST(SceneErrors, CylinderWallsAreChecked) {
  // A drum of 3 mm radius round the column of discs (2D: a circle).
  const std::string drum =
      "\n[[wall]]\nname = \"drum\"\ncylinder = { centre = [0.0, 0.002], radius = 0.003 }\nmaterial = "
      "\"sand\"\n";
  const std::string good = replace(kGood, "[[particles]]", drum + "\n[[particles]]");
  EXPECT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  const auto& w = scene.simulation.walls.back();
  EXPECT_TRUE(w.is_cylinder());
  EXPECT_TRUE(w.from_inside);  // the default: a drum
  EXPECT_EQ(w.radius, 0.003);
  auto msg = load_error(replace(good, "radius = 0.003", "radius = 0.0"));
  EXPECT_NE(msg.find("[[wall]] #2 cylinder key 'radius': must be > 0 m"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "radius = 0.003", "radius = 0.003, axis = [0.0, 1.0]"));
  EXPECT_NE(msg.find("cylinder key 'axis': a 2D cylinder is a circle"), std::string::npos) << msg;
  msg = load_error(replace(good, "radius = 0.003", "radius = 0.003, touched_from = \"above\""));
  EXPECT_NE(msg.find("key 'touched_from'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("inside"), std::string::npos) << msg;
  msg = load_error(replace(good, "centre = [0.0, 0.002], ", ""));
  EXPECT_NE(msg.find("centre"), std::string::npos) << msg;
  msg = load_error(replace(good, "cylinder = {", "point = [0.0, 0.0]\ncylinder = {"));
  EXPECT_NE(msg.find("key 'point': a cylinder wall is placed by 'cylinder' alone"), std::string::npos) << msg;
  // A servo changes its radius: by force, or by stress over its
  // perimeter (2D: times 1 m); no direction.
  const std::string servo =
      replace(good, "radius = 0.003 }\nmaterial = \"sand\"",
              "radius = 0.003 }\nmaterial = \"sand\"\nservo = { target_stress = 1000.0, gain = 1.0, "
              "max_speed = 1.0 }");
  ASSERT_EQ(load_error(servo), "");
  EXPECT_EQ(built_scene<2>(servo).simulation.walls.back().motion, WallMotion::servo);
  EXPECT_EQ(load_error(replace(servo, "target_stress = 1000.0", "target_force = 1.0")), "");
  msg = load_error(replace(servo, "max_speed = 1.0", "max_speed = 1.0, direction = [1.0, 0.0]"));
  EXPECT_NE(msg.find("servo key 'direction': a cylinder's servo changes its radius"), std::string::npos)
      << msg;
  // Or its radius changes at a set rate: a cylinder's only, not with a
  // servo; a stage sets it (zero unless the entry gives it).
  const std::string expanding = replace(good, "radius = 0.003 }\nmaterial = \"sand\"",
                                        "radius = 0.003 }\nmaterial = \"sand\"\nradial_velocity = -0.01");
  ASSERT_EQ(load_error(expanding), "");
  EXPECT_EQ(built_scene<2>(expanding).simulation.walls.back().radius_rate, -0.01);
  msg = load_error(replace(servo, "max_speed = 1.0 }", "max_speed = 1.0 }\nradial_velocity = 0.01"));
  EXPECT_NE(msg.find("key 'radial_velocity': a servo sets the cylinder's radius from its load"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "normal = [0.0, 1.0]\nmaterial = \"sand\"",
                           "normal = [0.0, 1.0]\nmaterial = \"sand\"\nradial_velocity = 0.01"));
  EXPECT_NE(msg.find("key 'radial_velocity': changes a cylinder wall's radius"), std::string::npos) << msg;
  msg = load_error(replace(expanding, "radial_velocity = -0.01", "radial_velocity = \"fast\""));
  EXPECT_NE(msg.find("key 'radial_velocity'"), std::string::npos) << msg;
  const std::string staged = replace(good, "gravity = [0.0, -9.81]",
                                     "gravity = [0.0, -9.81]\nwalls.drum = { radial_velocity = 0.002 }");
  ASSERT_EQ(load_error(staged), "");
  EXPECT_EQ(built_scene<2>(staged).stages[0].walls[0].radius_rate, 0.002);
  // 3D: the height its lateral surface has needs walls or a period along
  // the axis; the column's floor alone does not bound it.
  const std::string servo3 =
      replace(replace(in_3d(servo), "centre = [0.0, 0.002]", "centre = [0.0, 0.0, 0.002]"),
              "radius = 0.003 }", "radius = 0.003, axis = [0.0, 0.0, 1.0] }");
  msg = load_error(servo3);
  EXPECT_NE(
      msg.find("[[wall]] #2 servo key 'target_stress': loads wall \"drum\" over the sample's lateral "
               "surface, and its height is not bounded: the sample's extent along z needs one plane wall "
               "facing +z and one facing -z (or a periodic z); there are 1 and 0"),
      std::string::npos)
      << msg;
  EXPECT_EQ(load_error(replace(servo3, "[[particles]]",
                               "[[wall]]\nname = \"lid\"\npoint = [0.0, 0.0, 0.02]\nnormal = [0.0, 0.0, "
                               "-1.0]\nmaterial = \"sand\"\n\n[[particles]]")),
            "");
  // Touched from outside, the discs would start inside the solid: refused
  // as any overlap at the start is.
  msg = load_error(replace(good, "radius = 0.003", "radius = 0.003, touched_from = \"outside\""));
  EXPECT_NE(msg.find("overlaps wall \"drum\""), std::string::npos) << msg;
  // It turns about its axis, and has a torque probe (turning planes and
  // boxes: TurningWallsAreChecked).
  EXPECT_EQ(load_error(replace(good, "radius = 0.003 }\nmaterial = \"sand\"",
                               "radius = 0.003 }\nmaterial = \"sand\"\nangular_velocity = 2.0")),
            "");
  msg = load_error(replace(good, "radius = 0.003 }\nmaterial = \"sand\"",
                           "radius = 0.003 }\nmaterial = \"sand\"\nrotation_centre = [0.0, 0.0]"));
  EXPECT_NE(msg.find("key 'rotation_centre': a cylinder turns about its own axis"), std::string::npos) << msg;
  // Its radius: a length, of a cylinder only.
  const std::string radius_probe =
      "[[probe]]\nname = \"r\"\nquantity = \"wall_radius\"\nwall = \"drum\"\n\n[[stage]]";
  EXPECT_EQ(load_error(replace(good, "[[stage]]", radius_probe)), "");
  msg = load_error(replace(good, "[[stage]]", replace(radius_probe, "wall = \"drum\"", "wall = \"floor\"")));
  EXPECT_NE(msg.find("key 'wall': must name a cylinder wall (its radius); the scene's: \"drum\""),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "[[stage]]",
                           replace(radius_probe, "wall = \"drum\"", "wall = \"drum\"\ncomponent = \"x\"")));
  EXPECT_NE(msg.find("key 'component': does not apply: the radius is a length"), std::string::npos) << msg;
  // The pore water passes through it.
  msg = load_error(replace(good, "radius = 0.003 }\nmaterial = \"sand\"",
                           "radius = 0.003 }\nmaterial = \"sand\"\ndisplaces_fluid = true"));
  EXPECT_NE(msg.find("key 'displaces_fluid': a cylinder wall lets the pore water through"), std::string::npos)
      << msg;
}

std::string with_fluid(const std::string& extra);  // below, with the fluid's errors

TEST(SceneErrors, ServoSchedulesAreChecked) {
  // A servo's target in time: a number, or { times, values } (a ramp or
  // schedule from the stage's start), plus an optional cycle = {
  // amplitude, frequency, phase }; it must stay >= 0 (compressive).
  const std::string servo =
      "normal = [0.0, 1.0]\nmaterial = \"sand\"\n"
      "servo = { target_force = { times = [0.0, 0.5], values = [1.0, 3.0] }, cycle = { amplitude = 0.5, "
      "frequency = 2.0, phase = -90.0 }, gain = 1e-3, max_speed = 0.01 }";
  const std::string good = replace(kGood, "normal = [0.0, 1.0]\nmaterial = \"sand\"", servo);
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& s = scene.simulation.walls[0].servo;
    EXPECT_TRUE(s.varies());
    // 1 + 0.5 sin(-pi/2) at the start; at 0.25 s the ramp's 2 N plus the
    // cycle's 0.5 sin(pi - pi/2) = 0.5 N.
    EXPECT_DOUBLE_EQ(s.target_force, 0.5);
    EXPECT_NEAR(s.target_at(0.25), 2.5, 1e-12);
    EXPECT_NEAR(s.target_at(1.0), 3.0 + 0.5 * std::sin(4.0 * 3.141592653589793 - 0.5 * 3.141592653589793),
                1e-12);
  }
  auto expect = [&](const std::string& from, const std::string& to, const std::string& wanted) {
    const auto msg = load_error(replace(good, from, to));
    EXPECT_NE(msg.find(wanted), std::string::npos) << msg;
  };
  expect("values = [1.0, 3.0]", "values = [1.0, -3.0]",
         "[[wall]] #1 servo key 'target_force': must be >= 0 N at every time (a compressive load), got -3 at "
         "0.5 s");
  expect("values = [1.0, 3.0]", "values = [1.0]",
         "servo target_force key 'values': must have as many entries");
  expect("times = [0.0, 0.5]", "times = [0.5, 0.0]",
         "servo target_force key 'times': must increase strictly");
  expect(
      "amplitude = 0.5", "amplitude = 1.5",
      "[[wall]] #1 servo cycle key 'amplitude': must be at most the least of 'target_force' (1): the target, "
      "target_force plus the cycle, must stay >= 0");
  expect("amplitude = 0.5", "amplitude = 0.0", "servo cycle key 'amplitude': must be > 0 N");
  expect("frequency = 2.0", "frequency = -2.0", "servo cycle key 'frequency': must be > 0 Hz, got -2");
  expect("frequency = 2.0", "frequncy = 2.0", "unknown key 'frequncy'. Did you mean 'frequency'?");
  expect("cycle = {", "cycle = 3.0, cyc = {", "servo key 'cycle': must be a table");
  // The probe of a servo's target: a wall, no component.
  const std::string probe = "\n[[probe]]\nname = \"t\"\nquantity = \"wall_target\"\nwall = \"floor\"\n";
  EXPECT_EQ(load_error(replace(good, "[[particles]]", probe + "\n[[particles]]")), "");
  EXPECT_NE(load_error(replace(good, "[[particles]]", probe + "component = \"y\"\n\n[[particles]]"))
                .find("key 'component': does not apply: a servo's target is its load normal to the wall"),
            std::string::npos);
  expect("target_force = { times = [0.0, 0.5], values = [1.0, 3.0] }", "target_force = \"high\"",
         "servo key 'target_force': must be a number (N) or a table { times = [...], values = [...] }");
  // In a stage, with a stress target: Pa.
  const std::string staged = replace(
      kGood, "gravity = [0.0, -9.81]",
      "gravity = [0.0, -9.81]\nwalls.floor = { servo = { target_force = 2.0, cycle = { amplitude = 1.0, "
      "frequency = 5.0 }, gain = 1e-3, max_speed = 0.01 } }");
  ASSERT_EQ(load_error(staged), "");
  EXPECT_EQ(built_scene<2>(staged).stages.front().walls.front().servo.cycle.frequency, 5.0);
  const std::string msg = load_error(replace(staged, "amplitude = 1.0", "amplitude = 2.5"));
  EXPECT_NE(msg.find("[[stage]] #1 walls.floor servo cycle key 'amplitude': must be at most the least of "
                     "'target_force' (2)"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, OscillatingWallsAreChecked) {
  // A harmonic translation: amplitude (D numbers, m), frequency (Hz),
  // phase (degrees, optional), on a wall fixed or moving, in a [[wall]] or
  // a stage's walls.NAME.
  const std::string shaking =
      "normal = [0.0, 1.0]\nmaterial = \"sand\"\n"
      "oscillation = { amplitude = [0.0, 0.001], frequency = 20.0, phase = -90.0 }";
  const std::string good = replace(kGood, "normal = [0.0, 1.0]\nmaterial = \"sand\"", shaking);
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& o = scene.simulation.walls[0].oscillation;
    EXPECT_EQ(o.amplitude, Vec<2>(0.0, 0.001));
    EXPECT_EQ(o.frequency, 20.0);
    EXPECT_NEAR(o.phase, -0.5 * 3.141592653589793, 1e-15);
  }
  const std::string staged = replace(
      kGood, "gravity = [0.0, -9.81]",
      "gravity = [0.0, -9.81]\nwalls.floor = { fixed = true, oscillation = { amplitude = [0.0, 0.001], "
      "frequency = 5.0 } }");
  ASSERT_EQ(load_error(staged), "");
  EXPECT_EQ(built_scene<2>(staged).stages.front().walls.front().oscillation.frequency, 5.0);
  auto expect = [&](const std::string& from, const std::string& to, const std::string& wanted) {
    const auto msg = load_error(replace(good, from, to));
    EXPECT_NE(msg.find(wanted), std::string::npos) << msg;
  };
  expect("frequency = 20.0", "frequency = 0.0",
         "[[wall]] #1 oscillation key 'frequency': must be > 0 Hz, got 0");
  expect("amplitude = [0.0, 0.001]", "amplitude = [0.0, 0.0]",
         "[[wall]] #1 oscillation key 'amplitude': must be finite and not all zero");
  expect("amplitude = [0.0, 0.001]", "amplitude = [0.001]", "[[wall]] #1 oscillation key 'amplitude'");
  expect(", phase = -90.0", ", period = 0.05", "period");
  expect("oscillation = {", "oscillation = 3.0 #", "key 'oscillation': must be a table");
  expect("oscillation = {", "servo = { target_force = 1.0, gain = 1e-3, max_speed = 0.01 }\noscillation = {",
         "key 'oscillation': a servo sets the wall's place from its load");
}

TEST(SceneErrors, TurningWallsAreChecked) {
  // 2D: a plane or box turns counter-clockwise at a number of rad/s about
  // its rotation_centre (by default its point or centre).
  const std::string turning = "normal = [0.0, 1.0]\nmaterial = \"sand\"\nangular_velocity = 2.0";
  const std::string good = replace(kGood, "normal = [0.0, 1.0]\nmaterial = \"sand\"", turning);
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene =
        built_scene<2>(replace(good, "angular_velocity", "rotation_centre = [0.01, 0.0]\nangular_velocity"));
    const auto& w = scene.simulation.walls[0];
    EXPECT_EQ(w.spin, 2.0);
    EXPECT_EQ(w.pivot, Vec<2>(0.01, 0.0));
  }
  EXPECT_EQ(built_scene<2>(good).simulation.walls[0].pivot, Vec<2>(0.0, 0.0));
  // A 2D wall's torque probe: the moment about its centre of rotation.
  const std::string probe =
      "[[probe]]\nname = \"t\"\nquantity = \"wall_torque\"\nwall = \"floor\"\n\n[[stage]]";
  EXPECT_EQ(load_error(replace(kGood, "[[stage]]", probe)), "");
  // 3D: a vector, its direction the axis, right-handed.
  const std::string good3 =
      replace(in_3d(good), "angular_velocity = 2.0", "angular_velocity = [0.0, 0.0, -2.0]");
  ASSERT_EQ(load_error(good3), "");
  {
    const auto scene = built_scene<3>(good3);
    const auto& w = scene.simulation.walls[0];
    EXPECT_EQ(w.spin, 2.0);
    EXPECT_EQ(w.axis, Vec<3>(0.0, 0.0, -1.0));
  }
  EXPECT_EQ(load_error(replace(good3, "[[stage]]", probe)), "");
  auto msg = load_error(in_3d(good));
  EXPECT_NE(msg.find("[[wall]] #1 key 'angular_velocity': a plane or box wall turns about the axis of its "
                     "angular velocity through its 'rotation_centre': give [wx, wy, wz], rad/s"),
            std::string::npos)
      << msg;
  // Without a turn a 3D plane has no axis for its moment.
  msg = load_error(replace(in_3d(kGood), "[[stage]]", probe));
  EXPECT_NE(msg.find("key 'wall': must name a cylinder (the moment about its axis) or a plane or box wall "
                     "given an angular_velocity"),
            std::string::npos)
      << msg;
  msg = load_error(
      replace(good, "angular_velocity = 2.0",
              "angular_velocity = 2.0\nservo = { target_force = 1.0, gain = 1e-3, max_speed = 0.01 }"));
  EXPECT_NE(msg.find("key 'angular_velocity': a servo moves a wall along a fixed direction"),
            std::string::npos)
      << msg;
  msg =
      load_error(replace(good, "angular_velocity = 2.0", "angular_velocity = 2.0\nrotation_centre = [0.0]"));
  EXPECT_NE(msg.find("key 'rotation_centre'"), std::string::npos) << msg;
  // The pore fluid needs the walls it meets along its grid.
  msg = load_error(replace(with_fluid(""), "normal = [0.0, 1.0]\nmaterial = \"sand\"",
                           turning + "\ndisplaces_fluid = true"));
  EXPECT_NE(msg.find("key 'angular_velocity': a wall that displaces the pore fluid or is impermeable stays "
                     "along the fluid grid's axes: it cannot turn"),
            std::string::npos)
      << msg;
  // Walls are not repeated across periodic boundaries.
  const std::string periodic = "\n[periodic]\nx = [-0.003, 0.003]\n";
  msg = load_error(replace(good, "\n[[material]]", periodic + "\n[[material]]"));
  EXPECT_NE(
      msg.find("key 'angular_velocity': a plane or box wall cannot turn with periodic boundaries (along x)"),
      std::string::npos)
      << msg;
  // A stage turns it, or stops it; in 3D with a vector too.
  const std::string staged = replace(kGood, "gravity = [0.0, -9.81]",
                                     "gravity = [0.0, -9.81]\nwalls.floor = { angular_velocity = 1.0 }");
  EXPECT_EQ(load_error(staged), "");
  msg = load_error(in_3d(staged));
  EXPECT_NE(msg.find("walls.floor key 'angular_velocity': a plane or box wall turns about the axis"),
            std::string::npos)
      << msg;
  EXPECT_EQ(
      load_error(replace(in_3d(staged), "angular_velocity = 1.0", "angular_velocity = [1.0, 0.0, 0.0]")), "");
  msg = load_error(replace(replace(kGood, "\n[[material]]", periodic + "\n[[material]]"),
                           "gravity = [0.0, -9.81]",
                           "gravity = [0.0, -9.81]\nwalls.floor = { angular_velocity = 1.0 }"));
  EXPECT_NE(msg.find("walls.floor key 'angular_velocity': a plane or box wall cannot turn with periodic"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, BoxWallRotationsAreReadAndChecked) {
  // 2D: degrees counter-clockwise; the box's own axes are the rotation's
  // columns (cos, sin) and (-sin, cos).
  const std::string plate =
      "\n[[wall]]\nname = \"baffle\"\nbox = { min = [0.002, 0.0], max = [0.002, 0.002], rotation = 30.0 }\n"
      "material = \"sand\"\n";
  const std::string good = replace(kGood, "[[particles]]", plate + "\n[[particles]]");
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& axes = scene.simulation.walls[1].axes;
    const double c = std::sqrt(3.0) / 2.0;
    EXPECT_NEAR(axes(0, 0), c, 1e-15);
    EXPECT_NEAR(axes(1, 0), 0.5, 1e-15);
    EXPECT_NEAR(axes(0, 1), -0.5, 1e-15);
    EXPECT_NEAR(axes(1, 1), c, 1e-15);
  }
  auto msg = load_error(replace(good, "rotation = 30.0", "rotation = \"30\""));
  EXPECT_NE(msg.find("key 'rotation'"), std::string::npos) << msg;
  // 3D: { axis, angle }; 90 degrees about z turns x into y.
  std::string good3 = in_3d(kGood);
  good3 = replace(
      good3, "[[particles]]",
      "[[wall]]\nname = \"baffle\"\nmaterial = \"sand\"\nbox = { min = [0.002, 0.0, 0.0], max = "
      "[0.002, 0.002, 0.002], rotation = { axis = [0.0, 0.0, 2.0], angle = 90.0 } }\n\n[[particles]]");
  ASSERT_EQ(load_error(good3), "");
  {
    const auto scene = built_scene<3>(good3);
    Eigen::Matrix3d expected;
    expected << 0, -1, 0, 1, 0, 0, 0, 0, 1;
    EXPECT_LT((scene.simulation.walls[1].axes - expected).norm(), 1e-15);
  }
  msg = load_error(replace(good3, "rotation = { axis = [0.0, 0.0, 2.0], angle = 90.0 }", "rotation = 90.0"));
  EXPECT_NE(msg.find("key 'rotation': must be a table: rotation = { axis = [x, y, z], angle = degrees }"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good3, "axis = [0.0, 0.0, 2.0]", "axis = [0.0, 0.0, 0.0]"));
  EXPECT_NE(msg.find("rotation key 'axis': must be a non-zero vector"), std::string::npos) << msg;
  msg = load_error(replace(good, "material = \"sand\"\n\n[[particles]]",
                           "material = \"sand\"\nimpermeable = true\n\n[[particles]]"));
  EXPECT_NE(msg.find("key 'impermeable': an impermeable plate lies on the fluid grid's faces: it cannot be "
                     "rotated"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, OverlappingParticlesAtStartAreRefused) {
  // A second column 0.2 mm above the first: its discs overlap the first's by 0.8 mm.
  const auto msg = load_error(replace(kGood, "[[stage]]",
                                      "[[particles]]\ngenerator = \"column\"\nmaterial = \"sand\"\n"
                                      "base = [0.0, 0.0002]\ncount = 1\nradius = 0.0005\n\n[[stage]]"));
  EXPECT_NE(msg.find("particles 0 and 3 overlap"), std::string::npos) << msg;
  EXPECT_NE(msg.find("initial_overlap_tolerance"), std::string::npos) << msg;
}

TEST(SceneErrors, NegativeGapIsRefused) {
  const auto msg =
      load_error(replace(kGood, "radius = 0.0005", "radius = 0.0005\naxis = [0.0, 1.0]\ngap = -0.0002"));
  EXPECT_NE(msg.find("key 'gap': must be >= 0 m"), std::string::npos) << msg;
}

TEST(SceneErrors, TimeStepAboveCriticalNamesBoth) {
  const auto msg = load_error(replace(kGood, "time_step = \"auto\"", "time_step = 0.01"));
  EXPECT_NE(msg.find("0.01 s is larger than the critical time step"), std::string::npos) << msg;
  // Friction 0.5, k_t = k_n: the tangential spring turning a disc of 1 mm
  // (alpha = 1/2), sqrt(m / (3 k_t)) with m = 2650 pi (0.5e-3)^2 kg, k = 1e5.
  EXPECT_NE(msg.find("8.329e-05"), std::string::npos) << msg;
}

TEST(SceneErrors, UnknownMaterialIsNamed) {
  const auto msg = load_error(replace(kGood, "material = \"sand\"\nbase", "material = \"snad\"\nbase"));
  EXPECT_NE(msg.find("no material named \"snad\" (did you mean \"sand\"?)"), std::string::npos) << msg;
}

TEST(SceneErrors, SyntaxErrorHasALine) {
  const auto msg = load_error(replace(kGood, "dimension = 2", "dimension = = 2"));
  EXPECT_NE(msg.find(":3:"), std::string::npos) << msg;
  EXPECT_NE(msg.find("TOML syntax"), std::string::npos) << msg;
}

TEST(SceneErrors, BadDimension) {
  const auto msg = load_error(replace(kGood, "dimension = 2", "dimension = 4"));
  EXPECT_NE(msg.find("must be 2 (discs) or 3 (spheres), got 4"), std::string::npos) << msg;
}

// A good scene with a pore fluid, and its errors.
std::string with_fluid(const std::string& extra = "") {
  return std::string(kGood) + R"(
[fluid]
density = 1000.0
viscosity = 1.0e-3
bulk_modulus = 1e7
drag = "darcy"

[fluid.grid]
origin = [-0.0005, 0.0]
cells = [1, 2]
size = [0.001, 0.002]

[fluid.permeability]
model = "kozeny_carman"

[fluid.boundary]
y_max = { type = "drained", pressure = 0.0 }
)" + extra;
}

TEST(SceneErrors, GoodFluidSceneLoads) { EXPECT_EQ(load_error(with_fluid()), ""); }

TEST(SceneErrors, AnAutomaticTimeStepThatIsNoneIsRefused) {
  // A density of 1e-300 kg/m^3 with a pore fluid makes the critical step
  // (here the drag's relaxation time, mass over drag) underflow to 0; the
  // run used to stop at its first step with "time step not set".
  auto msg = load_error(replace(with_fluid(), "density = 2650.0", "density = 1e-300"));
  EXPECT_NE(
      msg.find(":4:13: error: [simulation] key 'time_step': \"auto\" gives 0 s, from a critical time step of "
               "0 s: a density, contact stiffness or pore-fluid value is out of range"),
      std::string::npos)
      << msg;
  // Every particle fixed: no critical step to take a fraction of.
  const std::string fixed = "[[particles]]\ngenerator = \"column\"\nmaterial = \"sand\"\nfixed = true\n";
  msg = load_error(replace(kGood, "[[particles]]\ngenerator = \"column\"\nmaterial = \"sand\"\n", fixed));
  EXPECT_NE(msg.find("key 'time_step': \"auto\" needs a particle free to move"), std::string::npos) << msg;
}

TEST(SceneErrors, KozenyCarmanDiameterDefaultsToTheSpecificSurfaceOne) {
  // Without `diameter`: the grains' sum d^2 / sum d (discs). Two columns
  // of 3 grains, d = 1 and 0.5 mm: (3 + 0.75) / (3 + 1.5) = 5/6 mm (the
  // arithmetic mean would be 0.75 mm).
  const std::string second = R"(
[[particles]]
generator = "column"
material = "sand"
base = [0.01, 0.0]
count = 3
radius = 0.00025
)";
  const std::string text = replace(with_fluid(), "[fluid]\n", second + "\n[fluid]\n");
  ASSERT_EQ(load_error(text), "");
  EXPECT_NEAR(built_scene<2>(text).fluid->permeability.diameter, 5.0e-3 / 6.0, 1e-15);
  // One whose square underflows to 0 (kappa = 0: the run blew up at its
  // first step) or overflows is refused.
  for (const std::string bad : {"1e-300", "1e200"}) {
    const auto msg = load_error(replace(with_fluid(), "model = \"kozeny_carman\"\n",
                                        "model = \"kozeny_carman\"\ndiameter = " + bad + "\n"));
    EXPECT_NE(
        msg.find("key 'diameter': must be > 0 m, with d^2 neither 0 nor infinite in double precision, got"),
        std::string::npos)
        << msg;
  }
  // Given, it is taken as it is.
  const std::string given =
      replace(with_fluid(), "model = \"kozeny_carman\"\n", "model = \"kozeny_carman\"\ndiameter = 0.0012\n");
  EXPECT_EQ(built_scene<2>(given).fluid->permeability.diameter, 0.0012);
}

TEST(SceneErrors, FluidUnknownKeySuggestsTheNearOne) {
  const auto msg = load_error(replace(with_fluid(), "viscosity = 1.0e-3", "viscosty = 1.0e-3"));
  EXPECT_NE(msg.find("unknown key 'viscosty'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("Did you mean 'viscosity'?"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidDragCellsAreChecked) {
  const std::string good =
      replace(with_fluid(), "drag = \"darcy\"", "drag = \"darcy\"\ndrag_cells = \"overlaps\"");
  EXPECT_EQ(load_error(good), "");
  const std::string bad = replace(good, "\"overlaps\"", "\"overlap\"");
  const auto line =
      1 + std::count(bad.begin(), bad.begin() + static_cast<std::ptrdiff_t>(bad.find("drag_cells")), '\n');
  const auto msg = load_error(bad);
  std::string at = ":";
  at += std::to_string(line);
  at += ':';
  EXPECT_NE(msg.find(at), std::string::npos) << msg;
  EXPECT_NE(
      msg.find("[fluid] key 'drag_cells': \"overlap\" is not allowed; one of \"centre\", \"overlaps\" (did "
               "you mean \"overlaps\"?)"),
      std::string::npos)
      << msg;
}

TEST(SceneErrors, FluidCellsNarrowerThanAGrainAreRefused) {
  const auto msg = load_error(replace(with_fluid(), "size = [0.001, 0.002]", "size = [0.0005, 0.002]"));
  EXPECT_NE(msg.find("[fluid.grid]"), std::string::npos) << msg;
  EXPECT_NE(msg.find("key 'size': cells must be at least one grain diameter wide"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidBoundaryTypeAndValueAreChecked) {
  auto msg = load_error(replace(with_fluid(), "type = \"drained\"", "type = \"drianed\""));
  EXPECT_NE(msg.find("did you mean \"drained\"?"), std::string::npos) << msg;
  msg = load_error(replace(with_fluid(), "pressure = 0.0 }", "inflow = 0.001 }"));
  EXPECT_NE(msg.find("key 'inflow': does not apply to a drained side (give 'pressure')"), std::string::npos)
      << msg;
  msg = load_error(replace(with_fluid(), "y_max = {", "y_mx = {"));
  EXPECT_NE(msg.find("key 'y_mx': is not a side (x_min, x_max, y_min, y_max) (did you mean \"y_max\"?); a "
                     "patch of a side needs 'side', 'from' and 'to'"),
            std::string::npos)
      << msg;
  msg = load_error(
      replace(with_fluid(), "pressure = 0.0 }", "pressure = { times = [0.0, 0.0], values = [1.0, 2.0] } }"));
  EXPECT_NE(msg.find("key 'times': must increase strictly"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidPatchesAreChecked) {
  // The grid is 1 x 2 cells of 1 x 2 mm from x = -0.5 mm: side y_min spans
  // x in [-0.5, 0.5] mm with one face, centred at x = 0.
  const std::string side = "y_max = { type = \"drained\", pressure = 0.0 }\n";
  auto with_patch = [&](const std::string& patch, const std::string& extra = "") {
    return replace(with_fluid(extra), side, side + patch);
  };
  const std::string inlet =
      "inlet = { side = \"y_min\", from = [-0.0005], to = [0.0005], type = \"flux\", inflow = 1e-3 }\n";
  EXPECT_EQ(load_error(with_patch(inlet)), "");
  auto msg = load_error(with_patch(replace(inlet, "to = [0.0005]", "to = [-0.0005]")));
  EXPECT_NE(msg.find("[fluid.boundary].inlet key 'to': must be greater than 'from' along x"),
            std::string::npos)
      << msg;
  msg = load_error(with_patch(replace(inlet, "to = [0.0005]", "to = [0.002]")));
  EXPECT_NE(
      msg.find("key 'to': the patch must lie on side y_min: along x the grid spans [-0.0005, 0.0005] m"),
      std::string::npos)
      << msg;
  msg = load_error(with_patch(replace(inlet, "from = [-0.0005]", "from = [0.0001]")));
  EXPECT_NE(msg.find("key 'from': the patch holds no face of side y_min: a face is in it when its centre is, "
                     "and the faces are 0.001 m wide along x"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(with_patch(inlet + replace(inlet, "inlet =", "second =")));
  EXPECT_NE(msg.find("patch \"second\" shares faces of side y_min with patch \"inlet\""), std::string::npos)
      << msg;
  msg = load_error(with_patch(replace(inlet, "side = \"y_min\"", "side = \"y_mn\"")));
  EXPECT_NE(msg.find("did you mean \"y_min\"?"), std::string::npos) << msg;
  msg = load_error(with_patch(replace(inlet, "type = \"flux\"", "type = \"drained\"")));
  EXPECT_NE(msg.find("key 'inflow': does not apply to a drained patch (give 'pressure')"), std::string::npos)
      << msg;
  // A stage changes a patch by its name, and only its condition.
  const std::string stage = "gravity = [0.0, -9.81]\n";
  auto in_stage = [&](const std::string& change) {
    return replace(with_patch(inlet), stage, stage + "[stage.fluid.boundary]\n" + change);
  };
  EXPECT_EQ(load_error(in_stage("inlet = { type = \"no_flow\" }\n")), "");
  msg = load_error(in_stage("inlt = { type = \"no_flow\" }\n"));
  EXPECT_NE(
      msg.find("key 'inlt': is neither a side (x_min, x_max, y_min, y_max) nor a patch of [fluid.boundary] "
               "(did you mean \"inlet\"?)"),
      std::string::npos)
      << msg;
  msg = load_error(in_stage("inlet = { type = \"no_flow\", from = [0.0] }\n"));
  EXPECT_NE(msg.find("key 'from': a stage changes a patch's condition only"), std::string::npos) << msg;
  // A probe reads a patch's inflow by its name.
  const std::string probe = "\n[[probe]]\nname = \"q\"\nquantity = \"fluid_inflow\"\nside = \"inlet\"\n";
  EXPECT_EQ(load_error(with_patch(inlet, probe)), "");
  EXPECT_EQ(load_error(with_patch(inlet, replace(probe, "fluid_inflow", "side_pressure"))), "");
  msg = load_error(with_patch(inlet, replace(probe, "side = \"inlet\"", "side = \"inlte\"")));
  EXPECT_NE(msg.find("did you mean \"inlet\"?"), std::string::npos) << msg;
  // The seepage column's analysis compares with a 1D solution: whole sides only.
  msg = load_error(with_patch(inlet, "\n[analysis]\nkind = \"seepage_column\"\n"));
  EXPECT_NE(msg.find("takes whole sides; the scene's [fluid.boundary] has patches (\"inlet\")"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, FluidSourcesAreChecked) {
  // The grid is 1 x 2 cells of 1 x 2 mm: x in [-0.5, 0.5] mm, y in [0, 4] mm.
  const std::string well = "\n[[fluid.source]]\nname = \"well\"\nposition = [0.0, 0.001]\ninflow = 1e-9\n";
  ASSERT_EQ(load_error(with_fluid(well)), "");
  {
    // A second source, holding 50 Pa in the upper cell.
    const std::string held =
        "\n[[fluid.source]]\nname = \"head\"\nposition = [0.0, 0.003]\npressure = 50.0\n";
    const auto scene = built_scene<2>(with_fluid(well + held));
    ASSERT_EQ(scene.fluid->sources.size(), 2U);
    EXPECT_EQ(scene.fluid->sources[0].type, FluidSourceType::inflow);
    EXPECT_EQ(scene.fluid->sources[0].value.at(0.0), 1e-9);
    EXPECT_EQ(scene.fluid->sources[1].name, "head");
    EXPECT_EQ(scene.fluid->sources[1].type, FluidSourceType::pressure);
    EXPECT_EQ(scene.fluid->sources[1].value.at(0.0), 50.0);
    EXPECT_EQ(scene.fluid->source_cell(0), 0U);  // y = 1 mm: the first cell
    EXPECT_EQ(scene.fluid->source_cell(1), 1U);
  }
  auto expect = [&](const std::string& text, const std::string& wanted) {
    const auto msg = load_error(text);
    EXPECT_NE(msg.find(wanted), std::string::npos) << msg;
    EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  };
  expect(
      with_fluid(replace(well, "[0.0, 0.001]", "[0.0, 0.005]")),
      "[[fluid.source]] #1 key 'position': must lie in the fluid grid: y = 0.005 m is outside [0, 0.004] m");
  expect(with_fluid(replace(well, "[0.0, 0.001]", "[0.0]")), "key 'position'");
  expect(with_fluid(replace(well, "\"well\"", "\"y_max\"")),
         "[[fluid.source]] #1 key 'name': \"y_max\" is already a side, a patch or a source of the fluid");
  expect(with_fluid(well + well), "[[fluid.source]] #2 key 'name': \"well\" is already a side");
  expect(with_fluid(replace(well, "inflow = 1e-9\n", "")),
         "[[fluid.source]] #1: give one of 'inflow' (m^2/s per metre into the pore water, negative out; a "
         "number "
         "or a series) and 'pressure' (Pa, the excess pore pressure it holds in its cell)");
  expect(with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\npressure = 1.0")), "give one of 'inflow'");
  expect(
      with_fluid(well + replace(replace(well, "\"well\"", "\"other\""), "[0.0, 0.001]", "[0.0, 0.0015]")),
      "[[fluid.source]] #2 key 'position': lies in the cell of source \"well\": each source needs a cell of "
      "its own");
  // A drain holds a pressure, taking water out only.
  {
    const auto scene =
        built_scene<2>(with_fluid(replace(well, "inflow = 1e-9", "pressure = 5.0\ndrain = true")));
    EXPECT_TRUE(scene.fluid->sources[0].drain);
    EXPECT_FALSE(built_scene<2>(with_fluid(well)).fluid->sources[0].drain);
  }
  expect(
      with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\ndrain = true")),
      "[[fluid.source]] #1 key 'drain': a drain holds a 'pressure' and takes water out only while the water "
      "around it stands above it: give it 'pressure' (Pa), not 'inflow'");
  expect(with_fluid(replace(well, "inflow = 1e-9", "pressure = 5.0\ndrain = 1")), "key 'drain'");
  expect(with_fluid(replace(well, "inflow = 1e-9", "inflow = { times = [0.0, 1.0], values = [1e-9] }")),
         "key 'values': must have as many entries as 'times'");
  // A well's radius: below its cell's equivalent radius, Peaceman's for
  // these 1 x 2 mm cells, (e^-gamma / 4) sqrt(1 + 4) mm = 0.3139 mm.
  {
    const auto scene =
        built_scene<2>(with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\nradius = 1e-4")));
    EXPECT_EQ(scene.fluid->sources[0].radius, 1e-4);
    EXPECT_NEAR(scene.fluid->equivalent_radius(0),
                0.25 * std::exp(-0.5772156649015329) * std::sqrt(5.0) * 1e-3, 1e-15);
  }
  expect(with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\nradius = 0.0")),
         "[[fluid.source]] #1 key 'radius': must be > 0 m, the well's radius, got 0");
  expect(with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\nradius = 0.001")),
         "[[fluid.source]] #1 key 'radius': must be less than its cell's equivalent radius, 0.000313");
  {
    // In 3D only a cubic cell and isotropic permeability have one.
    const std::string cubic =
        replace(replace(replace(in_3d(with_fluid(replace(replace(well, "[0.0, 0.001]", "[0.0, 0.0, 0.0015]"),
                                                         "inflow = 1e-9", "inflow = 1e-9\nradius = 1e-4"))),
                                "origin = [-0.0005, 0.0]", "origin = [-0.0005, -0.0005, 0.0]"),
                        "cells = [1, 2]", "cells = [1, 1, 4]"),
                "size = [0.001, 0.002]", "size = [0.001, 0.001, 0.001]");
    ASSERT_EQ(load_error(cubic), "");
    EXPECT_NEAR(built_scene<3>(cubic).fluid->equivalent_radius(0), 0.31487023135962e-3, 1e-15);
    expect(
        replace(replace(cubic, "cells = [1, 1, 4]", "cells = [1, 1, 2]"), "size = [0.001, 0.001, 0.001]",
                "size = [0.001, 0.001, 0.002]"),
        "key 'radius': in 3D a well's radius needs its cell to be a cube (0.001 x 0.001 x 0.002 m here) and "
        "the permeability the same along x, y and z");
    expect(replace(cubic, "model = \"kozeny_carman\"",
                   "model = \"constant\"\nhydraulic_conductivity = [1e-3, 1e-3, 2e-3]"),
           "key 'radius': in 3D a well's radius needs its cell to be a cube");
    // A screened well: its axis (x, y) and the screen's extent along z,
    // through cells of any height (its index is Peaceman's across it, 2D:
    // 0.1985 mm for these 1 x 1 mm cells); 0.5, 1, 1 and 0.5 mm of it in
    // the four cells.
    const std::string screened = replace(
        replace(cubic, "position = [0.0, 0.0, 0.0015]", "position = [0.0, 0.0]\nscreen = [0.0005, 0.0035]"),
        "cells = [1, 1, 4]", "cells = [1, 1, 4]");
    ASSERT_EQ(load_error(screened), "");
    {
      const auto scene = built_scene<3>(screened);
      const auto& f = *scene.fluid;
      EXPECT_TRUE(f.sources[0].screened());
      EXPECT_EQ(f.sources[0].position[2], 0.002);
      EXPECT_NEAR(f.equivalent_radius(0), 0.19850590409582e-3, 1e-15);
      EXPECT_EQ(source_cells(f.grid, f.sources[0]).size(), 4U);
      EXPECT_NEAR(source_cells(f.grid, f.sources[0])[0].length, 0.0005, 1e-15);
      EXPECT_NEAR(source_cells(f.grid, f.sources[0])[1].length, 0.001, 1e-15);
    }
    ASSERT_EQ(load_error(replace(replace(screened, "cells = [1, 1, 4]", "cells = [1, 1, 2]"),
                                 "size = [0.001, 0.001, 0.001]", "size = [0.001, 0.001, 0.002]")),
              "");
    expect(replace(screened, "position = [0.0, 0.0]", "position = [0.0, 0.0, 0.002]"),
           "key 'position': with a 'screen' along z is the well's line, [x, y]: the screen gives its extent "
           "along z");
    expect(replace(screened, "[0.0005, 0.0035]", "[0.0035, 0.0005]"),
           "key 'screen': must be [from, to] along z, from < to, in the fluid grid's [0, 0.004] m; got "
           "[0.0035, 0.0005] m");
    expect(replace(screened, "[0.0005, 0.0035]", "[0.0005, 0.0045]"), "key 'screen': must be [from, to]");
    // A probe of the screen's cells: a column per cell, in order along it.
    const std::string probe =
        "\n[[probe]]\nname = \"q\"\nquantity = \"screen_inflow_profile\"\nside = \"well\"\n";
    {
      const auto scene = built_scene<3>(screened + probe);
      std::vector<std::string> names;
      for (const auto& p : scene.output.probes) {
        if (p.quantity != ProbeQuantity::screen_inflow) continue;
        EXPECT_EQ(p.screen_cell, names.size());
        names.push_back(p.name);
      }
      EXPECT_EQ(names, (std::vector<std::string>{"q_0", "q_1", "q_2", "q_3"}));
    }
    expect(screened + probe + "component = \"x\"\n",
           "key 'component': does not apply to quantity \"screen_inflow_profile\"");
    expect(cubic + probe,
           "key 'quantity': \"screen_inflow_profile\" reads a screened well's cells: the scene has "
           "no [[fluid.source]] with a 'screen'");
    expect(screened + replace(probe, "side = \"well\"", "side = \"x_min\""),
           "key 'side': \"x_min\" is not allowed; one of \"well\"");
    // Nor do the other probes of the pore water take a component.
    expect(screened + replace(probe, "screen_inflow_profile", "fluid_inflow") + "component = \"x\"\n",
           "key 'component': does not apply to quantity \"fluid_inflow\"");
    expect(screened +
               "\n[[probe]]\nname = \"u\"\nquantity = \"pore_pressure_profile\"\nfrom = [0.0, 0.0, 0.0]\n"
               "to = [0.0, 0.0, 0.004]\npoints = 3\nwall = \"floor\"\n",
           "key 'wall': does not apply to quantity \"pore_pressure_profile\"");
    // Along x (a horizontal drain): its line is [y, z], the screen along x.
    {
      const auto scene =
          built_scene<3>(replace(replace(screened, "position = [0.0, 0.0]", "position = [0.0, 0.0015]"),
                                 "screen = [0.0005, 0.0035]", "screen = [-0.0005, 0.0005]\naxis = \"x\""));
      EXPECT_EQ(scene.fluid->sources[0].screen_axis, 0);
      EXPECT_EQ(scene.fluid->sources[0].position[0], 0.0);
      EXPECT_EQ(scene.fluid->sources[0].position[2], 0.0015);
      EXPECT_EQ(source_cells(scene.fluid->grid, scene.fluid->sources[0]).size(), 1U);
    }
    expect(replace(screened, "screen = [0.0005, 0.0035]", "screen = [0.0005, 0.0035]\naxis = \"x\""),
           "key 'screen': must be [from, to] along x, from < to, in the fluid grid's [-0.0005, 0.0005] m");
    expect(replace(screened, "position = [0.0, 0.0]", "position = [0.0, 0.0, 0.001]\naxis = \"y\""),
           "key 'position': with a 'screen' along y is the well's line, [x, z]");
    expect(replace(screened, "screen = [0.0005, 0.0035]", "screen = [0.0005, 0.0035]\naxis = \"w\""),
           "key 'axis'");
    expect(replace(cubic, "radius = 1e-4", "radius = 1e-4\naxis = \"z\""),
           "key 'axis': is a screened well's: give it a 'screen' = [from, to] too");
    expect(replace(screened, "radius = 1e-4", "radius = 3e-4"),
           "key 'radius': must be less than the equivalent radius of the cells the screen passes through, "
           "0.000198505904");
    expect(replace(screened, "\nradius = 1e-4", ""), "key 'screen': needs the well's 'radius' (m)");
    expect(replace(screened, "[[fluid.source]]",
                   "[[fluid.source]]\nname = \"point\"\nposition = [0.0, 0.0, 0.0025]\ninflow = 0.0\n\n"
                   "[[fluid.source]]"),
           "[[fluid.source]] #2 key 'screen': passes through a cell of source \"point\": each source needs "
           "a cell of its own");
  }
  expect(
      with_fluid(replace(well, "inflow = 1e-9", "inflow = 1e-9\nradius = 1e-4\nscreen = [0.0, 0.001]")),
      "[[fluid.source]] #1 key 'screen': is for 3D grids: in 2D a source is already a well through the whole "
      "thickness");
  // A stage changes a source's inflow by its name, and nothing else.
  const std::string stage = "gravity = [0.0, -9.81]\n";
  auto in_stage = [&](const std::string& change, const std::string& sources = "") {
    return replace(with_fluid(sources.empty() ? well : sources), stage,
                   stage + "[stage.fluid.sources]\n" + change);
  };
  EXPECT_EQ(load_error(in_stage("well = { inflow = 0.0 }\n")), "");
  EXPECT_EQ(load_error(in_stage("well = { pressure = 20.0 }\n")), "");
  expect(in_stage("well = { }\n"), "give one of 'inflow'");
  {
    const auto scene =
        built_scene<2>(in_stage("well = { inflow = { times = [0.0, 1.0], values = [0.0, 3e-9] } }\n"));
    ASSERT_EQ(scene.stages[0].fluid_sources.size(), 1U);
    EXPECT_NEAR(scene.stages[0].fluid_sources[0].value.at(0.5), 1.5e-9, 1e-24);
  }
  expect(in_stage("wel = { inflow = 0.0 }\n"),
         "is not a [[fluid.source]] of the scene (did you mean \"well\"?)");
  expect(in_stage("well = { inflow = 0.0, position = [0.0, 0.002] }\n"),
         "key 'position': a stage changes a source's inflow or pressure only");
  expect(in_stage("well = 0.0\n"), "must be a table, e.g. { inflow = 0.0 }");
  expect(replace(with_fluid(), stage, stage + "[stage.fluid.sources]\nwell = { inflow = 0.0 }\n"),
         "the scene has no [[fluid.source]]");
  // Probes read a source by its name: the flow it gives, the pressure in its cell.
  const std::string probe = "\n[[probe]]\nname = \"q\"\nquantity = \"fluid_inflow\"\nside = \"well\"\n";
  EXPECT_EQ(load_error(with_fluid(well + probe)), "");
  EXPECT_EQ(load_error(with_fluid(well + replace(probe, "fluid_inflow", "side_pressure"))), "");
  expect(with_fluid(well + replace(probe, "\"well\"", "\"wel\"")), "did you mean \"well\"?");
}

TEST(SceneErrors, FluidBarriersAreChecked) {
  // The grid is 1 x 2 cells of 1 x 2 mm from y = 0: the one plane of faces
  // between cells along y is at y = 2 mm, and its face is centred at x = 0.
  const std::string good =
      "\n[[fluid.barrier]]\nname = \"pile\"\naxis = \"y\"\nat = 0.002\nfrom = [-0.0005]\nto = [0.0005]\n";
  EXPECT_EQ(load_error(with_fluid(good)), "");
  auto msg = load_error(with_fluid(replace(good, "at = 0.002", "at = 0.0015")));
  EXPECT_NE(
      msg.find("[[fluid.barrier]] #1 key 'at': must be on a plane of faces between two cells inside the "
               "grid: along y they are at 0 + n x 0.002 m, n = 1 .. 1 (the nearest: 0.002 m)"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;                  // file:line:column
  msg = load_error(with_fluid(replace(good, "at = 0.002", "at = 0.004")));  // the grid's top side
  EXPECT_NE(msg.find("key 'at': must be on a plane of faces between two cells inside the grid"),
            std::string::npos)
      << msg;
  msg = load_error(with_fluid(replace(good, "from = [-0.0005]", "from = [0.0001]")));
  EXPECT_NE(msg.find("key 'from': the barrier holds no face"), std::string::npos) << msg;
  msg = load_error(
      with_fluid(replace(replace(good, "axis = \"y\"", "axis = \"x\""), "at = 0.002", "at = 0.0")));
  EXPECT_NE(msg.find("key 'axis': the grid has one cell along x: there is no face between cells to close"),
            std::string::npos)
      << msg;
  msg = load_error(with_fluid(replace(good, "axis = \"y\"", "axis = \"z\"")));
  EXPECT_NE(msg.find("key 'axis'"), std::string::npos) << msg;
  msg = load_error(with_fluid(replace(good, "to = [0.0005]", "to = [0.0005]\nthickness = 0.001")));
  EXPECT_NE(msg.find("unknown key 'thickness'"), std::string::npos) << msg;
}

/// The good scene with one more wall (a [[wall]] table), with its pore fluid or without.
std::string with_wall(const std::string& wall, bool fluid = true) {
  const std::string dem = replace(kGood, "[[particles]]", wall + "\n[[particles]]");
  if (!fluid) return dem;
  return with_fluid().replace(0, std::string(kGood).size(), dem);
}

TEST(SceneErrors, AnImpermeablePlateCannotOscillate) {
  // A plate on the plane of faces between the grid's cells is a barrier
  // fixed in the fluid grid (as in ImpermeableWallsAreChecked).
  const std::string plate =
      "\n[[wall]]\nname = \"pile\"\nbox = { min = [-0.0005, 0.002], max = [0.0005, 0.002] }\n"
      "material = \"sand\"\nimpermeable = true\noscillation = { amplitude = [0.001, 0.0], frequency = 20.0 "
      "}\n";
  const auto msg = load_error(with_wall(plate));
  EXPECT_NE(msg.find("[[wall]] #2 key 'impermeable': an impermeable wall cannot move"), std::string::npos)
      << msg;
}

TEST(SceneErrors, ImpermeableWallsAreChecked) {
  // A plate on the one plane of faces between the grid's cells (y = 2 mm),
  // across the grid's width; the discs of the column touch it, no more.
  const std::string plate =
      "\n[[wall]]\nname = \"pile\"\nbox = { min = [-0.0005, 0.002], max = [0.0005, 0.002] }\n"
      "material = \"sand\"\nimpermeable = true\n";
  EXPECT_EQ(load_error(with_wall(plate)), "");
  // A box with a thickness, or a plane, that is impermeable displaces the
  // fluid and closes the faces it covers: along the grid's axes only.
  const std::string block =
      "\n[[wall]]\nname = \"block\"\nbox = { min = [0.0006, 0.0], max = [0.0016, 0.004] }\n"
      "material = \"sand\"\nimpermeable = true\n";
  const auto with_block = built_scene<2>(with_wall(block));
  EXPECT_EQ(with_block.fluid->solid_walls, std::vector<std::size_t>{1});
  EXPECT_EQ(with_block.fluid->impermeable_walls, std::vector<std::size_t>{1});
  EXPECT_NE(describe_patches_and_barriers(*with_block.fluid, with_block.simulation.walls)
                .find("wall block displaces the fluid: a box, impermeable (closes the faces it covers)\n"),
            std::string::npos);
  auto msg = load_error(
      with_wall(replace(block, "max = [0.0016, 0.004] }", "max = [0.0016, 0.004], rotation = 10.0 }")));
  EXPECT_NE(
      msg.find("[[wall]] #2 key 'impermeable': an impermeable box closes the fluid grid's faces it covers, "
               "so it lies along the grid's axes: it cannot be rotated"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  const std::string platen = replace(plate, "box = { min = [-0.0005, 0.002], max = [0.0005, 0.002] }",
                                     "point = [0.0, 0.004]\nnormal = [0.0, -1.0]");
  EXPECT_EQ(load_error(with_wall(platen + "velocity = [0.0, -0.01]\n")), "");
  msg = load_error(with_wall(replace(platen, "normal = [0.0, -1.0]", "normal = [0.1, -1.0]")));
  EXPECT_NE(
      msg.find("key 'impermeable': an impermeable plane needs its normal along an axis of the fluid grid"),
      std::string::npos)
      << msg;
  msg = load_error(with_wall(block + "displaces_fluid = false\n"));
  EXPECT_NE(
      msg.find("key 'displaces_fluid': an impermeable box with a thickness, or plane, displaces the fluid"),
      std::string::npos)
      << msg;
  EXPECT_EQ(load_error(with_wall(block + "displaces_fluid = true\n")), "");
  msg = load_error(with_wall(block, false));
  EXPECT_NE(msg.find("key 'impermeable': needs a pore fluid to take up: the scene has no [fluid] table"),
            std::string::npos)
      << msg;
  msg = load_error(with_wall(plate + "velocity = [0.0, 0.01]\n"));
  EXPECT_NE(msg.find("key 'impermeable': an impermeable wall cannot move"), std::string::npos) << msg;
  msg = load_error(replace(with_wall(plate), "gravity = [0.0, -9.81]",
                           "gravity = [0.0, -9.81]\nwalls.pile = { velocity = [0.0, 0.01] }"));
  EXPECT_NE(msg.find("walls.pile key 'velocity': an impermeable wall cannot move"), std::string::npos) << msg;
  msg = load_error(with_wall(plate, false));
  EXPECT_NE(msg.find("key 'impermeable': needs a pore fluid to keep out: the scene has no [fluid] table"),
            std::string::npos)
      << msg;
  msg = load_error(with_wall(replace(replace(plate, "0.002]", "0.003]"), "0.002]", "0.003]")));
  EXPECT_NE(
      msg.find("key 'impermeable': the plate at y = 0.003 m: must be on a plane of faces between two cells "
               "inside the grid: along y they are at 0 + n x 0.002 m, n = 1 .. 1 (the nearest: 0.002 m)"),
      std::string::npos)
      << msg;
  msg = load_error(with_wall(replace(plate, "min = [-0.0005, 0.002]", "min = [0.0001, 0.002]")));
  EXPECT_NE(msg.find("key 'impermeable': the plate at y = 0.002 m: the barrier holds no face"),
            std::string::npos)
      << msg;
  msg = load_error(with_wall(replace(plate, "box = { min = [-0.0005, 0.002], max = [0.0005, 0.002] }",
                                     "box = { min = [0.0006, 0.0], max = [0.0006, 0.004] }")));
  EXPECT_NE(msg.find("key 'impermeable': the plate at x = 0.0006 m: the grid has one cell along x"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, FluidPreconditionerIsChecked) {
  const std::string base = "drag = \"darcy\"\n";
  EXPECT_EQ(load_error(replace(with_fluid(), base, base + "preconditioner = \"multigrid\"\n")), "");
  auto msg = load_error(replace(with_fluid(), base, base + "preconditioner = \"multgrid\"\n"));
  EXPECT_NE(msg.find("did you mean \"multigrid\"?"), std::string::npos) << msg;
  msg =
      load_error(replace(with_fluid(), base, base + "solver = \"cholesky\"\npreconditioner = \"jacobi\"\n"));
  EXPECT_NE(msg.find("key 'preconditioner': applies to solver = \"cg\" only"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
}

TEST(SceneErrors, BoxProbesAreChecked) {
  const std::string probe =
      "\n[[probe]]\nname = \"bed\"\nquantity = \"mean_particle_position\"\nmin = [0.0, 0.0]\n"
      "max = [0.001, 0.01]\ncomponent = \"y\"\n";
  const std::string good = replace(kGood, "[[stage]]", probe + "\n[[stage]]");
  EXPECT_EQ(load_error(good), "");
  auto msg = load_error(replace(good, "max = [0.001, 0.01]", "max = [0.001, 0.0]"));
  EXPECT_NE(
      msg.find("[[probe]] #1 key 'max': must be greater than 'min' along every axis; along y min = 0 and "
               "max = 0"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "component = \"y\"", "component = \"norm\""));
  EXPECT_NE(msg.find("key 'component'"), std::string::npos) << msg;
  msg = load_error(replace(good, "mean_particle_position", "particles_in_box"));
  EXPECT_NE(msg.find("key 'component': does not apply to quantity \"particles_in_box\""), std::string::npos)
      << msg;
  msg = load_error(replace(good, "mean_particle_position", "kinetic_energy"));
  EXPECT_NE(msg.find("key 'min': does not apply to quantity \"kinetic_energy\""), std::string::npos) << msg;
  msg = load_error(replace(good, "min = [0.0, 0.0]\n", ""));
  EXPECT_NE(msg.find("missing required key 'min'"), std::string::npos) << msg;
}

TEST(SceneErrors, StressAndPorosityProbesAreChecked) {
  // The box as for the other box probes; stress needs a tensor component
  // of the scene's dimension (or "mean"), porosity takes none.
  const std::string probe =
      "\n[[probe]]\nname = \"s\"\nquantity = \"stress\"\nmin = [-0.001, 0.0]\nmax = [0.001, 0.01]\n"
      "component = \"yy\"\n";
  const std::string good = replace(kGood, "[[stage]]", probe + "\n[[stage]]");
  EXPECT_EQ(load_error(good), "");
  EXPECT_EQ(load_error(replace(good, "\"yy\"", "\"mean\"")), "");
  auto msg = load_error(replace(good, "\"yy\"", "\"zz\""));  // the scene is 2D
  EXPECT_NE(msg.find("[[probe]] #1 key 'component'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\"xx\", \"yy\", \"xy\", \"mean\""), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "component = \"yy\"\n", ""));
  EXPECT_NE(msg.find("missing required key 'component'"), std::string::npos) << msg;
  msg = load_error(replace(good, "quantity = \"stress\"", "quantity = \"porosity\""));
  EXPECT_NE(msg.find("key 'component': does not apply to quantity \"porosity\""), std::string::npos) << msg;
  EXPECT_EQ(load_error(replace(replace(good, "quantity = \"stress\"", "quantity = \"porosity\""),
                               "component = \"yy\"\n", "")),
            "");
  msg = load_error(replace(good, "max = [0.001, 0.01]", "max = [0.001, -0.01]"));
  EXPECT_NE(msg.find("key 'max': must be greater than 'min'"), std::string::npos) << msg;
  // The fabric tensor: the same box and components, but no "mean" (its
  // trace is 1).
  const std::string fabric = replace(good, "quantity = \"stress\"", "quantity = \"fabric\"");
  EXPECT_EQ(load_error(fabric), "");
  msg = load_error(replace(fabric, "\"yy\"", "\"mean\""));
  EXPECT_NE(msg.find("[[probe]] #1 key 'component'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\"xx\", \"yy\", \"xy\""), std::string::npos) << msg;
  EXPECT_EQ(msg.find("\"xy\", \"mean\""), std::string::npos) << msg;
  msg = load_error(replace(fabric, "component = \"yy\"\n", ""));
  EXPECT_NE(msg.find("missing required key 'component'"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidProbeWithoutFluidIsRefused) {
  const auto msg =
      load_error(std::string(kGood) +
                 "\n[[probe]]\nname = \"u\"\nquantity = \"pore_pressure\"\nposition = [0.0, 0.001]\n");
  EXPECT_NE(msg.find("needs a pore fluid: the scene has no [fluid] table"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidForceProbesAreChecked) {
  // The pore fluid's force on a box's grains (a component or the norm) or
  // on one grain: both need a [fluid], and take the keys of their kind.
  const std::string probes =
      "\n[[probe]]\nname = \"bed\"\nquantity = \"fluid_force\"\nmin = [-0.001, 0.0]\nmax = [0.001, 0.01]\n"
      "component = \"norm\"\n\n[[probe]]\nname = \"one\"\nquantity = \"particle_fluid_force\"\n"
      "particle = 0\ncomponent = \"y\"\n";
  const std::string good = with_fluid() + probes;
  EXPECT_EQ(load_error(good), "");
  auto msg = load_error(std::string(kGood) + probes);
  EXPECT_NE(
      msg.find("[[probe]] #1 key 'quantity': \"fluid_force\" needs a pore fluid: the scene has no [fluid] "
               "table"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "max = [0.001, 0.01]", "max = [0.001, 0.0]"));
  EXPECT_NE(msg.find("key 'max': must be greater than 'min' along every axis"), std::string::npos) << msg;
  msg = load_error(replace(good, "component = \"norm\"", "component = \"z\""));  // the scene is 2D
  EXPECT_NE(msg.find("[[probe]] #1 key 'component'"), std::string::npos) << msg;
  msg = load_error(replace(good, "component = \"norm\"\n", "component = \"norm\"\nparticle = 0\n"));
  EXPECT_NE(msg.find("key 'particle': does not apply to quantity \"fluid_force\""), std::string::npos) << msg;
  msg = load_error(replace(good, "particle = 0\n", ""));
  EXPECT_NE(msg.find("[[probe]] #2"), std::string::npos) << msg;
  EXPECT_NE(msg.find("missing required key 'particle'"), std::string::npos) << msg;
  msg = load_error(replace(good, "particle = 0\n", "particle = 100000\n"));
  EXPECT_NE(msg.find("key 'particle': must be in 0.."), std::string::npos) << msg;
}

TEST(SceneErrors, ProbeStopConditionsAreChecked) {
  // stop_when = { probe = NAME, above/below = value }: a [[probe]] by its
  // name (a near miss suggested), at least one finite threshold.
  const std::string good =
      replace(kGood, "gravity = [0.0, -9.81]\n",
              "gravity = [0.0, -9.81]\nstop_when = { probe = \"top_y\", below = 0.001 }\n\n"
              "[[probe]]\nname = \"top_y\"\nquantity = \"particle_position\"\n"
              "particle = \"top\"\ncomponent = \"y\"\n");
  EXPECT_EQ(load_error(good), "");
  EXPECT_EQ(load_error(replace(good, "below = 0.001", "above = 0.0, below = 0.001")), "");
  auto msg = load_error(replace(good, "probe = \"top_y\"", "probe = \"top_z\""));
  EXPECT_NE(
      msg.find("[[stage]] #1 stop_when key 'probe': no probe named \"top_z\" (did you mean \"top_y\"?)"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, ", below = 0.001", ""));
  EXPECT_NE(msg.find("key 'probe': needs 'above' or 'below'"), std::string::npos) << msg;
  msg = load_error(replace(good, "below = 0.001", "below = nan"));
  EXPECT_NE(msg.find("key 'below'"), std::string::npos) << msg;
  msg = load_error(replace(good, "probe = \"top_y\", ", ""));
  EXPECT_NE(msg.find("key 'below': applies to a probe: give 'probe'"), std::string::npos) << msg;
  msg = load_error(replace(kGood, "gravity = [0.0, -9.81]\n",
                           "gravity = [0.0, -9.81]\nstop_when = { probe = \"top_y\", below = 0.001 }\n"));
  EXPECT_NE(msg.find("no probe named \"top_y\": the scene has no [[probe]]"), std::string::npos) << msg;
  msg = load_error(replace(good, "probe = \"top_y\", below = 0.001", "check_interval = 10"));
  EXPECT_NE(msg.find("needs 'kinetic_energy_below', 'unbalanced_force_below' or 'probe'"), std::string::npos)
      << msg;
}

TEST(SceneErrors, TimeStepAboveTheCoupledCriticalStepIsRefused) {
  // The dry critical step is 1.44e-4 s; with K_f = 1e7 Pa the pore fluid's
  // undrained stiffness brings it to a few microseconds: 5e-5 s is refused.
  const auto msg = load_error(replace(with_fluid(), "time_step = \"auto\"", "time_step = 5e-5"));
  EXPECT_NE(msg.find("is larger than the critical time step"), std::string::npos) << msg;
  EXPECT_NE(msg.find("K_f/n"), std::string::npos) << msg;
}

TEST(SceneErrors, ContactNetworkSwitchIsABoolean) {
  EXPECT_EQ(load_error(std::string(kGood) + "\n[output]\ncontacts = false\n"), "");
  const auto msg = load_error(std::string(kGood) + "\n[output]\ncontacts = 1\n");
  EXPECT_NE(msg.find("[output] key 'contacts': must be true or false"), std::string::npos) << msg;
  // file:line: kGood's lines, the blank one and [output] come before it.
  const std::string good(kGood);
  const auto line = std::count(good.begin(), good.end(), '\n') + 3;
  EXPECT_NE(msg.find(".toml:" + std::to_string(line) + ":"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidCouplingIntervalIsChecked) {
  const std::string base = "drag = \"darcy\"\n";
  EXPECT_EQ(load_error(replace(with_fluid(), base, base + "steps_per_update = 5\nhold_forces = true\n")), "");
  auto msg = load_error(replace(with_fluid(), base, base + "steps_per_update = 0\n"));
  EXPECT_NE(msg.find("key 'steps_per_update': must be an integer from 1 to 2147483647"), std::string::npos)
      << msg;
  msg = load_error(replace(with_fluid(), base, base + "hold_forces = \"yes\"\n"));
  EXPECT_NE(msg.find("key 'hold_forces': must be true or false"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  // A stage can change both.
  const std::string stage = "gravity = [0.0, -9.81]\n";
  EXPECT_EQ(load_error(replace(with_fluid(), stage,
                               stage + "[stage.fluid]\nsteps_per_update = 20\nhold_forces = true\n")),
            "");
  msg = load_error(replace(with_fluid(), stage, stage + "[stage.fluid]\nsteps_per_update = 3000000000\n"));
  EXPECT_NE(msg.find("[[stage]] #1 fluid key 'steps_per_update': must be an integer from 1 to 2147483647"),
            std::string::npos)
      << msg;
  msg = load_error(replace(with_fluid(), stage, stage + "[stage.fluid]\nhold_forces = 1\n"));
  EXPECT_NE(msg.find("key 'hold_forces': must be true or false"), std::string::npos) << msg;
}

TEST(SceneErrors, FluidWaterLevelIsReadAndChecked) {
  const std::string base = "drag = \"darcy\"\n";
  const std::string good = replace(with_fluid(), base, base + "water_level = 0.05\n");
  ASSERT_EQ(load_error(good), "");
  EXPECT_EQ(built_scene<2>(good).fluid->water_level, 0.05);
  // Without the key: no water outside the grid.
  EXPECT_TRUE(std::isnan(built_scene<2>(with_fluid()).fluid->water_level));
  auto msg = load_error(replace(with_fluid(), base, base + "water_level = nan\n"));
  EXPECT_NE(msg.find("key 'water_level': must be a finite number, got nan"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(with_fluid(), base, base + "water_level = \"top\"\n"));
  EXPECT_NE(msg.find("key 'water_level'"), std::string::npos) << msg;
  msg = load_error(replace(with_fluid(), base, base + "water_levle = 0.05\n"));
  EXPECT_NE(msg.find("Did you mean 'water_level'?"), std::string::npos) << msg;
}

TEST(SceneErrors, PeriodicBoundariesAreChecked) {
  // The column stands at x = 0 (discs of r = 0.5 mm, skin 0.1 mm): a period
  // along x must hold it and exceed 2 x (2 r + skin) = 2.2 mm; the floor is
  // parallel to x.
  const std::string periodic = "\n[periodic]\nx = [-0.003, 0.003]\n";
  const std::string good = replace(kGood, "\n[[material]]", periodic + "\n[[material]]");
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  EXPECT_TRUE(scene.simulation.periodic.periodic[0]);
  EXPECT_FALSE(scene.simulation.periodic.periodic[1]);
  EXPECT_DOUBLE_EQ(scene.simulation.periodic.length[0], 0.006);

  auto msg = load_error(replace(good, "x = [-0.003, 0.003]", "x = [0.003, -0.003]"));
  EXPECT_NE(msg.find("[periodic] key 'x': must be [min, max] with max > min"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;                        // file:line:column
  msg = load_error(replace(good, "x = [-0.003, 0.003]", "z = [-0.003, 0.003]"));  // a 2D scene
  EXPECT_NE(msg.find("unknown key 'z'"), std::string::npos) << msg;
  msg = load_error(replace(good, "x = [-0.003, 0.003]", ""));
  EXPECT_NE(msg.find("[periodic]: names no axis"), std::string::npos) << msg;
  msg = load_error(replace(good, "x = [-0.003, 0.003]", "x = [-0.001, 0.001]"));
  EXPECT_NE(msg.find("key 'x': the period 0.002 m must exceed 2 x (2 x largest radius + skin) = 0.0022 m"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "x = [-0.003, 0.003]", "x = [0.0001, 0.006]"));
  EXPECT_NE(
      msg.find("particle 0 starts at x = 0 m, outside the periodic range [periodic] x = [0.0001, 0.006)"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find("[[particles]] #1"), std::string::npos) << msg;
  msg = load_error(replace(good, "x = [-0.003, 0.003]", "y = [-0.003, 0.003]"));
  EXPECT_NE(msg.find("key 'normal': a plane wall must be parallel to the periodic axis y"), std::string::npos)
      << msg;
  const std::string box =
      "\n[[wall]]\nname = \"block\"\nbox = { min = [0.002, 0.0], max = [0.004, 0.001] }\n"
      "material = \"sand\"\n";
  msg = load_error(replace(good, "\n[[particles]]", box + "\n[[particles]]"));
  EXPECT_NE(msg.find("key 'box': a box wall must lie within the periodic range [-0.003, 0.003] along x"),
            std::string::npos)
      << msg;
  // A probe's box may lie across the ends but hold at most one period.
  const std::string probe =
      "\n[[probe]]\nname = \"n\"\nquantity = \"porosity\"\nmin = [0.001, 0.0]\nmax = [0.007, 0.003]\n";
  EXPECT_EQ(load_error(good + probe), "");
  msg = load_error(good + replace(probe, "max = [0.007, 0.003]", "max = [0.008, 0.003]"));
  EXPECT_NE(
      msg.find("key 'max': the box is 0.007 m long along x, longer than the period 0.006 m ([periodic] x)"),
      std::string::npos)
      << msg;
}

// [fluid.grid] axis by axis: each axis uniform (from, to, cells), graded
// (ratio = the last cell's width over the first's) or given by its faces.
TEST(SceneErrors, GradedFluidGridIsReadAndChecked) {
  const std::string uniform = "origin = [-0.0005, 0.0]\ncells = [1, 2]\nsize = [0.001, 0.002]\n";
  const std::string axes =
      "x = { from = -0.0005, to = 0.0005, cells = 1 }\ny = { from = 0.0, to = 0.004, cells = 2, ratio = 1.5 "
      "}\n";
  const std::string good = replace(with_fluid(), uniform, axes);
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  const auto& grid = scene.fluid->grid;
  EXPECT_FALSE(grid.graded(0));
  EXPECT_DOUBLE_EQ(grid.spacing[0], 0.001);
  ASSERT_TRUE(grid.graded(1));
  // Two cells, the second 1.5 x the first: 1.6 and 2.4 mm.
  EXPECT_NEAR(grid.width(1, 0), 0.0016, 1e-15);
  EXPECT_NEAR(grid.width(1, 1), 0.0024, 1e-15);
  const auto faces = replace(good, "y = { from = 0.0, to = 0.004, cells = 2, ratio = 1.5 }",
                             "y = { faces = [0.0, 0.0015, 0.004] }");
  ASSERT_EQ(load_error(faces), "");
  EXPECT_DOUBLE_EQ(built_scene<2>(faces).fluid->grid.face_at(1, 1), 0.0015);
  // A barrier on the graded axis: on its interior face, or refused naming the nearest.
  const std::string barrier =
      "\n[[fluid.barrier]]\nname = \"pile\"\naxis = \"y\"\nat = 0.0015\nfrom = [-0.0005]\nto = [0.0005]\n";
  EXPECT_EQ(load_error(faces + barrier), "");
  EXPECT_EQ(built_scene<2>(faces + barrier).fluid->barrier_faces(0), 1U);
  auto bad = load_error(faces + replace(barrier, "at = 0.0015", "at = 0.0017"));
  EXPECT_NE(
      bad.find(
          "[[fluid.barrier]] #1 key 'at': must be on a plane of faces between two cells inside the grid: "
          "along y (graded) the nearest is at 0.0015 m"),
      std::string::npos)
      << bad;

  auto msg = load_error(replace(with_fluid(), uniform, uniform + axes));
  EXPECT_NE(msg.find("[fluid.grid] key 'origin': the grid is given axis by axis"), std::string::npos) << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(with_fluid(), uniform, "y = { from = 0.0, to = 0.004, cells = 2 }\n"));
  EXPECT_NE(msg.find("[fluid.grid]: the x axis has no table"), std::string::npos) << msg;
  msg = load_error(replace(faces, "faces = [0.0, 0.0015, 0.004]", "faces = [0.0, 0.004, 0.0015]"));
  EXPECT_NE(msg.find("[fluid.grid] y key 'faces': must be finite face coordinates in increasing order"),
            std::string::npos)
      << msg;
  msg = load_error(replace(faces, "faces = [0.0, 0.0015, 0.004]", "faces = [0.0, 0.0008, 0.004]"));
  EXPECT_NE(msg.find("key 'faces': cells must be at least one grain diameter wide: the narrowest along y is "
                     "0.0008 m"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "cells = 2, ratio = 1.5", "cells = 2, ratio = 9.0"));
  EXPECT_NE(msg.find("key 'cells': cells must be at least one grain diameter wide"), std::string::npos)
      << msg;
  msg = load_error(replace(good, "cells = 2, ratio = 1.5", "cells = 2, ratio = -1.5"));
  EXPECT_NE(msg.find("key 'ratio': must be > 0 (the last cell's width over the first's)"), std::string::npos)
      << msg;
  msg = load_error(replace(good, "cells = 2, ratio = 1.5", "cells = 1, ratio = 1.5"));
  EXPECT_NE(msg.find("key 'ratio': grades cells: it needs at least two cells"), std::string::npos) << msg;
  msg = load_error(replace(faces, "faces = [0.0, 0.0015, 0.004]", "faces = [0.0, 0.0015, 0.004], cells = 2"));
  EXPECT_NE(msg.find("key 'cells': give either faces or from, to, cells (and ratio), not both"),
            std::string::npos)
      << msg;
  // Along a periodic axis the cells must be of one size.
  const std::string periodic = "\n[periodic]\nx = [-0.003, 0.003]\n";
  const std::string graded_x = replace(replace(good, "\n[[material]]", periodic + "\n[[material]]"),
                                       "x = { from = -0.0005, to = 0.0005, cells = 1 }",
                                       "x = { from = -0.003, to = 0.003, cells = 3, ratio = 1.2 }");
  msg = load_error(graded_x);
  EXPECT_NE(
      msg.find("key 'ratio': the scene is periodic along x: the grid's cells along it must be of one size"),
      std::string::npos)
      << msg;
  // Graded along another axis: a periodic scene takes it.
  EXPECT_EQ(load_error(replace(graded_x, "ratio = 1.2", "ratio = 1.0")), "");
  EXPECT_EQ(load_error(replace(replace(graded_x, "ratio = 1.2", "ratio = 1.0"), ", ratio = 1.5", "")), "");
}

// A pore fluid in a scene periodic along x: the grid spans the period, and
// its x sides take no condition (they are one face between its ends).
TEST(SceneErrors, PeriodicFluidGridIsChecked) {
  const std::string periodic = "\n[periodic]\nx = [-0.003, 0.003]\n";
  const std::string fluid = replace(with_fluid(), "\n[[material]]", periodic + "\n[[material]]");
  const std::string good = replace(replace(fluid, "origin = [-0.0005, 0.0]", "origin = [-0.003, 0.0]"),
                                   "cells = [1, 2]", "cells = [6, 2]");
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  EXPECT_TRUE(scene.fluid->grid.periodic[0]);
  EXPECT_FALSE(scene.fluid->grid.periodic[1]);

  auto msg = load_error(replace(good, "origin = [-0.003, 0.0]", "origin = [-0.0025, 0.0]"));
  EXPECT_NE(
      msg.find("[fluid.grid] key 'origin': the scene is periodic along x ([periodic] x = [-0.003, 0.003]): "
               "the grid must span the period, from -0.003 m over cells x size = 0.006 m along x; it "
               "spans [-0.0025, 0.0035] m"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "cells = [6, 2]", "cells = [5, 2]"));
  EXPECT_NE(msg.find("[fluid.grid] key 'size': the scene is periodic along x"), std::string::npos) << msg;
  const std::string side = "y_max = { type = \"drained\", pressure = 0.0 }\n";
  msg = load_error(replace(good, side, side + "x_min = { type = \"no_flow\" }\n"));
  EXPECT_NE(
      msg.find("[fluid.boundary] key 'x_min': the scene is periodic along x ([periodic]): the fluid grid "
               "spans the period and its two x sides are one face between its last and first cells, "
               "which takes no condition"),
      std::string::npos)
      << msg;
  msg = load_error(replace(
      good, side, side + "vent = { side = \"x_max\", from = [0.0], to = [0.002], type = \"no_flow\" }\n"));
  EXPECT_NE(msg.find("key 'side': the scene is periodic along x"), std::string::npos) << msg;
  const std::string stage = "gravity = [0.0, -9.81]\n";
  msg = load_error(replace(good, stage, stage + "[stage.fluid.boundary]\nx_max = { type = \"no_flow\" }\n"));
  EXPECT_NE(msg.find("key 'x_max': the scene is periodic along x"), std::string::npos) << msg;
  // A probe of a side's inflow or pressure: not on the periodic axis's sides.
  for (const std::string quantity : {"fluid_inflow", "side_pressure"}) {
    const std::string probe =
        "\n[[probe]]\nname = \"p\"\nquantity = \"" + quantity + "\"\nside = \"y_min\"\n";
    EXPECT_EQ(load_error(good + probe), "") << quantity;
    msg = load_error(good + replace(probe, "y_min", "x_max"));
    EXPECT_NE(msg.find("[[probe]] #1 key 'side': the fluid grid is periodic along x: its side x_max is no "
                       "boundary (allowed: a side along a non-periodic axis, a patch or a source)"),
              std::string::npos)
        << msg;
  }
}

TEST(SceneErrors, WallsThatDisplaceTheFluidAreChecked) {
  // A box beside the column of discs (x from 0.6 mm; the discs reach 0.5 mm).
  const std::string box =
      "\n[[wall]]\nname = \"block\"\nbox = { min = [0.0006, 0.0], max = [0.0016, 0.004] }\n"
      "material = \"sand\"\ndisplaces_fluid = true\n";
  EXPECT_EQ(load_error(with_wall(box)), "");
  // A plane normal to a grid axis (a platen over the column) takes up the
  // pore volume behind it; a tilted one is refused.
  const std::string platen = replace(box, "box = { min = [0.0006, 0.0], max = [0.0016, 0.004] }",
                                     "point = [0.0, 0.004]\nnormal = [0.0, -1.0]");
  EXPECT_EQ(load_error(with_wall(platen)), "");
  const auto with_platen = built_scene<2>(with_wall(platen));
  EXPECT_EQ(with_platen.fluid->solid_walls.size(), 1u);
  EXPECT_NE(describe_patches_and_barriers(*with_platen.fluid, with_platen.simulation.walls)
                .find("wall block displaces the fluid: a plane, solid where y > 0.004 m\n"),
            std::string::npos);
  // Beyond the grid's top (0.004 m) it displaces no water until it moves
  // in: the run log and `check` say so.
  const auto above =
      built_scene<2>(with_wall(replace(platen, "point = [0.0, 0.004]", "point = [0.0, 0.005]")));
  EXPECT_NE(
      describe_patches_and_barriers(*above.fluid, above.simulation.walls)
          .find("wall block displaces the fluid: a plane, solid where y > 0.005 m; now beyond the grid's "
                "y_max side (0.004 m): it displaces no water until it moves into the grid\n"),
      std::string::npos);
  // Its servo may count the water's thrust, and the probe reads it.
  const std::string loaded = replace(platen, "displaces_fluid = true\n",
                                     "displaces_fluid = true\nservo = { target_force = 1.0, gain = 1.0, "
                                     "max_speed = 1.0, load = \"total\" }\n");
  EXPECT_EQ(load_error(with_wall(loaded) + "\n[[probe]]\nname = \"thrust\"\nquantity = \"wall_fluid_force\"\n"
                                           "wall = \"block\"\ncomponent = \"y\"\n"),
            "");
  auto msg = load_error(with_wall(replace(platen, "normal = [0.0, -1.0]", "normal = [0.1, -1.0]")));
  EXPECT_NE(msg.find("[[wall]] #2 key 'displaces_fluid': a plane wall takes up the pore volume behind it "
                     "only with its normal along an axis of the fluid grid"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(with_wall(replace(box, "max = [0.0016, 0.004]", "max = [0.0006, 0.004]")));
  EXPECT_NE(msg.find("key 'displaces_fluid': a plate (min = max along an axis) has no volume to take up"),
            std::string::npos)
      << msg;
  msg = load_error(with_wall(box, false));
  EXPECT_NE(msg.find("key 'displaces_fluid': needs a pore fluid to take up: the scene has no [fluid] table"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, TheWaterThrustProbeNeedsAWallTheWaterCannotPass) {
  // wall_fluid_force on a box that displaces the fluid, on an impermeable
  // plate (its barrier, the grid's only one), and refused on the floor,
  // a plane the water passes, and without a fluid.
  const std::string box =
      "\n[[wall]]\nname = \"block\"\nbox = { min = [0.0006, 0.0], max = [0.0016, 0.004] }\n"
      "material = \"sand\"\ndisplaces_fluid = true\n";
  const std::string plate =
      "\n[[wall]]\nname = \"pile\"\nbox = { min = [-0.0005, 0.002], max = [0.0005, 0.002] }\n"
      "material = \"sand\"\nimpermeable = true\n";
  auto probe = [](const std::string& wall) {
    return "\n[[probe]]\nname = \"thrust\"\nquantity = \"wall_fluid_force\"\nwall = \"" + wall +
           "\"\ncomponent = \"y\"\n";
  };
  EXPECT_EQ(load_error(with_wall(box + plate) + probe("block")), "");
  const auto on_box = built_scene<2>(with_wall(box + plate) + probe("block"));
  EXPECT_EQ(on_box.output.probes.back().barrier, -1);
  const auto on_plate = built_scene<2>(with_wall(box + plate) + probe("pile"));
  EXPECT_EQ(on_plate.output.probes.back().barrier, 0);
  auto msg = load_error(with_wall(box + plate) + probe("floor"));
  EXPECT_NE(msg.find("[[probe]] #1 key 'wall': wall \"floor\" lets the pore water through"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("needs a wall with displaces_fluid = true or an impermeable plate"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(std::string(kGood) + probe("floor"));
  EXPECT_NE(msg.find("\"wall_fluid_force\" needs a pore fluid"), std::string::npos) << msg;
  // A box the water passes is refused even when a [[fluid.barrier]]
  // shares its name (only an impermeable plate's barrier is the wall's).
  const std::string permeable =
      "\n[[wall]]\nname = \"block\"\nbox = { min = [0.0006, 0.0], max = [0.0016, 0.004] }\nmaterial = "
      "\"sand\"\n";
  const std::string namesake =
      "\n[[fluid.barrier]]\nname = \"block\"\naxis = \"y\"\nat = 0.002\nfrom = [-0.0005]\nto = [0.0005]\n";
  EXPECT_EQ(load_error(with_wall(permeable) + namesake), "");
  msg = load_error(with_wall(permeable) + namesake + probe("block"));
  EXPECT_NE(msg.find("wall \"block\" lets the pore water through"), std::string::npos) << msg;
}

// A grading curve (`grading = { diameters, passing, by }`) is read as a
// sieve analysis gives it; whatever cannot be one is refused at its key.
TEST(SceneErrors, GradingCurvesAreReadAndChecked) {
  const std::string column =
      "generator = \"column\"\nmaterial = \"sand\"\nbase = [0.0, 0.0]\ncount = 3\nradius = 0.0005";
  auto with = [&](const std::string& sizes) {
    return replace(kGood, column,
                   "generator = \"random\"\nmaterial = \"sand\"\nmin = [0.0, 0.0]\nmax = [0.02, 0.02]\n"
                   "count = 200\n" +
                       sizes);
  };
  const std::string good = "grading = { diameters = [0.2e-3, 0.6e-3, 1.2e-3], passing = [0.0, 0.4, 1.0] }";
  ASSERT_EQ(load_error(with(good)), "");
  const auto scene = built_scene<2>(with(good));
  ASSERT_EQ(scene.simulation.particles.size(), 200U);
  for (std::size_t i = 0; i < scene.simulation.particles.size(); ++i) {
    EXPECT_GE(scene.simulation.particles.radius[i], 0.1e-3);
    EXPECT_LE(scene.simulation.particles.radius[i], 0.6e-3);
  }
  EXPECT_TRUE(scene.notes.empty());
  // A grading by mass over three decades: 200 grains cannot follow it (its
  // mass is in a few coarse grains), and the reader says so.
  const auto wide = built_scene<2>(with("grading = { diameters = [1e-6, 1e-3], passing = [0.0, 1.0] }"));
  ASSERT_EQ(wide.notes.size(), 1U);
  EXPECT_NE(wide.notes[0].find("[[particles]] #1: the 200 grains drawn follow the grading curve loosely"),
            std::string::npos)
      << wide.notes[0];
  auto msg = load_error(with("grading = { diameters = [0.2e-3, 0.6e-3], passing = [0, 100] }"));
  EXPECT_NE(
      msg.find("[[particles]] #1 grading key 'passing': must be fractions in [0, 1] (not percent), got 100"),
      std::string::npos)
      << msg;
  msg = load_error(with("grading = { diameters = [0.6e-3, 0.2e-3], passing = [0.0, 1.0] }"));
  EXPECT_NE(
      msg.find("key 'diameters': must increase, smallest first; element 2 (0.0002) is not above element 1"),
      std::string::npos)
      << msg;
  msg = load_error(with("grading = { diameters = [0.2e-3, 0.6e-3, 1e-3], passing = [0.0, 0.7, 0.5] }"));
  EXPECT_NE(msg.find("key 'passing': must never decrease"), std::string::npos) << msg;
  msg = load_error(with("grading = { diameters = [0.2e-3, 0.6e-3], passing = [0.1, 1.0] }"));
  EXPECT_NE(msg.find("key 'passing': must be 0 at the smallest diameter and 1 at the largest"),
            std::string::npos)
      << msg;
  msg = load_error(with("grading = { diameters = [0.2e-3, 0.6e-3], passing = [0.0, 0.5, 1.0] }"));
  EXPECT_NE(msg.find("key 'passing': needs one fraction per diameter: 2 diameters, 3 fractions"),
            std::string::npos)
      << msg;
  msg = load_error(with("grading = { diameters = [0.2e-3, 0.6e-3], passing = [0.0, 1.0], by = \"volume\" }"));
  EXPECT_NE(msg.find("key 'by': \"volume\" is not allowed; one of \"mass\", \"number\""), std::string::npos)
      << msg;
  msg = load_error(with("grading = { diameters = [0.2e-3], passing = [0.0] }"));
  EXPECT_NE(msg.find("key 'diameters': needs at least two sieve diameters"), std::string::npos) << msg;
  // Two ways of giving the sizes: the second would have been ignored.
  msg = load_error(with("radius = 0.5e-3\n" + good));
  EXPECT_NE(
      msg.find(":30:11: error: [[particles]] #1 key 'grading': give the sizes one way only; 'radius' is "
               "given too"),
      std::string::npos)
      << msg;
  // How many: a count or the box's porosity, one of them.
  ASSERT_EQ(load_error(replace(with(good), "count = 200", "porosity = 0.8")), "");
  msg = load_error(replace(with(good), "count = 200", "count = 200\nporosity = 0.8"));
  EXPECT_NE(msg.find("key 'porosity': give 'count' or 'porosity', not both"), std::string::npos) << msg;
  msg = load_error(replace(with(good), "count = 200", "porosity = 1.5"));
  EXPECT_NE(msg.find("key 'porosity': must be in (0, 1), got 1.5"), std::string::npos) << msg;
  msg = load_error(replace(with(good), "count = 200", "porosity = 0.1"));
  EXPECT_NE(msg.find("random sequential addition fills at most about 54 % of a box"), std::string::npos)
      << msg;
  msg = load_error(replace(with(good), "count = 200\n", ""));
  EXPECT_NE(msg.find("missing required key 'count' (an integer; or instead 'porosity'"), std::string::npos)
      << msg;
  msg = load_error(with("radius = 0.5e-3\nradius_max = 0.6e-3"));
  EXPECT_NE(msg.find("key 'radius_max': give the sizes one way only; 'radius' is given too"),
            std::string::npos)
      << msg;
}

// [domain]: the box outside of which particles are removed. The column's
// centres lie at x = 0, y = 0.5 to 2.5 mm; the fluid grid spans x in
// [-0.5, 0.5] mm, y in [0, 4] mm, and the largest radius is 0.5 mm.
TEST(SceneErrors, DomainIsReadAndChecked) {
  const std::string domain = "\n[domain]\nmin = [-0.01, -0.01]\nmax = [0.01, 0.01]\n";
  const std::string good = std::string(kGood) + domain;
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  EXPECT_TRUE(scene.simulation.has_domain);
  EXPECT_EQ(scene.simulation.domain_lower[1], -0.01);
  EXPECT_EQ(scene.simulation.domain_upper[0], 0.01);
  ASSERT_FALSE(scene.notes.empty());
  EXPECT_NE(
      scene.notes.back().find("[domain]: particles whose centres leave x in [-0.01, 0.01], y in [-0.01, "
                              "0.01] m are removed from the run"),
      std::string::npos)
      << scene.notes.back();
  EXPECT_FALSE(built_scene<2>(kGood).simulation.has_domain);

  auto msg = load_error(replace(good, "max = [0.01, 0.01]", "max = [0.01, -0.02]"));
  EXPECT_NE(
      msg.find("[domain] key 'max': must be greater than 'min' along every axis (m); along y min = -0.01 "
               "and max = -0.02"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "max = [0.01, 0.01]", "max = [0.01, 0.01, 0.01]"));
  EXPECT_NE(msg.find("[domain] key 'max'"), std::string::npos) << msg;
  msg = load_error(replace(good, "max = [0.01, 0.01]", "max = [0.01, 0.01]\nmargin = 1"));
  EXPECT_NE(msg.find("unknown key 'margin'"), std::string::npos) << msg;
  msg = load_error(replace(good, "max = [0.01, 0.01]", "max = [0.01, 0.002]"));
  EXPECT_NE(msg.find("particle 2 starts at y = 0.0025 m, outside the [domain] (allowed: -0.01 <= y <= 0.002"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("[[particles]] #1"), std::string::npos) << msg;
  msg = load_error("domain = 3\n" + std::string(kGood));  // a key of the top level
  EXPECT_NE(msg.find("key 'domain': must be a table"), std::string::npos) << msg;

  // The probes of what left it need one.
  const std::string probe = "\n[[probe]]\nname = \"gone\"\nquantity = \"removed_mass\"\n";
  EXPECT_EQ(load_error(good + probe), "");
  msg = load_error(std::string(kGood) + probe);
  EXPECT_NE(msg.find("key 'quantity': \"removed_mass\" counts what leaves the [domain]: the scene has no "
                     "[domain] table"),
            std::string::npos)
      << msg;
  msg = load_error(good + replace(probe, "quantity = \"removed_mass\"",
                                  "quantity = \"removed_particles\"\ncomponent = \"x\""));
  EXPECT_NE(msg.find("key 'component': does not apply to quantity \"removed_particles\""), std::string::npos)
      << msg;

  // With a pore fluid it must hold the grid with a radius to spare: a grain
  // it removes has no volume in the cells.
  ASSERT_EQ(load_error(with_fluid(domain)), "");
  msg = load_error(with_fluid(replace(domain, "min = [-0.01, -0.01]", "min = [-0.01, -0.0004]")));
  EXPECT_NE(msg.find("[domain] key 'min': must leave the largest grain's radius (0.0005 m) between the fluid "
                     "grid, [0, 0.004] along y, and the domain's side"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("(allowed: min <= y -0.0005 m)"), std::string::npos) << msg;
  msg = load_error(with_fluid(replace(domain, "max = [0.01, 0.01]", "max = [0.0009, 0.01]")));
  EXPECT_NE(msg.find("[domain] key 'max': must leave the largest grain's radius"), std::string::npos) << msg;

  // Along a periodic axis it holds the period.
  const std::string periodic = "\n[periodic]\nx = [-0.003, 0.003]\n";
  const std::string with_period = replace(good, "\n[[material]]", periodic + "\n[[material]]");
  EXPECT_EQ(load_error(with_period), "");
  msg = load_error(replace(with_period, "min = [-0.01, -0.01]", "min = [-0.002, -0.01]"));
  EXPECT_NE(msg.find("[domain] key 'min': along the periodic axis x the domain must hold the period [-0.003, "
                     "0.003] ([periodic] x)"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, InletIsReadAndChecked) {
  const std::string inlet = R"(
[[inlet]]
name = "rain"
material = "sand"
min = [-0.002, 0.01]
max = [0.002, 0.012]
radius = 0.0004
rate = 100.0
count = 20
)";
  const std::string good = std::string(kGood) + inlet;
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    ASSERT_EQ(scene.inlets.size(), 1U);
    EXPECT_EQ(scene.inlets[0].rate, 100.0);
    EXPECT_EQ(scene.inlets[0].max_count, 20U);
    EXPECT_EQ(scene.inlets[0].interval, 0.01);  // the documented default
    ASSERT_FALSE(scene.notes.empty());
    EXPECT_NE(scene.notes.back().find("[[inlet]] rain: 100 grains/s every 0.01 s into x in [-0.002, 0.002], "
                                      "y in [0.01, 0.012] m, at most 20 grains"),
              std::string::npos)
        << scene.notes.back();
    // The automatic skin and the critical step count the inlet's grains,
    // smaller than the scene's (0.4 mm against 0.5 mm).
    EXPECT_DOUBLE_EQ(scene.simulation.skin, 0.2 * 0.0004);
    EXPECT_LT(scene.critical_time_step, built_scene<2>(kGood).simulation.critical_time_step());
    EXPECT_EQ(scene.simulation.particles.size(), 3U);  // the grain added for the critical step is gone
  }
  // A scene may start empty when an inlet fills it, but not with a pore
  // fluid, whose permeability needs grains.
  const std::string particles =
      "[[particles]]\ngenerator = \"column\"\nmaterial = \"sand\"\nbase = [0.0, 0.0]\n"
      "count = 3\nradius = 0.0005\n";
  EXPECT_EQ(load_error(replace(good, particles, "")), "");
  auto msg = load_error(replace(std::string(kGood), particles, ""));
  EXPECT_NE(msg.find("or an [[inlet]] that adds them during the run"), std::string::npos) << msg;

  msg = load_error(replace(good, "rate = 100.0", "rate = 100.0\nmass_rate = 1.0"));
  EXPECT_NE(
      msg.find("[[inlet]] #1 key 'mass_rate': give 'rate' (grains per second) or 'mass_rate' (kg/s), not "
               "both"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "rate = 100.0", ""));
  EXPECT_NE(msg.find("key 'rate'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("'mass_rate'"), std::string::npos) << msg;
  msg = load_error(replace(good, "rate = 100.0", "rate = -1.0"));
  EXPECT_NE(msg.find("key 'rate': must be > 0 grains per second, got -1"), std::string::npos) << msg;
  msg = load_error(replace(good, "count = 20", "count = 0"));
  EXPECT_NE(msg.find("key 'count': must be >= 1"), std::string::npos) << msg;
  msg = load_error(replace(good, "count = 20", "interval = 0.0"));
  EXPECT_NE(msg.find("key 'interval': must be > 0 s, got 0"), std::string::npos) << msg;
  msg = load_error(replace(good, "count = 20", "interval = 1e-9"));
  EXPECT_NE(msg.find("key 'interval': must be at least the time step"), std::string::npos) << msg;
  msg = load_error(replace(good, "count = 20", "max_attempts = 2000000"));
  EXPECT_NE(msg.find("key 'max_attempts': must be in 1..1000000"), std::string::npos) << msg;
  msg = load_error(replace(good, "max = [0.002, 0.012]", "max = [0.002, 0.0107]"));
  EXPECT_NE(msg.find("key 'max': the box must be wider than the largest grain (0.0008 m across) along every "
                     "axis; along y it is 0.0007 m"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "material = \"sand\"\nmin", "material = \"sandd\"\nmin"));
  EXPECT_NE(msg.find("key 'material'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("did you mean \"sand\""), std::string::npos) << msg;
  msg = load_error(good + inlet);
  EXPECT_NE(msg.find("[[inlet]] #2 key 'name': inlet \"rain\" is defined twice"), std::string::npos) << msg;
  msg = load_error(replace(good, "count = 20", "count = 20\nsize = 3"));
  EXPECT_NE(msg.find("unknown key 'size'"), std::string::npos) << msg;

  // Its grains need contacts with every material they can meet.
  msg = load_error(replace(good, "material = \"sand\"\nmin", "material = \"glass\"\nmin") +
                   "\n[[material]]\nname = \"glass\"\ndensity = 2500.0\n");
  EXPECT_NE(msg.find("key 'material': no [[contact]] for materials \"glass\" and \"sand\", which can touch"),
            std::string::npos)
      << msg;

  // With a pore fluid, the box lies outside the grid: a grain that appeared
  // in a cell would compress its water at once.
  EXPECT_EQ(load_error(with_fluid(inlet)), "");
  msg = load_error(with_fluid(replace(inlet, "min = [-0.002, 0.01]", "min = [-0.002, 0.003]")));
  EXPECT_NE(
      msg.find("[[inlet]] #1 key 'min': the box must lie outside the fluid grid (x in [-0.0005, 0.0005], "
               "y in [0, 0.004] m"),
      std::string::npos)
      << msg;
  // With both, the domain leaves the inlet's largest grain room around the
  // grid, as it must the scene's (0.9 mm here, against their 0.5 mm).
  const std::string domain = "\n[domain]\nmin = [-0.0012, -0.002]\nmax = [0.01, 0.02]\n";
  const std::string narrow = replace(inlet, "min = [-0.002, 0.01]\nmax = [0.002, 0.012]",
                                     "min = [-0.001, 0.01]\nmax = [0.001, 0.012]");
  EXPECT_EQ(load_error(with_fluid(domain + narrow)), "");
  msg = load_error(with_fluid(domain + replace(narrow, "radius = 0.0004", "radius = 0.0009")));
  EXPECT_NE(msg.find("[[inlet]] #1 key 'radius': its largest grain's radius (0.0009 m) must fit between the "
                     "fluid grid, [-0.0005, 0.0005] along x, and the [domain]'s side"),
            std::string::npos)
      << msg;
  // And inside a [domain], which would remove its grains at once.
  msg = load_error(good + "\n[domain]\nmin = [-0.01, -0.01]\nmax = [0.01, 0.011]\n");
  EXPECT_NE(msg.find("[[inlet]] #1 key 'max': the box must lie in the [domain]"), std::string::npos) << msg;

  // Probes of what it added, for one inlet or all.
  const std::string probe = "\n[[probe]]\nname = \"added\"\nquantity = \"inserted_mass\"\ninlet = \"rain\"\n";
  EXPECT_EQ(load_error(good + probe), "");
  EXPECT_EQ(built_scene<2>(good + probe).output.probes.back().inlet, 0);
  msg = load_error(good + replace(probe, "inlet = \"rain\"", "inlet = \"rian\""));
  EXPECT_NE(msg.find("key 'inlet': no [[inlet]] named \"rian\" (did you mean \"rain\"?)"), std::string::npos)
      << msg;
  msg = load_error(std::string(kGood) + replace(probe, "inlet = \"rain\"\n", ""));
  EXPECT_NE(msg.find("key 'quantity': \"inserted_mass\" counts what an [[inlet]] adds: the scene has no "
                     "[[inlet]]"),
            std::string::npos)
      << msg;
  msg = load_error(good + replace(probe, "inlet = \"rain\"", "component = \"x\""));
  EXPECT_NE(msg.find("key 'component': does not apply to quantity \"inserted_mass\""), std::string::npos)
      << msg;
  msg = load_error(good + replace(probe, "quantity = \"inserted_mass\"", "quantity = \"kinetic_energy\""));
  EXPECT_NE(msg.find("key 'inlet': does not apply to quantity \"kinetic_energy\""), std::string::npos) << msg;
  // A particle probe may name a grain the inlet has not made yet.
  EXPECT_EQ(load_error(good + "\n[[probe]]\nname = \"p\"\nquantity = \"particle_position\"\nparticle = 10\n"
                              "component = \"y\"\n"),
            "");

  // A stage switches it on or off, by name.
  EXPECT_EQ(load_error(replace(good, "gravity = [0.0, -9.81]",
                               "gravity = [0.0, -9.81]\ninlets.rain = { active = false }")),
            "");
  msg = load_error(
      replace(good, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\ninlets.rian = { active = false }"));
  EXPECT_NE(msg.find("inlets: no [[inlet]] named \"rian\" (did you mean \"rain\"?)"), std::string::npos)
      << msg;
  msg = load_error(
      replace(good, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\ninlets.rain = { rate = 3 }"));
  EXPECT_NE(msg.find("inlets.rain: needs 'active'"), std::string::npos) << msg;
}

TEST(SceneErrors, BondIsReadAndChecked) {
  const std::string bond = "friction = 0.5\nbond = { tensile_strength = 2.0, shear_strength = 3.0 }";
  const std::string good = bonding_scene(bond) +
                           "\n[[probe]]\nname = \"b\"\nquantity = \"bonds\"\n"
                           "\n[[probe]]\nname = \"broken\"\nquantity = \"broken_bonds\"\n";
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& pp = scene.simulation.contact_table(0, 0);
    EXPECT_TRUE(pp.bondable);
    EXPECT_EQ(pp.bond_tensile, 2.0);
    EXPECT_EQ(pp.bond_shear, 3.0);
    EXPECT_TRUE(scene.stages[0].make_bonds);
    // The note: 2 N/m on k_n = 1e5 N/m stretches 2e-5 m, below half the
    // automatic skin (0.2 x 0.5 mm = 1e-4 m).
    ASSERT_FALSE(scene.notes.empty());
    EXPECT_NE(scene.notes.back().find(
                  "[[contact]] sand / sand: contact bonds (tensile strength 2 N/m, shear 3 N/m) "
                  "stretch by up to 2e-05 m before they break"),
              std::string::npos)
        << scene.notes.back();
    EXPECT_EQ(scene.notes.back().find("skin"), std::string::npos) << scene.notes.back();
    // A strength of 20 N/m stretches 2e-4 m, more than half the skin.
    const auto weak_skin = built_scene<2>(replace(good, "tensile_strength = 2.0", "tensile_strength = 20.0"));
    EXPECT_NE(
        weak_skin.notes.back().find("more than half the skin (0.0001 m): a bond may be stretched so far"),
        std::string::npos)
        << weak_skin.notes.back();
    EXPECT_NE(weak_skin.notes.back().find("Set [simulation] skin above 0.0004 m"), std::string::npos);
    // A bond's tangential spring acts without friction: the critical step
    // counts it as friction's does.
    const auto no_friction = built_scene<2>(replace(good, "friction = 0.5\n", ""));
    const auto plain = built_scene<2>(replace(std::string(kGood), "friction = 0.5\n", ""));
    EXPECT_LT(no_friction.simulation.critical_time_step(), plain.simulation.critical_time_step());
  }
  auto msg = load_error(replace(good, "shear_strength = 3.0", "shear_strength = -3.0"));
  EXPECT_NE(
      msg.find("[[contact]] #1 bond key 'shear_strength': must be >= 0 N per metre of thickness, got -3"),
      std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, ", shear_strength = 3.0", ""));
  EXPECT_NE(msg.find("key 'shear_strength'"), std::string::npos) << msg;
  msg = load_error(replace(good, "tensile_strength = 2.0, shear_strength = 3.0",
                           "tensile_strength = 0.0, shear_strength = 0.0"));
  EXPECT_NE(msg.find("a bond with both strengths 0 would break at once"), std::string::npos) << msg;
  msg = load_error(replace(good, "shear_strength = 3.0", "shear_strength = 3.0, moment = 1.0"));
  EXPECT_NE(msg.find("unknown key 'moment'"), std::string::npos) << msg;
  msg = load_error(replace(good, "bond = {", "bond = 5\nx = {"));
  EXPECT_NE(msg.find("key 'bond'"), std::string::npos) << msg;
  // Hertz's spring cannot pull.
  const std::string hertz =
      replace(replace(good, "law = \"linear\"\nnormal_stiffness = 1e5", "law = \"hertz_mindlin\""),
              "density = 2650.0", "density = 2650.0\nyoungs_modulus = 1e8\npoisson_ratio = 0.3");
  msg = load_error(hertz);
  EXPECT_NE(msg.find("key 'bond': a contact bond needs law = \"linear\""), std::string::npos) << msg;
  // Without a bond in any contact, make_bonds and the bond probes are refused.
  const std::string no_bond = replace(good, "\nbond = { tensile_strength = 2.0, shear_strength = 3.0 }", "");
  msg = load_error(bonding_scene());
  EXPECT_NE(msg.find("[[stage]] #1 key 'make_bonds': bonds pairs whose [[contact]] has a 'bond'"),
            std::string::npos)
      << msg;
  msg = load_error(replace(no_bond, "make_bonds = true", "make_bonds = false"));
  EXPECT_NE(
      msg.find("key 'quantity': \"bonds\" counts contact bonds: no [[contact]] of the scene has a 'bond'"),
      std::string::npos)
      << msg;
  msg = load_error(replace(good, "make_bonds = true", "make_bonds = 1"));
  EXPECT_NE(msg.find("key 'make_bonds'"), std::string::npos) << msg;
}

TEST(SceneErrors, BondMomentIsReadAndChecked) {
  const std::string plain_bond = "friction = 0.5\nbond = { tensile_strength = 2.0, shear_strength = 3.0 }";
  const std::string bond =
      "friction = 0.5\nbond = { tensile_strength = 2.0, shear_strength = 3.0, bending_stiffness_ratio = 0.5, "
      "bending_strength = 1e-4 }";
  const std::string good = bonding_scene(bond);
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& pp = scene.simulation.contact_table(0, 0);
    EXPECT_TRUE(pp.bond_has_moment());
    EXPECT_EQ(pp.bond_bending_ratio, 0.5);
    EXPECT_EQ(pp.bond_bending_strength, 1e-4);
    EXPECT_EQ(pp.bond_twisting_ratio, 0.0);
    // The bending spring turns a grain: the critical step counts it, beside
    // the bond's tangential spring (the time step is the smaller for it).
    const auto pin = built_scene<2>(bonding_scene(plain_bond));
    EXPECT_FALSE(pin.simulation.contact_table(0, 0).bond_has_moment());
    EXPECT_LT(scene.simulation.critical_time_step(), pin.simulation.critical_time_step());
  }
  auto msg = load_error(replace(good, ", bending_strength = 1e-4", ""));
  EXPECT_NE(msg.find("[[contact]] #1 bond key 'bending_stiffness_ratio': needs 'bending_strength' too"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "bending_stiffness_ratio = 0.5, ", ""));
  EXPECT_NE(msg.find("key 'bending_strength': applies with 'bending_stiffness_ratio'"), std::string::npos)
      << msg;
  msg = load_error(replace(good, "bending_stiffness_ratio = 0.5", "bending_stiffness_ratio = 0.0"));
  EXPECT_NE(msg.find("key 'bending_stiffness_ratio': must be > 0"), std::string::npos) << msg;
  msg = load_error(replace(good, "bending_strength = 1e-4", "bending_strength = -1e-4"));
  EXPECT_NE(msg.find("key 'bending_strength': must be > 0 N m per metre of thickness"), std::string::npos)
      << msg;
  msg = load_error(
      replace(good, "bending_strength = 1e-4", "bending_strength = 1e-4, twisting_strength = 1.0"));
  EXPECT_NE(msg.find("key 'twisting_strength': a 2D bond does not twist"), std::string::npos) << msg;

  // 3D: twisting too.
  std::string good3 = in_3d(good);
  good3 = replace(good3, "bending_strength = 1e-4",
                  "bending_strength = 1e-4, twisting_stiffness_ratio = 0.25, twisting_strength = 2e-4");
  ASSERT_EQ(load_error(good3), "");
  {
    const auto scene = built_scene<3>(good3);
    const auto& pp = scene.simulation.contact_table(0, 0);
    EXPECT_EQ(pp.bond_twisting_ratio, 0.25);
    EXPECT_EQ(pp.bond_twisting_strength, 2e-4);
  }
  msg = load_error(replace(good3, ", twisting_strength = 2e-4", ""));
  EXPECT_NE(msg.find("key 'twisting_stiffness_ratio': needs 'twisting_strength' too (the moment at which the "
                     "bond breaks, > 0 N m)"),
            std::string::npos)
      << msg;
}

TEST(SceneErrors, BondStrengthScatterIsReadAndChecked) {
  const std::string bond =
      "friction = 0.5\nbond = { tensile_strength = 2.0, shear_strength = 3.0, strength_weibull_modulus = "
      "5.0, "
      "strength_seed = 9 }";
  const std::string good = bonding_scene(bond);
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& pp = scene.simulation.contact_table(0, 0);
    EXPECT_TRUE(pp.bond_strength_varies());
    EXPECT_EQ(pp.bond_seed, 9U);
    // The mean factor 1: scale = 1 / Gamma(1.2) = 1.0891 (tables).
    EXPECT_NEAR(pp.bond_weibull_scale, 1.0 / 0.9181687424, 1e-9);
    // The note gives the strongest bond in a thousand: scale ln(1000)^(1/5)
    // = 1.0891 x 1.4716 = 1.603 times the mean.
    bool noted = false;
    for (const auto& note : scene.notes)
      noted = noted || note.find("1.603 times as strong") != std::string::npos;
    EXPECT_TRUE(noted);
    // Without a seed, the default 1.
    const auto unseeded = built_scene<2>(replace(good, ", strength_seed = 9", ""));
    EXPECT_EQ(unseeded.simulation.contact_table(0, 0).bond_seed, 1U);
  }
  auto msg = load_error(replace(good, "strength_weibull_modulus = 5.0", "strength_weibull_modulus = 0.1"));
  EXPECT_NE(msg.find("[[contact]] #1 bond key 'strength_weibull_modulus': must be in [0.5, 1000]"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find(".toml:"), std::string::npos) << msg;  // file:line:column
  msg = load_error(replace(good, "strength_seed = 9", "strength_seed = -2"));
  EXPECT_NE(msg.find("key 'strength_seed': must be an integer >= 0"), std::string::npos) << msg;
  msg = load_error(replace(good, "strength_weibull_modulus = 5.0, ", ""));
  EXPECT_NE(msg.find("key 'strength_seed': applies with 'strength_weibull_modulus'"), std::string::npos)
      << msg;
}

}  // namespace
}  // namespace darcydem

namespace darcydem {
namespace {

// Clumps with [periodic] boundaries: the column of three grains made pairs
// of discs along x (each a grain of 0.5 mm: discs of 0.25 mm at +-0.25 mm),
// at x = 0, the lower end of a period [0, 6 mm): each clump's centre is
// inside it, its left disc out of it and put back at the build (at
// 6 - 0.25 mm). A centre outside the period is refused, and so is a
// period a clump could meet its own image in: a pair of discs of 1/3 of
// the grain 4/3 apart reaches 0.5 mm, so with the default skin (0.2 of
// the smallest radius, 0.0333 mm) the period must exceed
// 2 x (0.5 + 0.0333) = 1.0667 mm, more than the discs' own
// 2 x (2 x 0.1667 + 0.0333) = 0.733 mm.
TEST(SceneErrors, PeriodicClumpsAreChecked) {
  const std::string pair =
      "[[clump_template]]\nname = \"pair\"\ncircles = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]\n\n";
  const std::string good =
      replace(replace(replace(kGood, "[[particles]]", pair + "[[particles]]"), "radius = 0.0005",
                      "radius = 0.0005\nclump = \"pair\"\norientation = \"aligned\""),
              "\n[[material]]", "\n[periodic]\nx = [0.0, 0.006]\n\n[[material]]");
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& p = scene.simulation.particles;
    ASSERT_EQ(p.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
      const double expect = i % 2 == 0 ? 0.006 - 0.25e-3 : 0.25e-3;
      EXPECT_NEAR(p.position[i].x(), expect, 1e-15) << i;
    }
  }
  auto msg = load_error(replace(good, "x = [0.0, 0.006]", "x = [0.0001, 0.006]"));
  EXPECT_NE(msg.find("the centre of clump 0 (of particle 0) starts at x = 0 m, outside the periodic range "
                     "[periodic] x = [0.0001, 0.006)"),
            std::string::npos)
      << msg;
  const std::string apart =
      replace(replace(good, "[[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]", "[[-2.0, 0.0, 1.0], [2.0, 0.0, 1.0]]"),
              "x = [0.0, 0.006]", "x = [-0.0005, 0.0005]");
  msg = load_error(apart);
  EXPECT_NE(msg.find("key 'x': the period 0.001 m must exceed 2 x (the larger of 2 x the largest radius and "
                     "the largest clump's reach, + skin) = 0.00106667 m"),
            std::string::npos)
      << msg;
  EXPECT_EQ(load_error(replace(apart, "x = [-0.0005, 0.0005]", "x = [-0.0007, 0.0007]")), "");
}

// A csv generator whose file has a `clump` column makes the clumps it says
// (each of its rows' members, where they stand); with `clump` too, or with
// a clump make_clump_shape refuses, the scene is refused at the key.
TEST(SceneErrors, CsvClumpsAreChecked) {
  const auto csv =
      std::filesystem::temp_directory_path() / ("darcydem_clumps_" + std::to_string(::getpid()) + ".csv");
  auto write = [&](const std::string& text) {
    std::ofstream f(csv);
    f << text;
  };
  const std::string column =
      "generator = \"column\"\nmaterial = \"sand\"\nbase = [0.0, 0.0]\ncount = 3\nradius = 0.0005";
  const std::string good =
      replace(kGood, column, "generator = \"csv\"\nmaterial = \"sand\"\nfile = \"" + csv.string() + "\"");
  // A pair of discs of 0.25 mm side by side at y = 0.5 mm, and a loose disc above.
  write("x,y,radius,clump\n-0.00025,0.0005,0.00025,0\n0.00025,0.0005,0.00025,0\n0.0,0.0015,0.0005,-1\n");
  {
    const auto scene = built_scene<2>(good);
    ASSERT_EQ(scene.simulation.clumps.size(), 1u);
    ASSERT_EQ(scene.simulation.particles.size(), 3u);
    EXPECT_NEAR(scene.simulation.clumps.position[0].y(), 0.0005, 1e-18);
    EXPECT_NEAR(scene.simulation.clumps.mass[0], 2.0 * 2650.0 * std::numbers::pi * 0.25e-3 * 0.25e-3, 1e-15);
    EXPECT_NEAR(scene.simulation.particles.position[1].x(), 0.00025, 1e-18);
  }
  const std::string pair =
      "[[clump_template]]\nname = \"pair\"\ncircles = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]\n\n[[particles]]";
  auto msg =
      load_error(replace(replace(good, "[[particles]]", pair), "file = ", "clump = \"pair\"\nfile = "));
  EXPECT_NE(msg.find("key 'clump': the file's clump column gives its clumps already"), std::string::npos)
      << msg;
  write("x,y,radius,clump\n0.0,0.0005,0.0005,0\n0.0001,0.0005,0.0002,0\n");
  msg = load_error(good);
  EXPECT_NE(msg.find("key 'file': clump 0 (its 2 rows from particle 0 of the file): member 2 lies wholly "
                     "inside member 1"),
            std::string::npos)
      << msg;
  std::filesystem::remove(csv);
}

// [[clump_template]] and a generator's `clump`: a column of three grains
// becomes three pairs of touching discs, each pair's bounding circle the
// grain's (radius 0.5 mm: discs of 0.25 mm at +-0.25 mm), placed as given
// with orientation "aligned". Bad templates and uses are refused at their key.
TEST(SceneErrors, ClumpsAreChecked) {
  const std::string pair =
      "[[clump_template]]\nname = \"pair\"\ncircles = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]\n\n";
  const std::string good = replace(replace(kGood, "[[particles]]", pair + "[[particles]]"), "radius = 0.0005",
                                   "radius = 0.0005\nclump = \"pair\"\norientation = \"aligned\"");
  ASSERT_EQ(load_error(good), "");
  {
    const auto scene = built_scene<2>(good);
    const auto& sim = scene.simulation;
    ASSERT_EQ(sim.clumps.size(), 3u);
    ASSERT_EQ(sim.particles.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i) {
      EXPECT_NEAR(sim.particles.radius[i], 0.25e-3, 1e-18);
      EXPECT_NEAR(std::abs(sim.particles.position[i].x()), 0.25e-3, 1e-18);
    }
    EXPECT_NEAR(sim.clumps.position[1].y(), 1.5e-3, 1e-18);
    // The mass is the two discs' (per metre), the inertia theirs about the centre.
    const double m = 2650.0 * std::numbers::pi * 0.25e-3 * 0.25e-3;
    EXPECT_NEAR(sim.clumps.mass[0], 2.0 * m, 1e-12 * m);
    EXPECT_NEAR(sim.clumps.inertia[0][0], 2.0 * (0.5 * m * 0.0625e-6 + m * 0.0625e-6), 1e-12 * m * 1e-7);
  }
  auto expect_error = [&](const std::string& text, const std::string& part) {
    const std::string msg = load_error(text);
    EXPECT_NE(msg.find(part), std::string::npos) << part << " | " << msg;
  };
  expect_error(replace(good, "clump = \"pair\"", "clump = \"pear\""), "did you mean \"pair\"");
  {
    // Members may overlap (PFC's pebbles): the mass is the union's, two
    // discs of radius a (the grain's 0.5 mm over the reach 1.75) 1.5 a
    // apart less the lens between them, counted once.
    const auto scene = built_scene<2>(replace(good, "[1.0, 0.0, 1.0]]", "[0.5, 0.0, 1.0]]"));
    const double a = 0.5e-3 / 1.75;
    const double d = 1.5 * a;
    const double lens = 2.0 * a * a * std::acos(0.5 * d / a) - 0.5 * d * std::sqrt(4.0 * a * a - d * d);
    const double m = 2650.0 * (2.0 * std::numbers::pi * a * a - lens);
    EXPECT_NEAR(scene.simulation.clumps.mass[0], m, 1e-12 * m);
  }
  expect_error(replace(good, "[1.0, 0.0, 1.0]]", "[-0.8, 0.0, 0.5]]"),
               "member 2 lies wholly inside member 1");
  expect_error(replace(good, "[1.0, 0.0, 1.0]]", "[1.0, 0.0]]"), "member 2 must be [x, y, r]");
  expect_error(replace(good, "[1.0, 0.0, 1.0]]", "[1.0, 0.0, 0.0]]"), "member 2: its radius must be > 0");
  expect_error(replace(good, "circles =", "spheres ="), "'circles'");
  expect_error(replace(good, "orientation = \"aligned\"", "orientation = \"upright\""), "orientation");
  expect_error(replace(good, "orientation = \"aligned\"", "orientation = \"aligned\"\norientation_seed = 3"),
               "seeds a random orientation");
  expect_error(replace(good, "clump = \"pair\"\n", ""), "orients clumps: give 'clump' too");
  {
    // A [domain] removes clumps whole, by their centres of mass (noted).
    const auto scene = built_scene<2>(good + "\n[domain]\nmin = [-1.0, -1.0]\nmax = [1.0, 1.0]\n");
    bool noted = false;
    for (const auto& note : scene.notes)
      noted = noted || note.find("a clump whose centre of mass leaves it") != std::string::npos;
    EXPECT_TRUE(noted);
  }
  // The energy budget counts clumps: its probes load and track it.
  EXPECT_TRUE(built_scene<2>(good + "\n[[probe]]\nname = \"g\"\nquantity = \"gravity_work\"\n")
                  .simulation.track_energy);
  expect_error(replace(good, "[[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]", "[]"), "must be a non-empty array");
}

// An [[inlet]] with `clump` adds clumps of a [[clump_template]]: the name is
// checked as a generator's is, `orientation` goes only with it, and the
// automatic time step counts the inlet's smallest clump as it counts a
// scene's clump of that size (a member's contact against the clump's mass
// and inertia), not as a disc of the clump's size.
TEST(SceneErrors, InletClumpsAreChecked) {
  const std::string pair =
      "[[clump_template]]\nname = \"pair\"\ncircles = [[-1.0, 0.0, 1.0], [1.0, 0.0, 1.0]]\n\n";
  const std::string discs =
      "\n[[inlet]]\nname = \"rain\"\nmaterial = \"sand\"\nmin = [-0.01, 0.01]\nmax = [0.01, 0.02]\n"
      "radius_min = 0.0002\nradius_max = 0.0004\nrate = 100.0\n";
  const std::string with_pair = replace(kGood, "[[particles]]", pair + "[[particles]]");
  const std::string good =
      with_pair + replace(discs, "material = \"sand\"", "material = \"sand\"\nclump = \"pair\"");
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  ASSERT_TRUE(scene.inlets.at(0).clump.has_value());
  EXPECT_FALSE(scene.inlets.at(0).aligned);
  EXPECT_EQ(scene.simulation.clumps.size(), 0u) << "the time step's clump is taken out again";
  EXPECT_EQ(scene.simulation.particles.size(), 3u);
  bool noted = false;
  for (const auto& n : scene.notes)
    noted = noted || n.find("clumps \"pair\" of 2 discs, turned at random") != std::string::npos;
  EXPECT_TRUE(noted);
  // The same clump, of the inlet's smallest size, made by a generator.
  const std::string generated =
      with_pair +
      "\n[[particles]]\ngenerator = \"column\"\nmaterial = \"sand\"\nbase = [0.005, 0.0]\ncount = 1\n"
      "radius = 0.0002\nclump = \"pair\"\n";
  ASSERT_EQ(load_error(generated), "");
  const double clump_step = built_scene<2>(generated).critical_time_step;
  EXPECT_NEAR(scene.critical_time_step, clump_step, 1e-12 * clump_step);
  const double disc_step = built_scene<2>(with_pair + discs).critical_time_step;
  EXPECT_LT(scene.critical_time_step, 0.9 * disc_step)
      << "a member is lighter than a disc of the clump's size";

  auto msg = load_error(replace(good, "clump = \"pair\"", "clump = \"par\""));
  EXPECT_NE(msg.find("key 'clump': \"par\" is not a [[clump_template]]'s name (did you mean \"pair\"?)"),
            std::string::npos)
      << msg;
  msg = load_error(with_pair + discs + "orientation = \"aligned\"\n");
  EXPECT_NE(msg.find("key 'orientation': orients an inlet's clumps: give 'clump' too"), std::string::npos)
      << msg;
  msg = load_error(good + "orientation = \"sideways\"\n");
  EXPECT_NE(msg.find("key 'orientation'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("\"aligned\""), std::string::npos) << msg;
  EXPECT_TRUE(built_scene<2>(good + "orientation = \"aligned\"\n").inlets.at(0).aligned);
}

// A random cloud in a cylinder instead of a box (2D a circle): loaded, each
// grain inside; refused at the key: a cylinder with 'min', not a table, a
// radius <= 0, one narrower than the largest grain, in 3D without its
// length or with an axis not x, y or z; an inlet's cylinder alike.
TEST(SceneErrors, CylindersAreChecked) {
  const std::string column =
      "generator = \"column\"\nmaterial = \"sand\"\nbase = [0.0, 0.0]\ncount = 3\nradius = 0.0005";
  const std::string good =
      replace(kGood, column,
              "generator = \"random\"\nmaterial = \"sand\"\n"
              "cylinder = { centre = [0.0, 0.005], radius = 0.004 }\ncount = 10\nradius = 0.0005");
  ASSERT_EQ(load_error(good), "");
  const auto scene = built_scene<2>(good);
  ASSERT_EQ(scene.simulation.particles.size(), 10u);
  for (const auto& x : scene.simulation.particles.position)
    EXPECT_LE((x - Vec<2>(0.0, 0.005)).norm(), 0.0035 * (1 + 1e-12));
  auto msg = load_error(replace(good, "count = 10", "count = 10\nmin = [0.0, 0.0]"));
  EXPECT_NE(msg.find("key 'min': the grains go in the 'cylinder'; give it or 'min' and 'max'"),
            std::string::npos)
      << msg;
  msg = load_error(replace(good, "cylinder = { centre = [0.0, 0.005], radius = 0.004 }", "cylinder = 3"));
  EXPECT_NE(msg.find("key 'cylinder': must be a table"), std::string::npos) << msg;
  msg = load_error(replace(good, "radius = 0.004", "radius = -0.004"));
  EXPECT_NE(msg.find("cylinder key 'radius'"), std::string::npos) << msg;
  EXPECT_NE(msg.find("> 0 m"), std::string::npos) << msg;
  msg = load_error(replace(good, "radius = 0.004", "radius = 0.0004"));
  EXPECT_NE(msg.find("key 'cylinder': the cylinder must be wider than the largest particle"),
            std::string::npos)
      << msg;
  std::string good3 = replace(good, "dimension = 2", "dimension = 3");
  good3 = replace(good3, "point = [0.0, 0.0]", "point = [0.0, 0.0, 0.0]");
  good3 = replace(good3, "normal = [0.0, 1.0]", "normal = [0.0, 0.0, 1.0]");
  good3 = replace(good3, "gravity = [0.0, -9.81]", "gravity = [0.0, 0.0, -9.81]");
  good3 = replace(good3, "centre = [0.0, 0.005]", "centre = [0.0, 0.0, 0.005], axis = \"z\", length = 0.008");
  ASSERT_EQ(load_error(good3), "");
  msg = load_error(replace(good3, ", length = 0.008", ""));
  EXPECT_NE(msg.find("'length'"), std::string::npos) << msg;
  msg = load_error(replace(good3, "axis = \"z\"", "axis = \"w\""));
  EXPECT_NE(msg.find("cylinder key 'axis'"), std::string::npos) << msg;
  // An inlet's cylinder: its refusals name the key 'cylinder'.
  const std::string inlet =
      "\n[[inlet]]\nname = \"rain\"\nmaterial = \"sand\"\ncylinder = { centre = [0.0, 0.02], radius = 0.004 "
      "}\n"
      "radius = 0.0005\nrate = 100.0\n";
  ASSERT_EQ(load_error(good + inlet), "");
  msg = load_error(good + replace(inlet, "radius = 0.004", "radius = 0.0004"));
  EXPECT_NE(msg.find("key 'cylinder': the cylinder must be wider than the largest grain"), std::string::npos)
      << msg;
}

}  // namespace
}  // namespace darcydem
