// Simulation::contact_forces, contact_stress, contact_fabric and
// contact_moments: the contacts of the last force evaluation with their
// forces, and the forces' moments about the particles' centres, over a box
// (Love and Weber's mean stress: the effective stress of a saturated bed;
// Satake's fabric: how the contacts' normals are oriented) or particle by
// particle.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "darcydem/contact/contact_kernel.hpp"
#include "darcydem/simulation/simulation.hpp"
#include "darcydem/walls/mesh_touches.hpp"

namespace darcydem {

template <int D>
template <class Select, class Visit>
void Simulation<D>::for_each_selected_pair(Select&& selected, Visit&& visit) const {
  if (!prepared_) throw std::logic_error("Simulation: contacts before prepare");
  const auto& p = particles;
  const auto& L = list_;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool i_in = selected(i);
    for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
      const std::uint32_t j = L.neighbour[k];
      const bool j_in = selected(j);
      if (!i_in && !j_in) continue;
      const Vec<D> d = periodic.shortest(p.position[j] - p.position[i]);
      const double reach = p.radius[i] + p.radius[j];
      const double dist = d.norm();
      const bool bonded = L.is_bonded(k);
      if ((dist >= reach && !bonded) || p.inv_mass[i] + p.inv_mass[j] == 0.0) continue;
      // The contact point is arm_i from i along n and arm_j from j against
      // it; the force (filled in by for_each_contact_force) on j is -f_on_i.
      const double overlap = reach - dist;
      visit(ContactRecord<D>{i, j, -1, d, d / dist, overlap, p.radius[i] - 0.5 * overlap,
                             p.radius[j] - 0.5 * overlap, Vec<D>::Zero(), bonded},
            k, i_in, j_in);
    }
  }
}

template <int D>
template <class Select, class Visit>
void Simulation<D>::for_each_contact_force(Select&& selected, Visit&& visit) const {
  const auto& p = particles;
  const auto& L = list_;
  const auto& W = wall_list_;
  // Forces the last step stored as it applied them, if it did.
  const bool recorded = pair_force_step_ == steps && pair_force_.size() == L.pair_count();
  for_each_selected_pair(selected, [&](ContactRecord<D> record, std::uint32_t k, bool i_in, bool j_in) {
    const std::size_t i = record.first, j = record.second;
    const Vec<D>& nrm = record.normal;
    const double reach = p.radius[i] + p.radius[j];
    const PairParameters& pp = contact_table(p.material[i], p.material[j]);
    // The force of the last evaluation: stored by it if the step recorded
    // (Simulation::record_contact_forces), else recomputed: the positions
    // are those it saw, and the tangential spring it left, xi, gives its
    // tangential force -k_t xi - c_t v_t whether the contact stuck or
    // slid (contact_kernel.hpp). Only the recomputed dashpots differ: they
    // take the velocities of the step's end (the evaluation saw those of
    // its middle).
    auto recomputed = [&] {
      const Vec<D> v_rel = p.velocity[i] - p.velocity[j] +
                           cross(AngVec<D>(p.angular_velocity[i] * record.arm_first +
                                           p.angular_velocity[j] * record.arm_second),
                                 nrm) -
                           cell_motion.strain_rate.cwiseProduct(record.branch);
      const double vn = v_rel.dot(nrm);
      const double sqrt_m = std::sqrt(1.0 / (p.inv_mass[i] + p.inv_mass[j]));
      const NormalResponse nr =
          MixedNormalLaw::evaluate(pp, record.overlap, vn, sqrt_m, p.radius[i] * p.radius[j] / reach);
      const Vec<D> vt = v_rel - vn * nrm;
      // A bond's normal force may pull (evaluate_bond), its tangential
      // spring acts whatever the friction.
      const double fn = record.bonded ? bond_normal_force(pp, record.overlap, vn, sqrt_m) : nr.force;
      Vec<D> f = -fn * nrm;
      if (pp.friction > 0.0 || record.bonded) {
        f += -nr.tangential_stiffness * L.tangential[k] -
             pp.tangential_damping * sqrt_m * nr.sqrt_tangential_stiffness * vt;
      }
      return f;
    };
    record.force = recorded ? pair_force_[k] : recomputed();
    if (record.bonded && pp.bond_has_moment()) {
      // The moments the bond's springs hold (evaluate_bond).
      const double r_eff = p.radius[i] * p.radius[j] / reach;
      record.bending_moment = pp.bond_bending_stiffness(r_eff) * L.bond_rotation[k].bending.norm();
      record.twisting_moment = pp.bond_twisting_stiffness(r_eff) * std::abs(L.bond_rotation[k].twist);
    }
    visit(record, i_in, j_in);
  });
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!selected(i)) continue;
    // Wall contacts keep their force; the contact point is on the wall (a
    // mesh's: on the facet the force came from).
    for_each_wall_touch<D>(
        walls, W, i, p.position[i], p.radius[i], [&](std::uint32_t k, const auto& touch, bool) {
          const Vec<D>& f = W.force_on_particle[k];
          if (f.squaredNorm() == 0.0) return;
          visit(ContactRecord<D>{i, i, static_cast<int>(W.wall[k]), -touch.gap * touch.normal, -touch.normal,
                                 p.radius[i] - touch.gap, touch.gap, 0.0, f},
                true, false);
        });
  }
}

template <int D>
template <class Select, class Add>
void Simulation<D>::for_each_contact_moment(Select&& selected, Add&& add) const {
  for_each_contact_force(selected, [&](const ContactRecord<D>& c, bool first_in, bool second_in) {
    if (first_in) add(c.first, Moment((c.arm_first * c.normal) * c.force.transpose()));
    if (second_in) add(c.second, Moment((c.arm_second * c.normal) * c.force.transpose()));
  });
}

template <int D>
std::vector<ContactRecord<D>> Simulation<D>::contact_forces() const {
  std::vector<ContactRecord<D>> contacts;
  for_each_contact_force([](std::size_t) { return true; },
                         [&](const ContactRecord<D>& c, bool, bool) { contacts.push_back(c); });
  return contacts;
}

template <int D>
typename Simulation<D>::Moment Simulation<D>::contact_stress(const Vec<D>& lo, const Vec<D>& hi) const {
  const auto& x = particles.position;
  Moment moment = Moment::Zero();
  // Along a periodic axis a particle is in the box if its image there is.
  for_each_contact_moment([&](std::size_t i) { return periodic.image_in_box(x[i], lo, hi); },
                          [&](std::size_t, const Moment& m) { moment += m; });
  const double volume = (hi - lo).prod();  // 2D: area x 1 m
  return -0.5 * (moment + moment.transpose()) / volume;
}

template <int D>
typename Simulation<D>::Moment Simulation<D>::cell_stress() const {
  return contact_stress(periodic.lower, periodic.lower + periodic.length);
}

template <int D>
typename Simulation<D>::Moment Simulation<D>::contact_fabric(const Vec<D>& lo, const Vec<D>& hi) const {
  const auto& x = particles.position;
  Moment sum = Moment::Zero();
  double count = 0.0;
  // Only the normals count: the pairs' walk, no force worked out.
  for_each_selected_pair([&](std::size_t i) { return periodic.image_in_box(x[i], lo, hi); },
                         [&](const ContactRecord<D>& c, std::uint32_t, bool, bool) {
                           sum += c.normal * c.normal.transpose();
                           count += 1.0;
                         });
  if (count == 0.0) return Moment::Constant(std::numeric_limits<double>::quiet_NaN());
  return sum / count;
}

template <int D>
std::vector<typename Simulation<D>::Moment> Simulation<D>::contact_moments() const {
  std::vector<Moment> moments(particles.size(), Moment::Zero());
  for_each_contact_moment([](std::size_t) { return true; },
                          [&](std::size_t i, const Moment& m) { moments[i] += m; });
  return moments;
}

template Simulation<2>::Moment Simulation<2>::contact_stress(const Vec<2>&, const Vec<2>&) const;
template Simulation<3>::Moment Simulation<3>::contact_stress(const Vec<3>&, const Vec<3>&) const;
template Simulation<2>::Moment Simulation<2>::cell_stress() const;
template Simulation<3>::Moment Simulation<3>::cell_stress() const;
template Simulation<2>::Moment Simulation<2>::contact_fabric(const Vec<2>&, const Vec<2>&) const;
template Simulation<3>::Moment Simulation<3>::contact_fabric(const Vec<3>&, const Vec<3>&) const;
template std::vector<Simulation<2>::Moment> Simulation<2>::contact_moments() const;
template std::vector<ContactRecord<2>> Simulation<2>::contact_forces() const;
template std::vector<ContactRecord<3>> Simulation<3>::contact_forces() const;
template std::vector<Simulation<3>::Moment> Simulation<3>::contact_moments() const;

}  // namespace darcydem
