#pragma once
// The energy budget of a run (YADE's trackEnergy, PFC's energy tracking):
// the work each kind of force has done on the grains since tracking began,
// accumulated kick by kick. A half kick of velocity Verlet changes a grain's
// kinetic energy by exactly
//   (m/2)(v'^2 - v^2) = (dt/4) (F_total' - m beta v) . (v + v'),
// so splitting the force into its kinds (gravity, contacts with grains and
// walls, the force field, external forces, local and viscous damping) splits
// the change of kinetic energy into their works, which add up to it to
// round-off (rotation likewise, with torques and I). Moving boundaries
// (walls with a velocity, fixed grains moving) do work on the grains through
// their contacts: minus the work of the contact forces on them.
//
// What the contacts took from the grains and did not store in their springs
// is the contact dissipation (dashpots, friction's slip, rolling
// resistance's slip, broken bonds' springs):
//   D_contacts = W_boundary - W_contacts - (E_elastic - E_elastic at start).
// It is inferred, not summed contact by contact; in a sound run it never
// decreases (a decrease means energy from nowhere: too large a time step).
// With the Hertz law it also holds the tangential and rolling springs'
// energy, which elastic_energy() does not count.
#include <cmath>

namespace darcydem {

struct EnergyBudget {
  bool started = false;        ///< tracking has begun (elastic_start, kinetic_start set)
  double elastic_start = 0.0;  ///< J, elastic_energy() when tracking began
  double kinetic_start = 0.0;  ///< J, kinetic_energy() when tracking began
  double gravity_work = 0.0;   ///< J, by gravity on the free grains
  double contact_work =
      0.0;                  ///< J, by the contacts (grains and walls) on the free grains, forces and torques
  double field_work = 0.0;  ///< J, by the force field (the pore fluid's drag, pressure and buoyancy)
  double external_work = 0.0;         ///< J, by ParticleData::external_force
  double local_damping_work = 0.0;    ///< J, by Cundall's local damping (<= 0)
  double viscous_damping_work = 0.0;  ///< J, by global viscous damping (<= 0)
  double boundary_work = 0.0;         ///< J, by moving walls and moving fixed grains on the free grains
  double inserted_kinetic = 0.0;      ///< J, kinetic energy the grains an inlet added brought in
  double removed_kinetic = 0.0;       ///< J, kinetic energy the grains the domain removed took out

  /// Adds another sum's works (not its start).
  void add(const EnergyBudget& o) {
    gravity_work += o.gravity_work;
    contact_work += o.contact_work;
    field_work += o.field_work;
    external_work += o.external_work;
    local_damping_work += o.local_damping_work;
    viscous_damping_work += o.viscous_damping_work;
    boundary_work += o.boundary_work;
  }
  /// J lost to damping: -(local + viscous damping's work).
  [[nodiscard]] double damping_dissipation() const { return -(local_damping_work + viscous_damping_work); }
  /// J lost in the contacts, given the springs' energy now (see above).
  [[nodiscard]] double contact_dissipation(double elastic_now) const {
    return boundary_work - contact_work - (elastic_now - elastic_start);
  }

  /// J of the kinetic energy's change since the start that neither a work
  /// nor the grains added (inlets) or removed (the domain) explain:
  /// round-off in a sound run.
  [[nodiscard]] double unaccounted(double kinetic_now) const {
    return kinetic_now - kinetic_start -
           (gravity_work + contact_work + field_work + external_work + local_damping_work +
            viscous_damping_work + inserted_kinetic - removed_kinetic);
  }

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(started, elastic_start, kinetic_start, gravity_work, contact_work, field_work, external_work,
       local_damping_work, viscous_damping_work, boundary_work, inserted_kinetic, removed_kinetic);
  }
};

}  // namespace darcydem
