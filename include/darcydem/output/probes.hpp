#pragma once
// Probe evaluation: one number per probe per output time.
#include "darcydem/scene/scene.hpp"

namespace darcydem {

template <int D>
double evaluate_probe(const ProbeSpec& probe, const Simulation<D>& sim, const PoreFluid<D>* fluid = nullptr,
                      const std::vector<Inlet<D>>* inlets = nullptr);

/// Porosity of the box [lo, hi]: 1 - the volume of the grains in it (each
/// grain's exact overlap with the box, ball_overlap::in_box) / its volume;
/// with periodic axes, of every image of each grain that reaches the box.
template <int D>
double box_porosity(const ParticleData<D>& particles, const Vec<D>& lo, const Vec<D>& hi,
                    const PeriodicCell<D>& periodic = {});

/// The contacts' mean stress in each cell of a grid (Simulation::
/// contact_stress over the cell's box, with the particles whose centres
/// lie in it, at their image in the period along periodic axes; particles
/// outside the grid count nowhere), Pa, compression positive: the
/// effective stress field of a saturated bed.
template <int D>
std::vector<typename Simulation<D>::Moment> cell_contact_stress(const Simulation<D>& sim,
                                                                const FluidGrid<D>& grid);

/// Index of the particle with the highest centre along the last axis.
template <int D>
std::size_t topmost_particle(const ParticleData<D>& particles);

}  // namespace darcydem
