// A stage that ends when a probe's value crosses a threshold ([[stage]]
// stop_when = { probe = NAME, above = x, below = y }), as PFC's solve with a
// fish condition or a YADE script checking a value: checked against free
// fall, where velocity Verlet is exact under a constant force, so the step
// at which the probe first crosses is known by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <sstream>
#include <string>

#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
using darcydem::testing::read_probes;
using darcydem::testing::temp_dir;

namespace {

constexpr double g = 9.80665;
constexpr double dt = 1e-4;

// One disc falling from rest at y = 1 m (no walls: nothing else acts). Stage
// "fall" ends once its height, checked every step, drops below 0.9 m; stage
// "on" once its speed, checked every 100 steps, exceeds 2 m/s.
const char* falling_disc = R"(
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

[[particles]]
generator = "column"
material = "glass"
base = [0.0, 0.999]
count = 1
radius = 0.001

[output]
probe_interval = 0.01

[[probe]]
name = "height"
quantity = "particle_position"
particle = 0
component = "y"

[[probe]]
name = "speed"
quantity = "particle_velocity"
particle = 0
component = "norm"

[[stage]]
name = "fall"
duration = 10.0
gravity = [0.0, -9.80665]
stop_when = { probe = "height", below = 0.9, check_interval = 1 }

[[stage]]
name = "on"
duration = 10.0
stop_when = { probe = "speed", above = 2.0 }
)";

}  // namespace

TEST(StopConditions, AStageEndsWhereItsProbeCrossesTheThreshold) {
  const std::string dir = temp_dir("stop_on_probe");
  Scene<2> scene = darcydem::testing::scene_from_text<2>(dir, "scene.toml", falling_disc);
  ASSERT_EQ(scene.stages.size(), 2U);
  ASSERT_TRUE(scene.stages[0].stop_probe.has_value());
  // By hand: after n steps from rest, y_n = 1 - g (n dt)^2 / 2 and
  // v_n = g n dt (exact for velocity Verlet under a constant force, up to
  // round-off, which is far below the 1.8e-6 m a step moves the disc here
  // and the 9.8e-4 m/s it adds to its speed).
  std::uint64_t fall = 0;
  while (1.0 - 0.5 * g * std::pow(static_cast<double>(fall) * dt, 2) >= 0.9) ++fall;
  // The second stage checks every 100 of its own steps.
  std::uint64_t on = 0;
  do {
    on += 100;
  } while (g * static_cast<double>(fall + on) * dt <= 2.0);
  RunOptions options;
  options.out_dir = dir + "/out";
  std::ostringstream log;
  options.log = &log;
  const RunSummary summary = run_scene<2>(scene, options);
  ASSERT_FALSE(summary.interrupted);
  EXPECT_EQ(summary.steps, fall + on) << "fall " << fall << " + on " << on;
  EXPECT_EQ(summary.stages_completed.size(), 2U);
  const auto& p = scene.simulation.particles;
  const double t = static_cast<double>(fall + on) * dt;
  EXPECT_NEAR(p.velocity[0].y(), -g * t, 1e-9);
  // The run log names the condition and the value that met it.
  EXPECT_NE(log.str().find("stage fall: stop condition met at t = "), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("probe height = 0.89"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("below 0.9"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("probe speed = 2.0"), std::string::npos) << log.str();
  // Each stage's end is a row of probes.csv: the height there is below
  // 0.9 m (that it is the first such step, the step count above shows).
  const auto probes = read_probes(options.out_dir + "/probes.csv");
  const double t_fall = static_cast<double>(fall) * dt;
  bool found = false;
  for (std::size_t k = 0; k < probes.at("time").size(); ++k) {
    if (std::abs(probes.at("time")[k] - t_fall) < 0.5 * dt) {
      found = true;
      EXPECT_LT(probes.at("height")[k], 0.9);
    }
  }
  EXPECT_TRUE(found) << "no row at the end of stage fall, t = " << t_fall;
  std::filesystem::remove_all(dir);
}
