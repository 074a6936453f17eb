#pragma once
// A bed of 120 frictional discs settling for 0.25 s in a box 20 mm wide
// (floor and sides are box walls) inside a [domain]; the tests that grains
// leaving (test_domain.cpp) or arriving (test_inlet.cpp) beside it leave its
// contact histories alone run it with and without them.
#include <string>

namespace darcydem::testing {

/// The bed's scene, with `before_bed` (e.g. particles made before the
/// bed's, so that the bed's indices move) ahead of its [[particles]] and
/// `after` at the end.
inline std::string frictional_bed_scene(const std::string& before_bed, const std::string& after) {
  return R"(
[simulation]
dimension = 2
time_step = "auto"

[domain]
min = [-0.05, -0.02]
max = [0.1, 0.2]

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e4
restitution = 0.3
friction = 0.5

[[wall]]
name = "floor"
box = { min = [-0.002, -0.002], max = [0.022, 0.0] }
material = "sand"

[[wall]]
name = "left"
box = { min = [-0.002, 0.0], max = [0.0, 0.04] }
material = "sand"

[[wall]]
name = "right"
box = { min = [0.02, 0.0], max = [0.022, 0.04] }
material = "sand"
)" + before_bed +
         R"(
[[particles]]
generator = "random"
material = "sand"
min = [0.0, 0.0]
max = [0.02, 0.04]
radius_min = 0.0006
radius_max = 0.0009
count = 120
seed = 2

[[stage]]
name = "settle"
duration = 0.25
gravity = [0.0, -9.80665]
)" + after;
}

}  // namespace darcydem::testing
