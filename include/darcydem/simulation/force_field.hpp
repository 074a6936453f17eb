#pragma once
// A body-force field acting on the particles, evaluated once per DEM step at
// the new positions (after the drift) and half-step velocities, before the
// second half kick, unless it says that the forces it gave last still hold
// (forces_current). The pore fluid is one; user fields can be others.
#include <vector>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/particles/particle_data.hpp"

namespace darcydem {

template <int D>
class ParticleForceField {
 public:
  virtual ~ParticleForceField() = default;
  /// Writes the force on every particle into `force` (already sized N), N.
  virtual void particle_forces(const ParticleData<D>& particles, const Vec<D>& gravity,
                               std::vector<Vec<D>>& force) const = 0;
  /// Whether `force`, as the last particle_forces() call wrote it, still
  /// holds for these particles under this gravity, so that the simulation
  /// may apply it again without a call (a field that holds its forces
  /// between its own updates, as the pore fluid can). By default never.
  [[nodiscard]] virtual bool forces_current(const ParticleData<D>& /*particles*/, const Vec<D>& /*gravity*/,
                                            const std::vector<Vec<D>>& /*force*/) const {
    return false;
  }
  /// Called after each drift that stretched a deforming periodic cell
  /// (Simulation::cell_motion), with the cell as it is now: a field laid
  /// on a grid that spans the period (the pore fluid's) stretches it
  /// along. By default nothing.
  virtual void follow_cell(const PeriodicCell<D>& /*cell*/) {}
  /// The mean pressure of the field's medium over the cell, Pa (the pore
  /// water's excess pressure), which a deforming cell's servo on the total
  /// stress adds to the contacts' stress. By default 0.
  [[nodiscard]] virtual double mean_pressure() const { return 0.0; }
};

}  // namespace darcydem
