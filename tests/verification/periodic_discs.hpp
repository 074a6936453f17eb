#pragma once
// The random packing of the periodic-cell tests: 150 discs (r = 0.4 to
// 0.6 mm, friction 0.5) in a periodic 17 mm square, no gravity; the scenes
// add their output, stages and, with pore water, a [fluid].
#include <string>

namespace darcydem::testing {

inline const std::string periodic_discs = R"(
[simulation]
dimension = 2
time_step = "auto"

[periodic]
x = [0.0, 0.017]
y = [0.0, 0.017]

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e5
restitution = 0.3
friction = 0.5

[[particles]]
generator = "random"
material = "sand"
min = [0.0, 0.0]
max = [0.017, 0.017]
count = 150
radius_min = 0.0004
radius_max = 0.0006
seed = 2

)";

}  // namespace darcydem::testing
