// The energy budget's accounting (energy_budget.hpp): the works of each
// kind of force in a half kick, and the moving walls' work.
#include "darcydem/simulation/energy_budget.hpp"

#include "darcydem/simulation/kick.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

template <int D>
void Simulation<D>::account_kick(std::size_t i, const Vec<D>& v, const AngVec<D>& w, double half_dt,
                                 EnergyBudget& sum) const {
  const auto& p = particles;
  if (p.fixed[i] == ParticleData<D>::clump_member) return;  // its clump's kick counts (Clumps::advance)
  const Vec<D>& f = p.force[i];
  const AngVec<D>& t = p.torque[i];
  // The load's kinds, as the force evaluation added them (finish_one).
  // Gravity as that evaluation had it (a stage may have changed it since).
  const Vec<D> f_gravity = p.inv_mass[i] > 0.0 ? Vec<D>(force_gravity_ / p.inv_mass[i]) : Vec<D>::Zero();
  const Vec<D> f_field =
      force_field != nullptr && field_force_.size() == p.size() ? field_force_[i] : Vec<D>::Zero();
  const Vec<D> f_external = p.external_force.empty() ? Vec<D>::Zero() : p.external_force[i];
  const Vec<D> f_contact = f - f_gravity - f_field - f_external;
  if (p.fixed[i] != 0) {
    // Its velocity is prescribed: the contacts' work on it over the half
    // kick, (dt/2) f.v, is what it takes from the grains.
    sum.boundary_work -= half_dt * (f_contact.dot(p.velocity[i]) + t.dot(p.angular_velocity[i]));
    return;
  }
  // (dt/4) F . (v + v') for each kind F of the half kick's load.
  const double q = 0.5 * half_dt;
  const Vec<D> sv = v + p.velocity[i];
  const AngVec<D> sw = w + p.angular_velocity[i];
  sum.gravity_work += q * f_gravity.dot(sv);
  sum.field_work += q * f_field.dot(sv);
  sum.external_work += q * f_external.dot(sv);
  sum.contact_work += q * (f_contact.dot(sv) + t.dot(sw));
  if (damping.local > 0.0) {
    sum.local_damping_work += q * (kick::local_damping<D>(damping.local, f, v).dot(sv) +
                                   kick::local_damping<rotation_dim<D>>(damping.local, t, w).dot(sw));
  }
  if (damping.viscous > 0.0) {
    sum.viscous_damping_work -=
        q * damping.viscous * (v.dot(sv) / p.inv_mass[i] + w.dot(sw) / p.inv_inertia[i]);
  }
}

template <int D>
void Simulation<D>::account_walls(const std::vector<Wall<D>>& before) {
  // The grains' force on a wall, taken as the mean of the step's start and
  // end (exact for a linear spring), times the wall's move: the work the
  // grains did on it, which the wall did on them with the other sign (the
  // move of its centre of rotation, the forces' moments being about it). A
  // turning wall's likewise from their moment about its axis times the
  // angle it turned, and a cylinder's whose radius changes (a servo's
  // or radial_velocity) from their push normal to it times the change
  // (outward when touched from inside).
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const Wall<D>& w = walls[k];
    const Wall<D>& b = before[k];
    energy.boundary_work -= 0.5 * (b.force + w.force).dot(w.centre_of_rotation() - b.centre_of_rotation());
    if (w.spin != 0.0) energy.boundary_work -= 0.5 * (b.torque + w.torque) * w.spin * time_step;
    if (w.radius != b.radius) {
      const double outward = w.from_inside ? 1.0 : -1.0;
      energy.boundary_work -= outward * 0.5 * (b.radial_load + w.radial_load) * (w.radius - b.radius);
    }
  }
}

template <int D>
double Simulation<D>::contact_dissipation() const {
  return energy.started ? energy.contact_dissipation(elastic_energy()) : 0.0;
}

template <int D>
double Simulation<D>::unaccounted_energy() const {
  return energy.started ? energy.unaccounted(kinetic_energy()) : 0.0;
}

template void Simulation<2>::account_kick(std::size_t, const Vec<2>&, const AngVec<2>&, double,
                                          EnergyBudget&) const;
template void Simulation<3>::account_kick(std::size_t, const Vec<3>&, const AngVec<3>&, double,
                                          EnergyBudget&) const;
template void Simulation<2>::account_walls(const std::vector<Wall<2>>&);
template void Simulation<3>::account_walls(const std::vector<Wall<3>>&);
template double Simulation<2>::contact_dissipation() const;
template double Simulation<3>::contact_dissipation() const;
template double Simulation<2>::unaccounted_energy() const;
template double Simulation<3>::unaccounted_energy() const;

}  // namespace darcydem
