#pragma once
// Reading the pore fluid from a scene: [fluid], [fluid.grid],
// [fluid.permeability], [fluid.boundary] and a stage's [stage.fluid.boundary].
// Documented in docs/SCENE.md.
#include <memory>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {

/// Boundary changes of one table of sides (x_min = {...}, ...), as
/// (side index, condition) pairs.
template <int D>
std::vector<std::pair<int, FluidBoundary>> read_fluid_sides(const toml::table& table,
                                                            const std::string& where,
                                                            const std::string& file);

/// `steps_per_update` of a [fluid] or [stage.fluid] table: DEM steps per
/// fluid step, 1 to 2^31 - 1 (refused otherwise, with the key).
int read_steps_per_update(TableReader& r);

/// The pore fluid of a [fluid] table, initialised on the particles.
template <int D>
std::unique_ptr<PoreFluid<D>> read_fluid(const toml::table& table, const std::string& file,
                                         const ParticleData<D>& particles);

}  // namespace darcydem
