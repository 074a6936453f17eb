#pragma once
// A bed of 40 discs under water in a grid of 5 x 5 cells of 2 mm, drained
// at the top, and an inlet above the grid that rains 40 more into it
// (test_inlet.cpp; test_inlet_clumps.cpp rains clumps instead).
namespace darcydem::testing {

inline const char* kRainIntoWater = R"(
[simulation]
dimension = 2
time_step = "auto"

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e4
restitution = 0.3
friction = 0.4

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "sand"

[[wall]]
name = "left"
point = [0.0, 0.0]
normal = [1.0, 0.0]
material = "sand"

[[wall]]
name = "right"
point = [0.01, 0.0]
normal = [-1.0, 0.0]
material = "sand"

[[particles]]
generator = "lattice"
material = "sand"
min = [0.0, 0.0]
max = [0.01, 0.004]
spacing = 0.001
radius = 0.00049

[[inlet]]
name = "rain"
material = "sand"
min = [0.0, 0.0105]
max = [0.01, 0.016]
radius = 0.00049
velocity = [0.0, -0.2]
rate = 4000.0
count = 40
interval = 0.005

[fluid]
density = 1000.0
viscosity = 1.0e-3
bulk_modulus = 1e6
drag = "ergun"

[fluid.grid]
origin = [0.0, 0.0]
cells = [5, 5]
size = [0.002, 0.002]

[fluid.permeability]
model = "kozeny_carman"

[fluid.boundary]
y_max = { type = "drained", pressure = 0.0 }

[[stage]]
name = "rain"
duration = 0.12
gravity = [0.0, -9.80665]
)";

}  // namespace darcydem::testing
