#pragma once
#include <omp.h>

#include <cmath>

// Small helpers to set up DEM cases through the library API.
#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem::testing {

/// One material with the given contact spec for every pair (walls included).
template <int D>
Simulation<D> single_material(double density, const ContactSpec& spec, double youngs_modulus = 0.0,
                              double poisson_ratio = 0.0) {
  Simulation<D> sim;
  Material m{"grain", density, youngs_modulus, poisson_ratio};
  sim.materials.push_back(m);
  sim.contact_table = ContactTable(1);
  sim.contact_table.set(0, 0, make_pair_parameters(m, m, spec));
  return sim;
}

/// Prepares make()'s simulation and runs it for `steps` steps (a multiple
/// of 10) on `threads` OpenMP threads: ten single steps at a time, or
/// advance(10) (which fuses each step's last kick with the next one's first
/// kick and drift). The thread count is restored afterwards.
template <class Make>
auto run_on_threads(Make&& make, int threads, bool single_steps, int steps) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto sim = make();
  sim.prepare();
  for (int s = 0; s < steps; s += 10) {
    if (single_steps) {
      for (int k = 0; k < 10; ++k) sim.step();
    } else {
      sim.advance(10);
    }
  }
  omp_set_num_threads(saved);
  return sim;
}

template <int D>
Wall<D> plane(const Vec<D>& point, const Vec<D>& normal, const char* name = "wall") {
  Wall<D> w;
  w.name = name;
  w.point = point;
  w.normal = normal.normalized();
  return w;
}

/// A particle of radius r (2500 kg/m^3) resting on a floor normal to the
/// last axis under gravity g and moving along x at v0. The normal stiffness
/// makes the resting overlap 1e-4 r; the other contact values are the
/// caller's. dt = 0.05 sqrt(m / k_n). Prepared.
template <int D>
Simulation<D> particle_on_floor(ContactSpec spec, double r, double v0, double g) {
  const double m = 2500.0 * particle_volume<D>(r);
  spec.normal_stiffness = m * g / (1e-4 * r);
  auto sim = single_material<D>(2500.0, spec);
  Vec<D> x = Vec<D>::Zero();
  x[D - 1] = r - m * g / spec.normal_stiffness;  // resting overlap
  Vec<D> v = Vec<D>::Zero();
  v[0] = v0;
  sim.particles.add(x, r, 2500.0, 0, false, v);
  Vec<D> up = Vec<D>::Zero();
  up[D - 1] = 1.0;
  sim.walls.push_back(plane<D>(Vec<D>::Zero(), up, "floor"));
  sim.gravity[D - 1] = -g;
  sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
  return sim;
}

/// The diagonal of -V sigma = sum over the particles in a box holding them
/// all and their contacts of (x_c - x_p) (x) f_c (Simulation::
/// contact_stress), rearranged without the contact forces between grains:
/// the two sides of such a contact share x_c and their forces cancel, which
/// leaves sum over wall contacts of x_c (x) f_c - sum over particles of x_p
/// (x) F_p, F_p the contact force on p (its total force less its weight and
/// any force field's force). The walls must be frictionless planes through
/// the origin and at `far` along each axis, so that on the diagonal a
/// wall's term is its plane's coordinate times the force it exerts along
/// its normal.
template <int D>
Vec<D> rearranged_moment(const Simulation<D>& sim, double far) {
  const auto& p = sim.particles;
  const bool field = sim.field_forces().size() == p.size();
  Vec<D> moment = Vec<D>::Zero();
  for (std::size_t i = 0; i < p.size(); ++i) {
    Vec<D> contact = p.force[i] - sim.gravity / p.inv_mass[i];
    if (field) contact -= sim.field_forces()[i];
    moment -= p.position[i].cwiseProduct(contact);
  }
  for (const auto& w : sim.walls) {
    for (int k = 0; k < D; ++k) {
      if (w.normal[k] < -0.5) moment[k] += far * -w.force[k];
    }
  }
  return moment;
}

}  // namespace darcydem::testing
