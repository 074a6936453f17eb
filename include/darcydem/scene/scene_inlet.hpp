#pragma once
// Reading an [[inlet]] from a scene: grains added during the run
// (generation/inlet.hpp). Documented in docs/SCENE.md.
#include <cstdint>
#include <string>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/generation/inlet.hpp"
#include "darcydem/scene/toml_reader.hpp"

namespace darcydem {

/// One [[inlet]] table, its material and its `clump` (a [[clump_template]]'s
/// shape, or none) already looked up; checked against the simulation (the
/// [domain], the periods) and the pore fluid's grid, which the box must lie
/// outside of. Refused with the file, line and key.
template <int D>
Inlet<D> read_inlet(TableReader& r, std::uint16_t material, const Simulation<D>& sim,
                    const PoreFluid<D>* fluid, const std::vector<std::string>& names_so_far,
                    const ClumpShape<D>* clump = nullptr);

/// The smallest and largest radius the scene's particles and inlets can
/// have, m (infinity and 0 when there are none); an inlet's clumps count
/// with their smallest member and their bounding sphere.
template <int D>
std::pair<double, double> radius_range(const ParticleData<D>& particles, const std::vector<Inlet<D>>& inlets);

}  // namespace darcydem
