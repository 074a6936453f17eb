#pragma once
// Particle state, one array per field (structure of arrays).
#include <cstdint>
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct ParticleData {
  // Identity and properties.
  std::vector<std::uint32_t> id;        ///< creation index; stable under reordering
  std::vector<double> radius;           ///< m
  std::vector<double> inv_mass;         ///< 1/kg (0 for fixed particles)
  std::vector<double> inv_inertia;      ///< 1/(kg m^2) (0 for fixed particles)
  std::vector<std::uint16_t> material;  ///< index into the material table
  std::vector<std::uint8_t> fixed;      ///< 1: velocity prescribed, not integrated
  // State.
  std::vector<Vec<D>> position;             ///< m
  std::vector<Vec<D>> velocity;             ///< m/s
  std::vector<AngVec<D>> angular_velocity;  ///< rad/s
  std::vector<Vec<D>> force;                ///< N, total of the last force evaluation
  std::vector<AngVec<D>> torque;            ///< N m
  std::vector<Vec<D>> external_force;       ///< N, added every step (user loads)

  [[nodiscard]] std::size_t size() const { return position.size(); }

  void add(const Vec<D>& x, double r, double density, std::uint16_t mat, bool is_fixed,
           const Vec<D>& v = Vec<D>::Zero()) {
    const double m = density * particle_volume<D>(r);
    id.push_back(static_cast<std::uint32_t>(position.size()));
    radius.push_back(r);
    inv_mass.push_back(is_fixed ? 0.0 : 1.0 / m);
    inv_inertia.push_back(is_fixed ? 0.0 : 1.0 / (inertia_factor<D> * m * r * r));
    material.push_back(mat);
    fixed.push_back(is_fixed ? 1 : 0);
    position.push_back(x);
    velocity.push_back(v);
    angular_velocity.push_back(AngVec<D>::Zero());
    force.push_back(Vec<D>::Zero());
    torque.push_back(AngVec<D>::Zero());
    external_force.push_back(Vec<D>::Zero());
  }

  /// Mass from density for any particle, fixed or not (kg).
  [[nodiscard]] static double mass_of(double density, double r) { return density * particle_volume<D>(r); }
};

}  // namespace darcydem
