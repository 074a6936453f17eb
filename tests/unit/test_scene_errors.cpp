// Strict scene input: each bad scene is refused with a message that names
// the file, the line, the key and what is allowed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <unistd.h>

#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {
namespace {

const char* kGood = R"(
[simulation]
dimension = 2
time_step = "auto"

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e5
restitution = 0.5
friction = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "sand"

[[particles]]
generator = "column"
material = "sand"
base = [0.0, 0.0]
count = 3
radius = 0.0005

[[stage]]
name = "settle"
duration = 0.01
gravity = [0.0, -9.81]
)";

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

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
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
  EXPECT_NE(msg.find("0.0001443"), std::string::npos) << msg;  // sqrt(m/k) for d = 1 mm discs
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

}  // namespace
}  // namespace darcydem
