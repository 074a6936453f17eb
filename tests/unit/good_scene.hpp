#pragma once
// A small scene that loads: three discs in a column on a floor, one stage.
// The scene-input tests change it a key at a time.
namespace darcydem {

inline const char* kGoodScene = R"(
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

}  // namespace darcydem
