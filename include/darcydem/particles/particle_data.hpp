#pragma once
// Particle state, one array per field (structure of arrays).
#include <algorithm>
#include <cstdint>
#include <type_traits>
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
  /// 1: velocity prescribed, not integrated; clump_member: moved by its
  /// clump (clumps.hpp). Either way the particle's own kick is skipped.
  std::vector<std::uint8_t> fixed;
  // State.
  std::vector<Vec<D>> position;             ///< m
  std::vector<Vec<D>> velocity;             ///< m/s
  std::vector<AngVec<D>> angular_velocity;  ///< rad/s
  std::vector<Vec<D>> force;                ///< N, total of the last force evaluation
  std::vector<AngVec<D>> torque;            ///< N m
  /// N, added every step (user loads). Empty unless the user sizes it to N:
  /// most scenes have none, and an unused array still costs memory traffic.
  std::vector<Vec<D>> external_force;
  /// The particle's solid volume over its ball's (pore fluid, probes):
  /// below 1 for members of a clump whose members overlap, each taking its
  /// share of their union. Empty when every particle has 1.
  std::vector<double> volume_scale;

  /// The `fixed` value of a member of a clump.
  static constexpr std::uint8_t clump_member = 2;

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
    if (!external_force.empty()) external_force.push_back(Vec<D>::Zero());
    if (!volume_scale.empty()) volume_scale.push_back(1.0);
  }

  /// Particle i's solid volume (m^3; 2D m^2 per metre).
  [[nodiscard]] double solid_volume(std::size_t i) const {
    const double v = particle_volume<D>(radius[i]);
    return volume_scale.empty() ? v : v * volume_scale[i];
  }

  /// Gives particle i the solid volume `scale` times its ball's.
  void set_volume_scale(std::size_t i, double scale) {
    if (volume_scale.empty()) {
      if (scale == 1.0) return;
      volume_scale.assign(size(), 1.0);
    }
    volume_scale[i] = scale;
  }

  /// Index of the particle created as number `creation` (particles are
  /// reordered in space for speed, so indices move; ids do not).
  [[nodiscard]] std::size_t index_of(std::uint32_t creation) const {
    if (creation < id.size() && id[creation] == creation) return creation;
    for (std::size_t i = 0; i < id.size(); ++i) {
      if (id[i] == creation) return i;
    }
    return id.size();
  }

  /// The particles' indices in creation order (by id; ids of particles
  /// removed outside a domain are missing).
  [[nodiscard]] std::vector<std::size_t> creation_order() const {
    std::vector<std::size_t> order(size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return id[a] < id[b]; });
    return order;
  }

  /// Reorders one per-particle array (left alone if empty): new entry k is
  /// old entry order[k]. For arrays kept beside the particles, too. An
  /// order shorter than the array keeps only the entries it names.
  template <class T>
  static void reorder(std::vector<T>& v, const std::vector<std::uint32_t>& order) {
    if (v.empty()) return;
    std::vector<T> out(order.size());
    for (std::size_t k = 0; k < order.size(); ++k) out[k] = v[order[k]];
    v.swap(out);
  }

  /// Reorders every per-particle array: new particle k is old particle
  /// order[k]; the particles order does not name are removed.
  void permute(const std::vector<std::uint32_t>& order) {
    auto apply = [&](auto& v) { reorder(v, order); };
    apply(id);
    apply(radius);
    apply(inv_mass);
    apply(inv_inertia);
    apply(material);
    apply(fixed);
    apply(position);
    apply(velocity);
    apply(angular_velocity);
    apply(force);
    apply(torque);
    apply(external_force);
    apply(volume_scale);
  }

  /// Every array, in the order the checkpoint stores them (checkpoint_archive.hpp).
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(id, radius, inv_mass, inv_inertia, material, fixed, position, velocity, angular_velocity, force,
       torque, external_force, volume_scale);
  }

  /// Bytes held by the arrays (capacity), for memory reports.
  [[nodiscard]] std::size_t memory_bytes() const {
    auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
    return bytes(id) + bytes(radius) + bytes(inv_mass) + bytes(inv_inertia) + bytes(material) + bytes(fixed) +
           bytes(position) + bytes(velocity) + bytes(angular_velocity) + bytes(force) + bytes(torque) +
           bytes(external_force) + bytes(volume_scale);
  }

  /// Mass from density for any particle, fixed or not (kg).
  [[nodiscard]] static double mass_of(double density, double r) { return density * particle_volume<D>(r); }
};

}  // namespace darcydem
