#pragma once
// Probe evaluation: one number per probe per output time.
#include "darcydem/scene/scene.hpp"

namespace darcydem {

template <int D>
double evaluate_probe(const ProbeSpec& probe, const Simulation<D>& sim, const PoreFluid<D>* fluid = nullptr);

/// Index of the particle with the highest centre along the last axis.
template <int D>
std::size_t topmost_particle(const ParticleData<D>& particles);

}  // namespace darcydem
