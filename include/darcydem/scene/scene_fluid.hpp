#pragma once
// Reading the pore fluid from a scene: [fluid], [fluid.grid],
// [fluid.permeability], [fluid.boundary] (sides and patches) and a stage's
// [stage.fluid.boundary].
// Documented in docs/SCENE.md.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {

/// New conditions of sides and patches.
/// A stage's `fluid.sources` table: each [[fluid.source]] by its name, a
/// table { inflow = ... } or { pressure = ... }: its new condition.
template <int D>
std::vector<FluidSourceChange> read_source_changes(const toml::table& table, const std::string& where,
                                                   const std::string& file, const PoreFluid<D>& fluid);

struct FluidBoundaryChanges {
  std::vector<std::pair<int, FluidBoundary>> sides;    ///< (side index, condition)
  std::vector<std::pair<int, FluidBoundary>> patches;  ///< (index in PoreFluid::patches, condition)
};

/// A table of conditions: sides by their names (x_min = {...}, ...), and
/// patches by theirs. With `define` ([fluid.boundary]) any other name is a
/// new patch, which gives its 'side', 'from' and 'to' and is checked
/// against `fluid`'s grid and appended to `define`; without it (a stage's
/// fluid.boundary) it must name one of `fluid`'s patches, whose condition
/// changes. Refused with the file, line and key otherwise.
template <int D>
FluidBoundaryChanges read_fluid_boundary_changes(const toml::table& table, const std::string& where,
                                                 const std::string& file, const PoreFluid<D>* fluid,
                                                 std::vector<FluidPatch<D>>* define = nullptr);

/// `steps_per_update` of a [fluid] or [stage.fluid] table: DEM steps per
/// fluid step, 1 to 2^31 - 1 (refused otherwise, with the key).
int read_steps_per_update(TableReader& r);

/// The barrier an impermeable box wall makes ([[wall]] impermeable = true):
/// on the plate's plane, over its extent; errors found against the grid
/// start with `error_prefix` ("file:line:column: error: [[wall]] #N key
/// 'impermeable': ").
template <int D>
struct WallBarrier {
  FluidBarrier<D> barrier;
  std::string error_prefix;
};

/// The pore fluid of a [fluid] table with the impermeable plates' barriers,
/// initialised on the particles and the walls `solid_walls` (indices into
/// `walls`) that take up pore volume, of which `impermeable_walls` also
/// close the faces they cover; along the periodic axes of
/// `periodic` the grid must span the period, and its ends meet.
template <int D>
std::unique_ptr<PoreFluid<D>> read_fluid(const toml::table& table, const std::string& file,
                                         const ParticleData<D>& particles,
                                         const std::vector<WallBarrier<D>>& wall_barriers = {},
                                         const PeriodicCell<D>& periodic = {},
                                         const std::vector<Wall<D>>& walls = {},
                                         const std::vector<std::size_t>& solid_walls = {},
                                         const std::vector<std::size_t>& impermeable_walls = {});

}  // namespace darcydem
