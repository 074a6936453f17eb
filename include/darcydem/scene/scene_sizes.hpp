#pragma once
// Reading a particle size distribution from a scene table: one of
// `radius`, `radius_min` + `radius_max`, `radii` + `fractions`, or a
// `grading` curve ([[particles]] with the random generator, [[inlet]]).
// Documented in docs/SCENE.md.
#include "darcydem/generation/generators.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {

/// The sizes the table gives, one way only; refused with the file, line
/// and key otherwise. `dimension` weighs a grading by mass (d^2 or d^3).
RadiusDistribution read_radius(TableReader& r, int dimension);

}  // namespace darcydem
