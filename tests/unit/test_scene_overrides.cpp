// Scene overrides, `--set PATH=VALUE` (scene/scene_overrides.hpp): a scene
// changed by overrides is the scene edited by hand, and a bad override is
// refused with a message that names it.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/scene_overrides.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "good_scene.hpp"

namespace darcydem {
namespace {

// The scene-input tests' scene with a second stage, "rest".
const std::string kScene = std::string(kGoodScene) + R"(
[[stage]]
name = "rest"
duration = 0.02
)";

/// The scene built from `text` after `overrides`; its text (with the
/// overrides appended) in *text_out.
Scene<2> built(const std::string& text, const std::vector<std::string>& overrides = {}) {
  std::string t = text;
  toml::table root = toml::parse(std::string_view(t), std::string_view("scene.toml"));
  apply_scene_overrides(root, overrides, "scene.toml", t);
  auto scene = build_scene<2>(root, "scene.toml", t);
  scene.overrides = overrides;
  return scene;
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

/// The message an override is refused with ("" if the scene builds).
std::string refusal(const std::vector<std::string>& overrides) {
  try {
    built(kScene, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneOverrides, AreTheSceneEditedByHand) {
  // Each kind of path: a table's key, an array's element by its name and
  // by its number (from 1, as the reader's messages count), a key the
  // file does not have, and a whole inline table.
  const auto set =
      built(kScene, {"contact.1.friction=0.2", "wall.floor.point=[0.0, -0.001]", "stage.rest.duration=0.05",
                     "particles.1.count=5", "simulation.safety_factor=0.1",
                     "stage.settle.walls.floor={ velocity = [0.0, 0.01] }"});
  std::string edited = replaced(kScene, "friction = 0.5", "friction = 0.2");
  edited = replaced(edited, "point = [0.0, 0.0]", "point = [0.0, -0.001]");
  edited = replaced(edited, "duration = 0.02", "duration = 0.05");
  edited = replaced(edited, "count = 3", "count = 5");
  edited = replaced(edited, "time_step = \"auto\"", "time_step = \"auto\"\nsafety_factor = 0.1");
  edited = replaced(edited, "gravity = [0.0, -9.81]",
                    "gravity = [0.0, -9.81]\nwalls.floor = { velocity = [0.0, 0.01] }");
  const auto by_hand = built(edited);
  EXPECT_EQ(set.simulation.contact_table(0, 0).friction, 0.2);
  EXPECT_EQ(set.simulation.contact_table(0, 0).friction, by_hand.simulation.contact_table(0, 0).friction);
  EXPECT_EQ(set.simulation.walls[0].point, by_hand.simulation.walls[0].point);
  EXPECT_EQ(set.stages[1].duration, 0.05);
  EXPECT_EQ(set.stages[1].duration, by_hand.stages[1].duration);
  ASSERT_EQ(set.simulation.particles.size(), 5u);
  EXPECT_EQ(set.simulation.particles.position, by_hand.simulation.particles.position);
  EXPECT_EQ(set.simulation.time_step, by_hand.simulation.time_step);
  EXPECT_EQ(set.simulation.time_step, 0.5 * built(kScene).simulation.time_step);  // safety factor 0.2 -> 0.1
  ASSERT_EQ(set.stages[0].walls.size(), 1u);
  EXPECT_EQ(set.stages[0].walls[0].velocity, by_hand.stages[0].walls[0].velocity);
}

TEST(SceneOverrides, TheLastOfTwoOnOneKeyHoldsAndTheHashTellsThemApart) {
  const auto twice = built(kScene, {"stage.rest.duration=0.05", "stage.2.duration=0.07"});
  EXPECT_EQ(twice.stages[1].duration, 0.07);
  // A checkpoint keeps the scene's hash: a run resumed with other
  // overrides, or none, is another scene.
  const auto plain = built(kScene);
  const auto one = built(kScene, {"stage.rest.duration=0.05"});
  EXPECT_NE(one.text_hash, plain.text_hash);
  EXPECT_NE(one.text_hash, twice.text_hash);
  EXPECT_EQ(one.text_hash, built(kScene, {"stage.rest.duration=0.05"}).text_hash);
}

TEST(SceneOverrides, BadOnesAreRefusedNamingThem) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"stage.rest.duration", "--set stage.rest.duration: error: give PATH=VALUE"},
      {"=3", "--set =3: error: give PATH=VALUE"},
      {"stage..duration=1", "'stage..duration' has an empty key between its dots"},
      // A table the scene lacks is made, as the file would make it; the
      // reader then finds what it lacks.
      {"fluid.bulk_modulus=1e5",
       "--set fluid.bulk_modulus=1e5: error: [fluid]: missing required key 'density'"},
      {"stage.rest.dura tion=1",
       "'dura tion' in 'stage.rest.dura tion' is not a key: keys are letters, digits"},
      {"stage.shear.duration=1",
       "scene.toml has no [[stage]] named or numbered 'shear' (there are: 'settle', 'rest'; number them from "
       "1)"},
      {"stage.3.duration=1", "no [[stage]] named or numbered '3'"},
      {"contact.0.friction=1", "no [[contact]] named or numbered '0' (there are: #1; number them from 1)"},
      {"stage.rest=1", "'stage.rest' is a whole [[stage]]; name one of its keys, e.g. stage.rest.name"},
      {"simulation.dimension.x=1", "'simulation.dimension' in scene.toml is a value, not a table"},
      {"stage.rest.duration=abc", "--set stage.rest.duration=abc: error: 'abc' is not a TOML value"},
      {"stage.rest.duration=1 2", "'1 2' is not a TOML value"},
      // Values the reader refuses: its message names the override, as it
      // names a file's line.
      {"stage.rest.duration=-1",
       "--set stage.rest.duration=-1: error: [[stage]] #2 key 'duration': must be > 0"},
      {"stage.rest.duraton=1",
       "--set stage.rest.duraton=1: error: [[stage]] #2 has unknown key 'duraton'. Did you "
       "mean 'duration'?"},
      {"wall.floor.material=\"clay\"",
       "--set wall.floor.material=\"clay\": error: [[wall]] #1 key 'material': no "
       "material named \"clay\""},
      {"stage.settle.walls={ ceiling = { fixed = true } }",
       "--set stage.settle.walls={ ceiling = { fixed = true } }: error: [[stage]] #1 walls: no wall named "
       "\"ceiling\""},
  };
  for (const auto& [given, says] : cases) {
    const std::string message = refusal({given});
    EXPECT_NE(message.find(says), std::string::npos) << given << "\n  got: " << message;
  }
  // A key the override does not touch is still named by its line.
  const std::string message = refusal({"stage.rest.gravity=[0.0, 1.0, 2.0]"});
  EXPECT_NE(message.find("--set stage.rest.gravity=[0.0, 1.0, 2.0]: error"), std::string::npos) << message;
  std::string bad_file = replaced(kScene, "duration = 0.02", "duration = -0.02");
  try {
    built(bad_file, {"stage.settle.duration=0.5"});
    ADD_FAILURE() << "a bad duration in the file passed";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.toml:37:12: error: [[stage]] #2 key 'duration'"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace darcydem
