// Clumps: shapes, placement of members and the rigid-body integration
// (clumps.hpp).
#include "darcydem/particles/clumps.hpp"

#include "darcydem/core/parallel.hpp"
#include "darcydem/particles/ball_union.hpp"
#include "darcydem/simulation/kick.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace darcydem {

Eigen::Matrix<double, 2, 2> rotation_matrix(const Orientation<2>& q) {
  const double c = std::cos(q[0]);
  const double s = std::sin(q[0]);
  Eigen::Matrix<double, 2, 2> r;
  r << c, -s, s, c;
  return r;
}

Eigen::Matrix<double, 3, 3> rotation_matrix(const Orientation<3>& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).toRotationMatrix();
}

Orientation<2> compose(const Orientation<2>& q1, const Orientation<2>& q0) {
  return Orientation<2>(q1[0] + q0[0]);
}
Orientation<3> compose(const Orientation<3>& q1, const Orientation<3>& q0) {
  Eigen::Quaterniond q =
      Eigen::Quaterniond(q1[0], q1[1], q1[2], q1[3]) * Eigen::Quaterniond(q0[0], q0[1], q0[2], q0[3]);
  q.normalize();
  return Orientation<3>(q.w(), q.x(), q.y(), q.z());
}

namespace {
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
}  // namespace

template <>
Orientation<2> random_orientation<2>(std::mt19937_64& rng) {
  return Orientation<2>(2.0 * std::numbers::pi * unit(rng));
}
template <>
Orientation<3> random_orientation<3>(std::mt19937_64& rng) {
  // Shoemake's uniform quaternion.
  const double u1 = unit(rng);
  const double u2 = 2.0 * std::numbers::pi * unit(rng);
  const double u3 = 2.0 * std::numbers::pi * unit(rng);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  return Orientation<3>(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
}

namespace {

/// The turn by the rotation vector phi (rad) as a unit quaternion:
/// (cos(a/2), sin(a/2) phi/a), a = |phi|. A clump turns by w dt each step,
/// a few 1e-4 rad: below a = 1e-3 by the series of cos(a/2) and
/// sin(a/2)/a to a^4, whose next terms (a^6 / 46080) lie below round-off,
/// without sine, cosine or square root.
Eigen::Quaterniond turn_of(const AngVec<3>& phi) {
  const double a2 = phi.squaredNorm();
  double c = 0.0;
  double s = 0.0;
  if (a2 < 1e-6) {
    c = 1.0 - a2 / 8.0 + a2 * a2 / 384.0;
    s = 0.5 - a2 / 48.0 + a2 * a2 / 3840.0;
  } else {
    const double a = std::sqrt(a2);
    c = std::cos(0.5 * a);
    s = std::sin(0.5 * a) / a;
  }
  return {c, s * phi.x(), s * phi.y(), s * phi.z()};
}

/// The angular velocity (world frame) of a clump of principal moments I at
/// orientation R with angular momentum L (world frame), and the inverse.
AngVec<2> spin_of(const Eigen::Matrix<double, 2, 2>&, const AngVec<2>& inertia, const AngVec<2>& momentum) {
  return AngVec<2>(momentum[0] / inertia[0]);
}
AngVec<3> spin_of(const Eigen::Matrix<double, 3, 3>& r, const AngVec<3>& inertia, const AngVec<3>& momentum) {
  return r * (r.transpose() * momentum).cwiseQuotient(inertia);
}
AngVec<2> momentum_of(const Eigen::Matrix<double, 2, 2>&, const AngVec<2>& inertia, const AngVec<2>& spin) {
  return AngVec<2>(spin[0] * inertia[0]);
}
AngVec<3> momentum_of(const Eigen::Matrix<double, 3, 3>& r, const AngVec<3>& inertia, const AngVec<3>& spin) {
  return r * (r.transpose() * spin).cwiseProduct(inertia);
}

/// Each member's share of the volume of the union of overlapping members
/// (which the pore fluid sees as its solid and gravity as its mass): the
/// shares add up to the union's volume and their moment about the members'
/// centres puts it at the union's centroid, so that the members' weights
/// and buoyancies, acting at their centres, turn the clump no more than
/// the true distribution would. Of such shares, the nearest to the
/// members' own volumes scaled to the union's, in the metric weighted by
/// those (w_i = w0_i (1 + a_i . lambda), a_i = (1, c_i - centroid)).
template <int D>
std::vector<double> volume_shares(const std::vector<Vec<D>>& centres, const std::vector<double>& radii,
                                  double volume, const Vec<D>& centroid) {
  const auto n = static_cast<Eigen::Index>(centres.size());
  double own = 0.0;
  for (double r : radii) own += particle_volume<D>(r);
  Eigen::VectorXd w0(n);
  Eigen::MatrixXd a(D + 1, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    w0[i] = particle_volume<D>(radii[k]) * volume / own;
    a(0, i) = 1.0;
    a.block<D, 1>(1, i) = centres[k] - centroid;
  }
  Eigen::VectorXd b = Eigen::VectorXd::Zero(D + 1);
  b[0] = volume;
  const Eigen::MatrixXd weighted = a * w0.asDiagonal();
  const Eigen::VectorXd lambda =
      (weighted * a.transpose()).completeOrthogonalDecomposition().solve(b - a * w0);
  const Eigen::VectorXd w = w0 + weighted.transpose() * lambda;
  double reach = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i)
    reach = std::max(reach, (centres[i] - centroid).norm() + radii[i]);
  const Eigen::VectorXd miss = a * w - b;
  if (!(w.minCoeff() > 0.0) || !(std::abs(miss[0]) <= 1e-9 * volume) ||
      !(miss.tail<D>().norm() <= 1e-9 * volume * reach)) {
    throw std::invalid_argument(fmt::format(
        "the members' centres do not surround the centre of mass of their union ({}): no positive share "
        "of its volume per member puts its weight there; add a member about that point",
        fmt::join(centroid, ", ")));
  }
  return {w.data(), w.data() + n};
}

}  // namespace

template <int D>
ClumpShape<D> make_clump_shape(const std::vector<Vec<D>>& centres, const std::vector<double>& radii) {
  if (centres.empty() || centres.size() != radii.size()) {
    throw std::invalid_argument("a clump needs at least one member, each with a centre and a radius");
  }
  for (std::size_t i = 0; i < radii.size(); ++i) {
    if (!(radii[i] > 0.0) || !std::isfinite(radii[i]) || !centres[i].allFinite()) {
      throw std::invalid_argument(fmt::format("member {} needs a finite centre and a radius > 0", i + 1));
    }
  }
  bool overlapping = false;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    for (std::size_t j = i + 1; j < centres.size(); ++j) {
      const double d = (centres[j] - centres[i]).norm();
      overlapping = overlapping || d - radii[i] - radii[j] < -1e-9 * std::min(radii[i], radii[j]);
      if (d + std::min(radii[i], radii[j]) <= std::max(radii[i], radii[j])) {
        const bool i_inside = radii[i] <= radii[j];
        throw std::invalid_argument(
            fmt::format("member {} lies wholly inside member {}: it adds nothing to the "
                        "clump's solid; leave it out",
                        i_inside ? i + 1 : j + 1, i_inside ? j + 1 : i + 1));
      }
    }
  }
  ClumpShape<D> shape;
  shape.overlapping = overlapping;
  // The volume, centroid and second moments (about the origin given) of
  // the solid: the members' sums, or with overlaps those of their union.
  double volume = 0.0;
  Vec<D> centroid = Vec<D>::Zero();
  Eigen::Matrix<double, D, D> second = Eigen::Matrix<double, D, D>::Zero();
  std::vector<double> share(centres.size());
  if (!overlapping) {
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const double v = particle_volume<D>(radii[i]);
      share[i] = v;
      volume += v;
      centroid += v * centres[i];
    }
    centroid /= volume;
  } else {
    const BallUnionMoments<D> m = ball_union_moments<D>(centres, radii);
    volume = m.volume;
    centroid = m.centroid();
    second = m.second - volume * centroid * centroid.transpose();
    share = volume_shares<D>(centres, radii, volume, centroid);
  }
  std::vector<Vec<D>> arm(centres.size());
  for (std::size_t i = 0; i < centres.size(); ++i) arm[i] = centres[i] - centroid;
  if (!overlapping) {
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const double v = particle_volume<D>(radii[i]);
      second += v * (radii[i] * radii[i] / (D == 2 ? 4.0 : 5.0) * Eigen::Matrix<double, D, D>::Identity() +
                     arm[i] * arm[i].transpose());
    }
  }
  AngVec<D> moments = AngVec<D>::Zero();
  if constexpr (D == 2) {
    moments[0] = second.trace();
  } else {
    const Eigen::Matrix3d tensor = second.trace() * Eigen::Matrix3d::Identity() - second;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(tensor);
    Eigen::Matrix3d axes = solver.eigenvectors();
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
    moments = solver.eigenvalues();
    for (auto& b : arm) b = axes.transpose() * b;
    const Eigen::Quaterniond q(axes);
    shape.principal = Orientation<3>(q.w(), q.x(), q.y(), q.z());
  }
  double reach = 0.0;
  for (std::size_t i = 0; i < centres.size(); ++i) reach = std::max(reach, arm[i].norm() + radii[i]);
  shape.centre.resize(arm.size());
  shape.radius.resize(arm.size());
  for (std::size_t i = 0; i < arm.size(); ++i) {
    shape.centre[i] = arm[i] / reach;
    shape.radius[i] = radii[i] / reach;
    shape.share.push_back(overlapping ? share[i] / std::pow(reach, D) : particle_volume<D>(shape.radius[i]));
  }
  shape.volume = volume / std::pow(reach, D);
  shape.inertia_per_density = moments / std::pow(reach, D + 2);
  return shape;
}

template <int D>
std::size_t Clumps<D>::add(ParticleData<D>& particles, const ClumpShape<D>& shape, double size,
                           const Vec<D>& x, const Orientation<D>& q, double density, std::uint16_t mat,
                           bool is_fixed, const Vec<D>& v) {
  const Orientation<D> turned_principal = compose(q, shape.principal);
  const auto r = rotation_matrix(turned_principal);
  if (first.empty()) first.push_back(0);
  double m = 0.0;
  for (std::size_t k = 0; k < shape.centre.size(); ++k) {
    const Vec<D> b = size * shape.centre[k];
    const double radius = size * shape.radius[k];
    particles.add(x + r * b, radius, density, mat, false, v);
    double member_mass = ParticleData<D>::mass_of(density, radius);
    if (shape.overlapping) {
      member_mass = density * shape.share[k] * std::pow(size, D);
      particles.inv_mass.back() = 1.0 / member_mass;
      particles.inv_inertia.back() = 1.0 / (inertia_factor<D> * member_mass * radius * radius);
      particles.set_volume_scale(particles.size() - 1, shape.share[k] / particle_volume<D>(shape.radius[k]));
    }
    particles.fixed.back() = ParticleData<D>::clump_member;
    member_id.push_back(particles.id.back());
    member_index.push_back(static_cast<std::uint32_t>(particles.size() - 1));
    offset.push_back(b);
    m += member_mass;
  }
  first.push_back(static_cast<std::uint32_t>(member_id.size()));
  mass.push_back(m);
  inertia.push_back(shape.inertia_per_density * density * std::pow(size, D + 2));
  fixed.push_back(is_fixed ? 1 : 0);
  position.push_back(x);
  orientation.push_back(turned_principal);
  velocity.push_back(v);
  angular_velocity.push_back(AngVec<D>::Zero());
  force.push_back(Vec<D>::Zero());
  torque.push_back(AngVec<D>::Zero());
  // The members are the last particles: the indices stay valid until the
  // particles are reordered or removed (refresh()).
  clump_of.resize(particles.size(), -1);
  for (std::uint32_t k = first[mass.size() - 1]; k < first.back(); ++k)
    clump_of[member_index[k]] = static_cast<std::int32_t>(mass.size() - 1);
  return mass.size() - 1;
}

template <int D>
void Clumps<D>::keep(const std::vector<std::uint8_t>& kept) {
  if (std::all_of(kept.begin(), kept.end(), [](std::uint8_t k) { return k != 0; })) return;
  std::vector<std::uint32_t> clump_order;
  std::vector<std::uint32_t> member_order;
  std::vector<std::uint32_t> new_first{0};
  for (std::size_t c = 0; c < size(); ++c) {
    if (kept[c] == 0) continue;
    clump_order.push_back(static_cast<std::uint32_t>(c));
    for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) member_order.push_back(k);
    new_first.push_back(static_cast<std::uint32_t>(member_order.size()));
  }
  auto per_clump = [&](auto& v) { ParticleData<D>::reorder(v, clump_order); };
  per_clump(mass);
  per_clump(inertia);
  per_clump(fixed);
  per_clump(position);
  per_clump(orientation);
  per_clump(velocity);
  per_clump(angular_velocity);
  per_clump(force);
  per_clump(torque);
  ParticleData<D>::reorder(member_id, member_order);
  ParticleData<D>::reorder(offset, member_order);
  first = clump_order.empty() ? std::vector<std::uint32_t>{} : new_first;
  member_index.clear();
  clump_of.clear();
}

template <int D>
void Clumps<D>::refresh(const ParticleData<D>& particles) {
  std::uint32_t top = 0;
  for (auto id : particles.id) top = std::max(top, id);
  std::vector<std::uint32_t> index_of_id(particles.size() == 0 ? 0 : top + 1, ~std::uint32_t{0});
  for (std::size_t i = 0; i < particles.size(); ++i)
    index_of_id[particles.id[i]] = static_cast<std::uint32_t>(i);
  member_index.assign(member_id.size(), 0);
  clump_of.assign(empty() ? 0 : particles.size(), -1);
  for (std::size_t c = 0; c < size(); ++c) {
    for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
      const std::uint32_t id = member_id[k];
      if (id >= index_of_id.size() || index_of_id[id] == ~std::uint32_t{0}) {
        throw std::logic_error(fmt::format("clump {}: its member, particle {}, is gone", c, id));
      }
      member_index[k] = index_of_id[id];
      clump_of[index_of_id[id]] = static_cast<std::int32_t>(c);
    }
  }
}

template <int D>
void Clumps<D>::gather_one(std::size_t c, const Rotation& r, const ParticleData<D>& particles) {
  Vec<D> f = Vec<D>::Zero();
  AngVec<D> t = AngVec<D>::Zero();
  for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
    const std::uint32_t i = member_index[k];
    f += particles.force[i];
    t += particles.torque[i] + cross(Vec<D>(r * offset[k]), particles.force[i]);
  }
  force[c] = f;
  torque[c] = t;
}

template <int D>
void Clumps<D>::gather(const ParticleData<D>& particles) {
  for_each_index(static_cast<std::int64_t>(size()), [&](std::int64_t c) {
    gather_one(static_cast<std::size_t>(c), rotation_matrix(orientation[c]), particles);
  });
}

template <int D>
std::pair<Vec<D>, AngVec<D>> Clumps<D>::kick_one(std::size_t c, const Rotation& r, double half_dt,
                                                 double alpha, double beta) {
  Vec<D> f = force[c];
  AngVec<D> t = torque[c];
  Vec<D> f_damping = Vec<D>::Zero();
  AngVec<D> t_damping = AngVec<D>::Zero();
  if (alpha != 0.0) {
    f_damping = kick::local_damping<D>(alpha, f, velocity[c]);
    t_damping = kick::local_damping<rotation_dim<D>>(alpha, t, angular_velocity[c]);
    f += f_damping;
    t += t_damping;
  }
  velocity[c] += (f / mass[c] - beta * velocity[c]) * half_dt;
  AngVec<D> momentum = momentum_of(r, inertia[c], angular_velocity[c]);
  momentum += (t - beta * momentum) * half_dt;
  angular_velocity[c] = spin_of(r, inertia[c], momentum);
  return {f_damping, t_damping};
}

template <int D>
void Clumps<D>::account_kick(std::size_t c, const Rotation& r, double half_dt, double alpha, double beta,
                             const std::array<Vec<D>, 3>& load, const std::array<AngVec<D>, 3>& moment,
                             EnergyBudget& works) {
  // The half kick changes the kinetic energy by exactly
  // (dt/4) [(F - beta M v) . (v + v') + (T - beta L) . (w + w')]
  // (the orientation held: 1/2 L.I^-1 L with I^-1 symmetric); each kind of
  // load's share is its part of F and T.
  const Vec<D> f_contact = force[c] - load[0] - load[1] - load[2];
  const AngVec<D> t_contact = torque[c] - moment[0] - moment[1] - moment[2];
  if (fixed[c] != 0) {
    works.boundary_work -= half_dt * (f_contact.dot(velocity[c]) + t_contact.dot(angular_velocity[c]));
    return;
  }
  const Vec<D> v = velocity[c];
  const AngVec<D> w = angular_velocity[c];
  const AngVec<D> momentum = momentum_of(r, inertia[c], w);
  const auto [f_damping, t_damping] = kick_one(c, r, half_dt, alpha, beta);
  const double q = 0.5 * half_dt;
  const Vec<D> sv = v + velocity[c];
  const AngVec<D> sw = w + angular_velocity[c];
  works.gravity_work += q * (load[0].dot(sv) + moment[0].dot(sw));
  works.field_work += q * (load[1].dot(sv) + moment[1].dot(sw));
  works.external_work += q * (load[2].dot(sv) + moment[2].dot(sw));
  works.contact_work += q * (f_contact.dot(sv) + t_contact.dot(sw));
  works.local_damping_work += q * (f_damping.dot(sv) + t_damping.dot(sw));
  works.viscous_damping_work -= q * beta * (mass[c] * v.dot(sv) + momentum.dot(sw));
}

template <int D>
double Clumps<D>::kinetic_energy(std::size_t c) const {
  if (fixed[c] != 0) return 0.0;
  const Rotation r = rotation_matrix(orientation[c]);
  return 0.5 * mass[c] * velocity[c].squaredNorm() +
         0.5 * angular_velocity[c].dot(momentum_of(r, inertia[c], angular_velocity[c]));
}

template <int D>
double Clumps<D>::kinetic_energy() const {
  double sum = 0.0;
  for (std::size_t c = 0; c < size(); ++c) sum += kinetic_energy(c);
  return sum;
}

template <int D>
typename Clumps<D>::Rotation Clumps<D>::turn_one(std::size_t c, const Rotation& r, double dt) {
  const AngVec<D> w = angular_velocity[c];
  if (!(w.squaredNorm() > 0.0)) return r;
  if constexpr (D == 2) {
    orientation[c][0] += w[0] * dt;
    return rotation_matrix(orientation[c]);
  } else {
    // The implicit midpoint: turn at the angular velocity the clump has
    // halfway through the turn, its angular momentum unchanged (no torque
    // acts during the drift). Three fixed-point passes leave an error of
    // order (w dt)^3 in that velocity.
    const Eigen::Quaterniond q0(orientation[c][0], orientation[c][1], orientation[c][2], orientation[c][3]);
    const AngVec<D> momentum = momentum_of(r, inertia[c], w);
    AngVec<D> mid = w;
    for (int pass = 0; pass < 3; ++pass) {
      mid = spin_of((turn_of(AngVec<D>(0.5 * dt * mid)) * q0).toRotationMatrix(), inertia[c], momentum);
    }
    Eigen::Quaterniond q1 = turn_of(AngVec<D>(mid * dt)) * q0;
    q1.normalize();
    orientation[c] = Orientation<3>(q1.w(), q1.x(), q1.y(), q1.z());
    const Rotation r1 = q1.toRotationMatrix();
    angular_velocity[c] = spin_of(r1, inertia[c], momentum);
    return r1;
  }
}

template <int D>
double Clumps<D>::advance(ParticleData<D>& particles, int kicks, double half_dt, double alpha, double beta,
                          double dt, const std::vector<Vec<D>>& reference, const ClumpLoadKinds<D>* kinds) {
  const bool referenced = reference.size() == particles.size();
  auto one = [&](std::int64_t index) {
    const auto c = static_cast<std::size_t>(index);
    const Rotation r = rotation_matrix(orientation[c]);
    gather_one(c, r, particles);
    if (kinds != nullptr) {
      // The members' loads by kind (gravity, the field's, the external)
      // and their moments about the centre of mass.
      std::array<Vec<D>, 3> load{Vec<D>::Zero(), Vec<D>::Zero(), Vec<D>::Zero()};
      std::array<AngVec<D>, 3> moment{AngVec<D>::Zero(), AngVec<D>::Zero(), AngVec<D>::Zero()};
      const bool field = kinds->field != nullptr && kinds->field->size() == particles.size();
      const bool external = !particles.external_force.empty();
      for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
        const std::uint32_t i = member_index[k];
        const Vec<D> arm = r * offset[k];
        const std::array<Vec<D>, 3> f{Vec<D>(kinds->gravity / particles.inv_mass[i]),
                                      field ? (*kinds->field)[i] : Vec<D>::Zero(),
                                      external ? particles.external_force[i] : Vec<D>::Zero()};
        for (int kind = 0; kind < 3; ++kind) {
          load[kind] += f[kind];
          moment[kind] += cross(arm, f[kind]);
        }
      }
      for (int k = 0; k < kicks; ++k)
        account_kick(c, r, half_dt, alpha, beta, load, moment, (*kinds->works)[c]);
    } else if (fixed[c] == 0) {
      for (int k = 0; k < kicks; ++k) kick_one(c, r, half_dt, alpha, beta);
    }
    if (!(dt > 0.0)) {
      for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
        const std::uint32_t i = member_index[k];
        particles.velocity[i] = velocity[c] + cross(angular_velocity[c], Vec<D>(r * offset[k]));
        particles.angular_velocity[i] = angular_velocity[c];
      }
      return 0.0;
    }
    position[c] += velocity[c] * dt;
    place(c, turn_one(c, r, dt), particles);
    double moved2 = 0.0;
    for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
      const std::uint32_t i = member_index[k];
      const double d2 = referenced ? (particles.position[i] - reference[i]).squaredNorm()
                                   : std::numeric_limits<double>::infinity();
      moved2 = std::max(moved2, std::isnan(d2) ? std::numeric_limits<double>::infinity() : d2);
    }
    return moved2;
  };
  return max_over_index(static_cast<std::int64_t>(size()), parallel_threshold, one);
}

template <int D>
void Clumps<D>::place(std::size_t c, const Rotation& r, ParticleData<D>& particles) const {
  const bool periodic = period.any();
  for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
    const std::uint32_t i = member_index[k];
    const Vec<D> arm = r * offset[k];
    const Vec<D> x = position[c] + arm;
    particles.position[i] =
        periodic ? Vec<D>(particles.position[i] + period.shortest(x - particles.position[i])) : x;
    particles.velocity[i] = velocity[c] + cross(angular_velocity[c], arm);
    particles.angular_velocity[i] = angular_velocity[c];
  }
}

template <int D>
void Clumps<D>::place_members(ParticleData<D>& particles) const {
  for (std::size_t c = 0; c < size(); ++c) place(c, rotation_matrix(orientation[c]), particles);
}

template <int D>
double Clumps<D>::largest_reach(const ParticleData<D>& particles) const {
  double reach = 0.0;
  for (std::size_t k = 0; k < member_id.size(); ++k)
    reach = std::max(reach, offset[k].norm() + particles.radius[member_index[k]]);
  return reach;
}

template <int D>
double Clumps<D>::contact_mass(std::size_t c, std::size_t k) const {
  // A normal force f n at the member's surface has the moment b x (f n)
  // about the centre of mass (the member's own radius lies along n): the
  // point's acceleration per unit force along n is 1/M + (b x n).I^-1 (b x n),
  // at most 1/M plus the largest eigenvalue of [b]x^T I^-1 [b]x.
  const Vec<D>& b = offset[k];
  double turning = 0.0;
  if constexpr (D == 2) {
    turning = b.squaredNorm() / inertia[c][0];
  } else {
    Eigen::Matrix3d skew;
    skew << 0.0, -b.z(), b.y(), b.z(), 0.0, -b.x(), -b.y(), b.x(), 0.0;
    const Eigen::Matrix3d m = skew.transpose() * inertia[c].cwiseInverse().asDiagonal() * skew;
    turning =
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  }
  return 1.0 / (1.0 / mass[c] + turning);
}

template ClumpShape<2> make_clump_shape<2>(const std::vector<Vec<2>>&, const std::vector<double>&);
template ClumpShape<3> make_clump_shape<3>(const std::vector<Vec<3>>&, const std::vector<double>&);
template struct Clumps<2>;
template struct Clumps<3>;

}  // namespace darcydem
