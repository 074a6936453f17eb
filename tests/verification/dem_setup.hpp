#pragma once
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

template <int D>
Wall<D> plane(const Vec<D>& point, const Vec<D>& normal, const char* name = "wall") {
  Wall<D> w;
  w.name = name;
  w.point = point;
  w.normal = normal.normalized();
  return w;
}

}  // namespace darcydem::testing
