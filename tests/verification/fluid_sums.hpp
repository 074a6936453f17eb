#pragma once
// Sums over a 3D pore fluid and its grains that several verification
// tests compare: the excess pressure's thrust on the grid's floor and the
// fluid's total force on the grains.
#include <functional>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"

namespace darcydem::testing {

/// The excess pressure on the grid's floor times the faces' areas, N: each
/// bottom cell's value plus, on the faces where inflow(i, j) holds, the
/// drop over the half cell below its centre that carries the inflow q.
inline double floor_thrust(const PoreFluid<3>& f, double q, const std::function<bool(int, int)>& inflow) {
  double thrust = 0.0;
  for (int i = 0; i < f.grid.cells[0]; ++i) {
    for (int j = 0; j < f.grid.cells[1]; ++j) {
      const std::size_t c = f.grid.index({i, j, 0});
      const double half_drop =
          inflow(i, j) ? q * f.fluid.viscosity / f.permeability_field()[c][2] * 0.5 * f.grid.width(2, 0)
                       : 0.0;
      thrust += (f.pressure()[c] + half_drop) * f.grid.face_area(2, {i, j, 0});
    }
  }
  return thrust;
}

/// The fluid's force on all the grains under gravity g along -z, and their
/// volume.
struct GrainForceSum {
  Vec<3> force = Vec<3>::Zero();  ///< N
  double solid = 0.0;             ///< m^3
};
inline GrainForceSum fluid_force_on_grains(const PoreFluid<3>& f, const ParticleData<3>& p, double g) {
  std::vector<Vec<3>> force(p.size());
  f.particle_forces(p, Vec<3>(0.0, 0.0, -g), force);
  GrainForceSum sum;
  for (std::size_t i = 0; i < p.size(); ++i) {
    sum.force += force[i];
    sum.solid += particle_volume<3>(p.radius[i]);
  }
  return sum;
}

}  // namespace darcydem::testing
