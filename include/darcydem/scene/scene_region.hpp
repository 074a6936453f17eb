#pragma once
// Reading where a random cloud or an inlet puts its grains: a box (`min`,
// `max`) or a `cylinder` table ([[particles]] with the random generator,
// [[inlet]]). Documented in docs/SCENE.md.
#include <optional>

#include "darcydem/generation/generators.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {

/// The table's `cylinder = { centre, radius, axis, length }` (2D: centre and
/// radius, a circle), or none without the key; refused with the file, line
/// and key if it is malformed or the table also has `min` or `max`.
template <int D>
std::optional<Cylinder<D>> read_cylinder(TableReader& r);

}  // namespace darcydem
