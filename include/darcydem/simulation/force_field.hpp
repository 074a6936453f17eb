#pragma once
// A body-force field acting on the particles, evaluated once per DEM step at
// the new positions (after the drift) and half-step velocities, before the
// second half kick, unless it says that the forces it gave last still hold
// (forces_current). The pore fluid is one; user fields can be others.
#include <vector>

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
};

}  // namespace darcydem
