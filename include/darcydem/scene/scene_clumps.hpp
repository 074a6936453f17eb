#pragma once
// Reading clumps from a scene: [[clump_template]] tables (a clump's shape)
// and a [[particles]] generator's `clump` key, which puts a clump of that
// shape in place of each grain it makes (YADE's replaceByClumps, PFC's
// clump generate). Documented in docs/SCENE.md.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "darcydem/generation/generators.hpp"
#include "darcydem/particles/clumps.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

/// One [[clump_template]] table: `name` and `spheres` (2D `circles`) =
/// [[x, y, (z,) r], ...] in any one unit; refused with the file, line and key.
template <int D>
std::pair<std::string, ClumpShape<D>> read_clump_template(TableReader& r);

/// The rest of a [[particles]] table with `clump`: `orientation` ("random",
/// the default, or "aligned") and `orientation_seed`; adds a clump of
/// `shape` in place of each grain of the packing, its bounding sphere the
/// grain's. Returns how many particles (members) it added.
template <int D>
std::size_t add_clumps(TableReader& r, Simulation<D>& sim, const ClumpShape<D>& shape,
                       const Packing<D>& packing, std::uint16_t material, bool fixed, const Vec<D>& velocity);

/// Where a clump of `shape`, made by make_clump_shape from members whose
/// first has centre `first_centre` and radius `first_radius`, stands with
/// its members where they were given: its size (m) and centre of mass, at
/// the identity orientation (its principal axes turned back).
template <int D>
std::pair<double, Vec<D>> clump_as_given(const ClumpShape<D>& shape, const Vec<D>& first_centre,
                                         double first_radius) {
  const double size = first_radius / shape.radius[0];
  return {size, first_centre - rotation_matrix(shape.principal) * Vec<D>(size * shape.centre[0])};
}

/// A csv packing with a `clump` column (read_packing_csv): adds its rows
/// in order, loose particles as such and each clump's members as a clump of
/// those members where they stand (its shape, mass and inertia from them,
/// as a [[clump_template]] of them would give). Refuses, at `file`, a clump
/// make_clump_shape refuses. Returns how many clumps it added.
template <int D>
std::size_t add_clumps_from_file(TableReader& r, Simulation<D>& sim, const Packing<D>& packing,
                                 std::uint16_t material, bool fixed, const Vec<D>& velocity);

}  // namespace darcydem
