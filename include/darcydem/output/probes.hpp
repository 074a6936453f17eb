#pragma once
// Probe evaluation: one number per probe per output time.
#include "darcydem/scene/scene.hpp"

namespace darcydem {

template <int D>
double evaluate_probe(const ProbeSpec& probe, const Simulation<D>& sim, const PoreFluid<D>* fluid = nullptr);

/// Porosity of the box [lo, hi]: 1 - the volume of the grains in it (each
/// grain's exact overlap with the box, ball_overlap::in_box) / its volume.
template <int D>
double box_porosity(const ParticleData<D>& particles, const Vec<D>& lo, const Vec<D>& hi);

/// Index of the particle with the highest centre along the last axis.
template <int D>
std::size_t topmost_particle(const ParticleData<D>& particles);

}  // namespace darcydem
