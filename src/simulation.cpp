#include "darcydem/simulation/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <type_traits>

#include <fmt/format.h>

#include "darcydem/contact/contact_batch.hpp"
#include "darcydem/contact/contact_kernel.hpp"
#include "darcydem/core/deterministic_sum.hpp"
#include "darcydem/core/parallel.hpp"
#include "darcydem/simulation/kick.hpp"
#include "darcydem/walls/loaded_area.hpp"
#include "darcydem/walls/mesh_touches.hpp"

namespace darcydem {

template <int D>
void Simulation<D>::prepare() {
  if (contact_table.materials() != materials.size()) {
    throw std::logic_error("contact table does not match the materials");
  }
  bool any_linear = false;
  bool any_hertz = false;
  for (const auto& p : contact_table.all()) {
    (p.law == NormalLaw::linear ? any_linear : any_hertz) = true;
  }
  law_choice_ = (any_linear && any_hertz) ? LawChoice::mixed
                : any_hertz               ? LawChoice::hertz
                                          : LawChoice::linear;
  rolling_ = contact_table.any_rolling();
  skin = skin_or_default();
  if (time_step <= 0.0) throw std::logic_error("time step not set");
  check_periods();
  rebuild();
  compute_forces(Finish::none);
  prepared_ = true;
}

template <int D>
void Simulation<D>::step() {
  advance(1);
}

template <int D>
void Simulation<D>::advance(std::uint64_t count) {
  if (!prepared_) prepare();
  if (count == 0) return;
  const bool tracked = track_energy;
  if (tracked && !energy.started) {
    energy.elastic_start = elastic_energy();
    energy.kinetic_start = kinetic_energy();
    energy.started = true;
  }
  // With tracking the same operations, in separate sweeps; and with a
  // deforming cell, whose servo reads the stress between the force
  // evaluation and the drift.
  const bool deforming = cell_motion.active();
  // The budget takes the cell's work over each drift from the contacts'
  // moments at both its ends: those of the evaluation before the first.
  if (tracked && deforming && cell_moment_step_ != steps) {
    cell_moment_ = -periodic.length.prod() * cell_stress().diagonal();
    cell_moment_step_ = steps;
  }
  double moved = tracked ? tracked_kick(true) : deforming ? deforming_kick(true) : kick_drift();
  std::vector<Wall<D>> walls_before;
  for (std::uint64_t s = 0; s < count; ++s) {
    if (tracked) walls_before = walls;
    update_servo_targets();
    for (auto& w : walls) {
      w.advance(time_step, time);
      if (w.is_cylinder() && !(w.radius > 0.0)) {
        throw std::runtime_error(fmt::format(
            "wall \"{}\": the cylinder's radius has come to {} m at t = {} s: its servo or radial_velocity "
            "has closed it past the grains it should hold (check its target or rate and the grains' place)",
            w.name, w.radius, time));
      }
    }
    time += time_step;
    rebuild_if_needed(moved);
    // The budget needs each pair's force; a servo alone only the normal
    // stresses, which the force pass sums row by row as it goes.
    recording_ = (record_contact_forces && s + 1 == count) || (deforming && tracked);
    summing_moments_ = deforming && !tracked && cell_motion.any_by_stress();
    if (recording_) pair_force_.assign(list_.pair_count(), Vec<D>::Zero());
    if (summing_moments_) pair_moment_.resize(particles.size());
    if (tracked) {
      compute_forces(Finish::none);
      if (deforming) cell_step(true);
      account_walls(walls_before);
      tracked_kick(false);
      moved = s + 1 < count ? tracked_kick(true) : 0.0;
    } else if (deforming) {
      compute_forces(Finish::none);
      cell_step(false);
      deforming_kick(false);
      moved = s + 1 < count ? deforming_kick(true) : 0.0;
    } else {
      moved = compute_forces(s + 1 < count ? Finish::kick_kick_drift : Finish::kick);
    }
    ++steps;
    if (recording_) {
      pair_force_step_ = steps;
      if (s + 1 == count) record_contact_forces = false;
      recording_ = false;
    }
  }
}

template <int D>
std::size_t Simulation<D>::add_particle(const Vec<D>& x, double radius, std::uint16_t material,
                                        const Vec<D>& velocity) {
  const auto next_id = static_cast<std::uint32_t>(particles.size() + removed_count);
  const double density = materials.at(material).density;
  particles.add(x, radius, density, material, false, velocity);
  particles.id.back() = next_id;
  const double mass = ParticleData<D>::mass_of(density, radius);
  particles.force.back() = mass * gravity;
  ++inserted_count;
  inserted_mass += mass;
  if (energy.started) energy.inserted_kinetic += 0.5 * mass * velocity.squaredNorm();
  return particles.size() - 1;
}

template <int D>
std::size_t Simulation<D>::add_clump(const ClumpShape<D>& shape, double size, const Vec<D>& x,
                                     const Orientation<D>& q, std::uint16_t material,
                                     const Vec<D>& velocity) {
  const std::size_t before = particles.size();
  const auto next_id = static_cast<std::uint32_t>(before + removed_count);
  const std::size_t c =
      clumps.add(particles, shape, size, x, q, materials.at(material).density, material, false, velocity);
  const std::uint32_t first = clumps.first[c];
  for (std::size_t k = 0; before + k < particles.size(); ++k) {
    const std::size_t i = before + k;
    particles.id[i] = next_id + static_cast<std::uint32_t>(k);
    clumps.member_id[first + k] = particles.id[i];
    particles.force[i] = gravity / particles.inv_mass[i];
  }
  clumps.force[c] = clumps.mass[c] * gravity;
  inserted_count += particles.size() - before;
  inserted_mass += clumps.mass[c];
  if (energy.started) energy.inserted_kinetic += 0.5 * clumps.mass[c] * velocity.squaredNorm();
  return c;
}

template <int D>
std::size_t Simulation<D>::make_bonds(double gap) {
  if (!prepared_) throw std::logic_error("Simulation: make_bonds before prepare");
  if (!(gap >= 0.0 && gap < skin)) {
    throw std::invalid_argument(
        fmt::format("make_bonds: the gap {:.6g} m must be >= 0 and below the skin {:.6g} m", gap, skin));
  }
  if (!contact_table.any_bondable()) return 0;
  // The lists hold every pair that touches now (no grain has moved half
  // the skin since they were built); a pair up to `gap` apart may have come
  // that close from beyond their reach, so they are built afresh for it (as
  // a step would, histories kept; the recorded pair forces no longer match).
  if (gap > 0.0) {
    rebuild();
    pair_force_step_ = ~std::uint64_t{0};
  }
  auto& L = list_;
  if (L.bonded.size() != L.pair_count()) L.bonded.assign(L.pair_count(), 0);
  const bool moments = contact_table.any_bond_moment();
  if (moments && L.bond_rotation.size() != L.pair_count()) L.bond_rotation.assign(L.pair_count(), {});
  const bool varies = contact_table.any_bond_strength_variation();
  if (varies && L.bond_strength.size() != L.pair_count()) L.bond_strength.assign(L.pair_count(), 1.0);
  const auto& p = particles;
  std::size_t made = 0;
  for (std::size_t i = 0; i < L.row_offset.size() - 1; ++i) {
    for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
      const std::uint32_t j = L.neighbour[k];
      const PairParameters& pp = contact_table(p.material[i], p.material[j]);
      if (L.bonded[k] != 0 || !pp.bondable) continue;
      if (p.inv_mass[i] + p.inv_mass[j] == 0.0) continue;
      const double reach = p.radius[i] + p.radius[j] + gap;
      if (periodic.shortest(p.position[j] - p.position[i]).squaredNorm() >= reach * reach) continue;
      L.bonded[k] = 1;
      if (moments) L.bond_rotation[k] = {};  // a new bond starts unbent
      if (varies) L.bond_strength[k] = pp.bond_strength_factor(p.id[i], p.id[j]);
      ++made;
    }
  }
  return made;
}

template <int D>
std::size_t Simulation<D>::bond_count() const {
  return static_cast<std::size_t>(std::count(list_.bonded.begin(), list_.bonded.end(), std::uint8_t{1}));
}

template <int D>
double Simulation<D>::skin_or_default() const {
  if (skin > 0.0) return skin;
  if (particles.size() == 0) return 1e-3;
  return 0.2 * *std::min_element(particles.radius.begin(), particles.radius.end());
}

template <int D>
double Simulation<D>::shortest_period() const {
  double r_max = 0.0;
  for (double r : particles.radius) r_max = std::max(r_max, r);
  // A clump must not reach its own image either (its members never touch
  // each other, images included).
  return 2.0 * (std::max(2.0 * r_max, clumps.largest_reach(particles)) + skin_or_default());
}

template <int D>
void Simulation<D>::check_periods() const {
  for (int k = 0; k < D; ++k) {
    if (periodic.periodic[k] && !(periodic.length[k] > shortest_period())) {
      throw std::invalid_argument(
          fmt::format("periodic axis {}: the period {:.6g} m must exceed 2 x (the larger of 2 x the largest "
                      "radius and the largest clump's reach, + skin) = {:.6g} m",
                      "xyz"[k], periodic.length[k], shortest_period()));
    }
  }
}

template <int D>
void Simulation<D>::rebuild() {
  if (periodic.any()) {
    for (auto& x : particles.position) x = periodic.wrap(x);
    for (auto& x : clumps.position) x = periodic.wrap(x);
  }
  clumps.period = periodic;
  if (cell_motion.active()) {
    for (int k = 0; k < D; ++k) {
      if (periodic.length[k] > shortest_period()) continue;
      throw std::runtime_error(fmt::format(
          "the periodic cell has shrunk along {} to {:.6g} m, below 2 x (2 x the largest radius + skin) = "
          "{:.6g} m, where a grain would meet two images of a neighbour: use more grains across the cell or "
          "stop the compression sooner",
          "xyz"[k], periodic.length[k], shortest_period()));
    }
  }
  built_length_ = periodic.length;
  // Each particle's index at the last build, for the lists' histories
  // (empty: the same index); no_old_index for a particle added since.
  std::vector<std::uint32_t> old;
  const std::size_t built = list_.reference().size();
  if (prepared_ && particles.size() > built) {
    old.resize(particles.size());
    for (std::size_t i = 0; i < old.size(); ++i)
      old[i] = i < built ? static_cast<std::uint32_t>(i) : no_old_index;
  }
  // Composes a new order (new particle k is particle order[k] before it)
  // with the old indices.
  auto compose = [&](std::vector<std::uint32_t>& order) {
    if (!old.empty()) {
      for (auto& k : order) k = old[k];
    }
    old.swap(order);
  };
  std::vector<std::uint32_t> kept = remove_outside_domain();
  if (!kept.empty()) compose(kept);
  if (particles.size() > sort_threshold) {
    std::vector<std::uint32_t> order =
        list_.spatial_order(particles.position, particles.radius, skin, periodic);
    bool identity = true;
    for (std::size_t k = 0; k < order.size() && identity; ++k) identity = order[k] == k;
    if (!identity) {
      particles.permute(order);
      // Forces a field holds move with their particles.
      if (field_force_.size() == order.size()) ParticleData<D>::reorder(field_force_, order);
      compose(order);
    }
  }
  if (!clumps.empty()) clumps.refresh(particles);
  const std::vector<std::uint32_t>* old_index = old.empty() ? nullptr : &old;
  // Bonds the build does not carry over (a removed grain's; a pair no
  // longer listed) are lost: counted as broken.
  const std::size_t bonds_before = list_.bonded.empty() ? 0 : bond_count();
  list_.build(particles.position, particles.radius, skin, rolling_, old_index, periodic,
              clumps.empty() ? nullptr : &clumps.clump_of);
  wall_list_.build(particles.position, particles.radius, walls, skin, rolling_, old_index);
  if (bonds_before > 0) broken_bonds += bonds_before - bond_count();
  block_sums_.assign(static_cast<std::size_t>(list_.block_count()), {0.0, 0.0});
}

template <int D>
std::vector<std::uint32_t> Simulation<D>::remove_outside_domain() {
  std::vector<std::uint32_t> kept;
  if (!has_domain) return kept;
  auto inside = [&](const Vec<D>& x) {
    bool in = true;
    for (int k = 0; k < D; ++k) in = in && x[k] >= domain_lower[k] && x[k] <= domain_upper[k];
    return in;  // false for a NaN position: the list build reports it
  };
  const std::size_t n = particles.size();
  // A clump's members stay or go with its centre of mass (clump_of is the
  // last build's, and the particles have kept their order since; those an
  // inlet added since are not members).
  std::vector<std::uint8_t> clump_kept(clumps.size(), 1);
  for (std::size_t c = 0; c < clumps.size(); ++c)
    clump_kept[c] = inside(clumps.position[c]) || !clumps.position[c].allFinite() ? 1 : 0;
  auto stays = [&](std::size_t i) {
    if (i < clumps.clump_of.size() && clumps.clump_of[i] >= 0)
      return clump_kept[static_cast<std::size_t>(clumps.clump_of[i])] != 0;
    return inside(particles.position[i]) || !particles.position[i].allFinite();
  };
  std::size_t first_out = 0;
  while (first_out < n && stays(first_out)) ++first_out;
  if (first_out == n) return kept;
  kept.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (stays(i)) {
      kept.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    ++removed_count;
    removed_volume += particles.solid_volume(i);
    if (particles.inv_mass[i] > 0.0) {
      removed_mass += 1.0 / particles.inv_mass[i];
      // The budget's kinetic energy leaves with it (the step's first half
      // kick is in the budget and in this velocity alike); a clump's below.
      if (energy.started && particles.fixed[i] != ParticleData<D>::clump_member) {
        energy.removed_kinetic +=
            0.5 * particles.velocity[i].squaredNorm() / particles.inv_mass[i] +
            0.5 * particles.angular_velocity[i].squaredNorm() / particles.inv_inertia[i];
      }
    }
  }
  // Forces a field holds go with their particles.
  if (field_force_.size() == n) ParticleData<D>::reorder(field_force_, kept);
  particles.permute(kept);
  if (energy.started) {
    for (std::size_t c = 0; c < clumps.size(); ++c) {
      if (clump_kept[c] == 0) energy.removed_kinetic += clumps.kinetic_energy(c);
    }
  }
  clumps.keep(clump_kept);  // rebuild() refreshes the members' indices
  return kept;
}

template <int D>
void Simulation<D>::update_servo_targets() {
  for (std::size_t i = 0; i < walls.size(); ++i) {
    ServoControl& servo = walls[i].servo;
    if (walls[i].motion != WallMotion::servo) continue;
    if (servo.varies()) (servo.by_stress ? servo.target_stress : servo.target_force) = servo.target_at(time);
    if (!servo.by_stress) continue;
    const LoadedArea a = loaded_area(walls, i, periodic);
    if (!a.why_not.empty()) {
      throw std::runtime_error(
          fmt::format("wall \"{}\": its servo's target_stress needs a loaded area, but {} (at t = {} s)",
                      walls[i].name, a.why_not, time));
    }
    servo.target_force = servo.target_stress * a.area;
  }
}

template <int D>
void Simulation<D>::rebuild_if_needed(double moved) {
  double wall_moved = 0.0;
  for (const auto& w : walls) {
    wall_moved = std::max(wall_moved, w.moved_since_build());
  }
  // Across a deforming cell's ends a pair's images also move apart by the
  // change of the period.
  const double cell_moved = (periodic.length - built_length_).norm();
  if (2.0 * moved > skin || moved + wall_moved > skin || 2.0 * moved + cell_moved > skin) rebuild();
}

namespace {
/// NaN would be ignored by max(): count it as an infinite displacement, so
/// the list is rebuilt and the rebuild reports the blown-up state.
inline double finite_or_inf(double v) { return std::isnan(v) ? std::numeric_limits<double>::infinity() : v; }
}  // namespace

template <int D>
void Simulation<D>::kick_group(std::size_t first, double half_dt) {
  auto& p = particles;
  const int count = static_cast<int>(std::min<std::size_t>(4, p.size() - first));
  const kick::Settings s{damping.local, damping.viscous, half_dt};
  kick::kick_group<D>(p.velocity[first].data(), p.force[first].data(), &p.inv_mass[first], &p.fixed[first],
                      count, s);
  kick::kick_group<rotation_dim<D>>(p.angular_velocity[first].data(), p.torque[first].data(),
                                    &p.inv_inertia[first], &p.fixed[first], count, s);
}

template <int D>
double Simulation<D>::drift_group(std::size_t first, bool referenced) {
  auto& p = particles;
  const double dt = time_step;
  const std::size_t last = std::min<std::size_t>(first + 4, p.size());
  double moved2 = 0.0;
  for (std::size_t i = first; i < last; ++i) {
    p.position[i] += p.velocity[i] * dt;
    moved2 = std::max(moved2, referenced ? finite_or_inf((p.position[i] - list_.reference()[i]).squaredNorm())
                                         : std::numeric_limits<double>::infinity());
  }
  return moved2;
}

template <int D>
double Simulation<D>::kick_drift() {
  const auto groups = static_cast<std::int64_t>((particles.size() + 3) / 4);
  // Without reference positions for every particle (particles added since
  // the last build) the lists must be rebuilt: report an infinite move.
  const bool referenced = list_.reference().size() == particles.size();
  const double half_dt = 0.5 * time_step;
  auto one = [&](std::int64_t g) {
    const auto first = static_cast<std::size_t>(4 * g);
    kick_group(first, half_dt);
    return drift_group(first, referenced);
  };
  double moved2 = max_over_index(groups, parallel_threshold / 4, one);
  if (!clumps.empty()) {
    moved2 = std::max(moved2, clumps.advance(particles, 1, half_dt, damping.local, damping.viscous, time_step,
                                             list_.reference()));
  }
  return std::sqrt(moved2);
}

template <int D>
double Simulation<D>::drift_group_in_field(std::size_t first, bool referenced) {
  auto& p = particles;
  const double dt = time_step;
  const Vec<D>& rate = cell_motion.strain_rate;
  const Vec<D> centre = periodic.lower + 0.5 * periodic.length;
  const std::size_t last = std::min<std::size_t>(first + 4, p.size());
  double moved2 = 0.0;
  for (std::size_t i = first; i < last; ++i) {
    // Its own velocity and the field's at its place.
    p.position[i] += (p.velocity[i] + rate.cwiseProduct(p.position[i] - centre)) * dt;
    moved2 = std::max(moved2, referenced ? finite_or_inf((p.position[i] - list_.reference()[i]).squaredNorm())
                                         : std::numeric_limits<double>::infinity());
  }
  return moved2;
}

template <int D>
double Simulation<D>::deforming_kick(bool drift) {
  const double half_dt = 0.5 * time_step;
  const bool referenced = list_.reference().size() == particles.size();
  const auto groups = static_cast<std::int64_t>((particles.size() + 3) / 4);
  auto one = [&](std::int64_t g) {
    const auto first = static_cast<std::size_t>(4 * g);
    kick_group(first, half_dt);
    return drift ? drift_group_in_field(first, referenced) : 0.0;
  };
  const double moved2 = max_over_index(groups, parallel_threshold / 4, one);
  if (drift) stretch_cell();
  return std::sqrt(moved2);
}

template <int D>
void Simulation<D>::stretch_cell() {
  cell_motion.stretch(periodic, time_step);
  if (force_field != nullptr) force_field->follow_cell(periodic);
}

template <int D>
void Simulation<D>::cell_step(bool tracked) {
  if (!tracked) {
    if (!summing_moments_) return;  // no servo: the rates are set
    // -1/V diag(sum d (x) f): the rows' sums added in fixed blocks (the
    // same whatever the thread count).
    const Vec<D> sum = deterministic_sum(static_cast<std::int64_t>(particles.size()), Vec<D>(Vec<D>::Zero()),
                                         [&](std::int64_t i) { return pair_moment_[i]; });
    cell_motion.servo(servo_stress(-sum / periodic.length.prod()));
    return;
  }
  // The cell's work on the contacts over the last drift: the field moved
  // each pair's separation d by rate (x) d dt, d as it was before the
  // drift, against the mean of the forces f (on the first grain) at its
  // two ends: sum_k rate_k dt sum_c d_k (f_k + f'_k) / 2, positive while
  // the cell shrinks against their push (the fluctuations' share is the
  // contacts' work on the grains, which the kicks count).
  Vec<D> before = Vec<D>::Zero();
  const Moment stress = recorded_cell_stress(&before);
  const Vec<D> moment = -periodic.length.prod() * stress.diagonal();
  energy.boundary_work += 0.5 * time_step * cell_motion.strain_rate.dot(cell_moment_ + before);
  cell_moment_ = moment;
  cell_moment_step_ = steps + 1;
  if (cell_motion.any_by_stress()) cell_motion.servo(servo_stress(stress.diagonal()));
}

template <int D>
Vec<D> Simulation<D>::servo_stress(const Vec<D>& contacts) const {
  if (!cell_motion.total_stress || force_field == nullptr) return contacts;
  return contacts + Vec<D>::Constant(force_field->mean_pressure());
}

template <int D>
typename Simulation<D>::Moment Simulation<D>::recorded_cell_stress(Vec<D>* before_drift) const {
  const auto& p = particles;
  const auto& L = list_;
  const double dt = time_step;
  const Vec<D> stretch = Vec<D>::Ones() + dt * cell_motion.strain_rate;
  const bool before = before_drift != nullptr;
  // Columns 0..D-1: sum d (x) f; column D: the diagonal of sum d0 (x) f.
  using Sums = Eigen::Matrix<double, D, D + 1>;
  auto row = [&](std::int64_t i) {
    Sums sum = Sums::Zero();
    for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
      const Vec<D>& f = pair_force_[k];
      if (f == Vec<D>::Zero()) continue;
      const std::uint32_t j = L.neighbour[k];
      const Vec<D> d = periodic.shortest(p.position[j] - p.position[i]);
      for (int b = 0; b < D; ++b) {
        for (int a = 0; a < D; ++a) sum(a, b) += d[a] * f[b];
      }
      // The drift moved d by (v_j - v_i) dt + rate (x) d dt, the velocities
      // those of the half step it took (the present ones).
      if (before) {
        const Vec<D> dv = p.velocity[j] - p.velocity[i];
        for (int a = 0; a < D; ++a) sum(a, D) += (d[a] - dv[a] * dt) / stretch[a] * f[a];
      }
    }
    return sum;
  };
  const Sums sums = deterministic_sum(static_cast<std::int64_t>(p.size()), Sums(Sums::Zero()), row);
  if (before) *before_drift = sums.col(D);
  const Moment sum = sums.template leftCols<D>();
  return -0.5 * (sum + sum.transpose()) / periodic.length.prod();
}

template <int D>
double Simulation<D>::tracked_kick(bool drift) {
  auto& p = particles;
  const bool deforming = cell_motion.active();
  const double half_dt = 0.5 * time_step;
  const bool referenced = list_.reference().size() == p.size();
  const auto groups = static_cast<std::int64_t>((p.size() + 3) / 4);
  // Each group's works apart, then added in group order: the same sums
  // whatever the thread count.
  group_works_.assign(static_cast<std::size_t>(groups), EnergyBudget{});
  auto one = [&](std::int64_t g) {
    const auto first = static_cast<std::size_t>(4 * g);
    const std::size_t last = std::min<std::size_t>(first + 4, p.size());
    std::array<Vec<D>, 4> v;
    std::array<AngVec<D>, 4> w;
    for (std::size_t i = first; i < last; ++i) {
      v[i - first] = p.velocity[i];
      w[i - first] = p.angular_velocity[i];
    }
    kick_group(first, half_dt);
    for (std::size_t i = first; i < last; ++i) {
      account_kick(i, v[i - first], w[i - first], half_dt, group_works_[static_cast<std::size_t>(g)]);
    }
    if (!drift) return 0.0;
    return deforming ? drift_group_in_field(first, referenced) : drift_group(first, referenced);
  };
  double moved2 = max_over_index(groups, parallel_threshold / 4, one);
  if (drift && deforming) stretch_cell();
  for (const auto& works : group_works_) energy.add(works);
  if (!clumps.empty()) {
    // The clumps' half kicks (their members' were skipped), each clump's
    // works apart, added in clump order.
    clump_works_.assign(clumps.size(), EnergyBudget{});
    const ClumpLoadKinds<D> kinds{force_gravity_, &field_force_, &clump_works_};
    moved2 = std::max(moved2, clumps.advance(p, 1, half_dt, damping.local, damping.viscous,
                                             drift ? time_step : 0.0, list_.reference(), &kinds));
    for (const auto& works : clump_works_) energy.add(works);
  }
  return std::sqrt(moved2);
}

template <int D>
template <class Law>
double Simulation<D>::compute_forces_for_law(Finish finish) {
  if (periodic.any()) {
    return rolling_ ? compute_forces_with<Law, true, true>(finish)
                    : compute_forces_with<Law, false, true>(finish);
  }
  return rolling_ ? compute_forces_with<Law, true, false>(finish)
                  : compute_forces_with<Law, false, false>(finish);
}

template <int D>
double Simulation<D>::compute_forces(Finish finish) {
  double moved = 0.0;
  switch (law_choice_) {
    case LawChoice::linear:
      moved = compute_forces_for_law<LinearSpringDashpot>(finish);
      break;
    case LawChoice::hertz:
      moved = compute_forces_for_law<HertzMindlin>(finish);
      break;
    case LawChoice::mixed:
      moved = compute_forces_for_law<MixedNormalLaw>(finish);
      break;
  }
  if (clumps.empty()) return moved;
  // The members' kicks were skipped and their drift was a straight line:
  // their clumps now take the same steps and put them in place.
  if (finish == Finish::none) {
    clumps.gather(particles);
    return moved;
  }
  const bool drift = finish == Finish::kick_kick_drift;
  const double moved2 = clumps.advance(particles, drift ? 2 : 1, 0.5 * time_step, damping.local,
                                       damping.viscous, drift ? time_step : 0.0, list_.reference());
  return std::max(moved, std::sqrt(moved2));
}

template <int D>
template <class Law, bool Rolling, bool Periodic>
double Simulation<D>::compute_forces_with(Finish finish) {
  auto& p = particles;
  auto& L = list_;
  auto& W = wall_list_;
  const auto n = static_cast<std::int64_t>(p.size());
  const double dt = time_step;
  const bool measure = measure_contact_forces;
  const bool recording = recording_;
  const bool row_moments = summing_moments_;
  const bool bonds = !L.bonded.empty();
  // One material: every pair has the same parameters.
  const PairParameters* uniform = materials.size() == 1 ? &contact_table(0, 0) : nullptr;
  // x_j - x_i, at j's nearest image across periodic boundaries.
  const PeriodicCell<D> cell = periodic;
  const Vec<D> rate = cell_motion.strain_rate;  // zero unless the cell deforms
  auto separation = [&cell](const Vec<D>& xj, const Vec<D>& xi) -> Vec<D> {
    if constexpr (Periodic) {
      return cell.shortest(xj - xi);
    } else {
      return xj - xi;
    }
  };

  // Wall contacts of particle i, added to its force f and torque t.
  auto wall_contacts = [&](std::int64_t i, const Vec<D>& xi, const Vec<D>& vi, const AngVec<D>& wi, Vec<D>& f,
                           AngVec<D>& t, double& magnitude_sum, double& touching) {
    const double ri = p.radius[i];
    const double inv_mi = p.inv_mass[i];
    const auto mat_i = p.material[i];
    for_each_wall_touch<D>(
        walls, W, static_cast<std::size_t>(i), xi, ri, [&](std::uint32_t k, const auto& touch, bool counts) {
          const Wall<D>& w = walls[W.wall[k]];
          const double overlap = ri - touch.gap;
          if (overlap <= 0.0 || inv_mi == 0.0 || !counts) {
            W.tangential[k].setZero();
            if constexpr (Rolling) W.rolling[k].setZero();
            W.force_on_particle[k].setZero();
            W.torque_on_particle[k].setZero();
            return;
          }
          const Vec<D> nrm = -touch.normal;
          const double arm_i = ri - overlap;
          // Against the wall's surface where they touch (a spinning drum's moves).
          const Vec<D> v_rel =
              vi + cross(AngVec<D>(wi * arm_i), nrm) - w.surface_velocity(Vec<D>(xi + arm_i * nrm));
          const AngVec<D> w_rel = w.spin == 0.0 ? wi : AngVec<D>(wi - w.angular_velocity());
          const auto c = evaluate_contact<D, Law>(contact_table(mat_i, w.material), nrm, overlap, arm_i, 0.0,
                                                  v_rel, w_rel, std::sqrt(1.0 / inv_mi), ri, dt,
                                                  W.tangential[k], Rolling ? &W.rolling[k] : nullptr);
          f += c.force_on_i;
          t += c.torque_i;
          if (measure) magnitude_sum += std::sqrt(c.force_on_i.squaredNorm());
          touching += 1.0;
          W.force_on_particle[k] = c.force_on_i;
          W.torque_on_particle[k] = c.torque_i;
        });
  };

  // A block's forces are summed in place, starting from zero.
  auto zero_block = [&](std::int64_t lo, std::int64_t hi) {
    for (std::int64_t i = lo; i < hi; ++i) {
      p.force[i].setZero();
      p.torque[i].setZero();
    }
    if (row_moments) std::fill(pair_moment_.begin() + lo, pair_moment_.begin() + hi, Vec<D>::Zero());
  };

  // Pass 1, block by block (verlet_list.hpp): every pair once, j's share added
  // to j directly inside the block and to a slot across blocks; the sum and
  // count of contact force magnitudes per block for the unbalanced force.
  auto block_pass = [&](std::int64_t b) {
    const std::int64_t lo = L.block_begin(b);
    const auto hi = static_cast<std::uint32_t>(L.block_end(b, n));
    zero_block(lo, hi);
    std::uint32_t slot = L.cross_begin[b];
    double magnitude_sum = 0.0;
    double touching = 0.0;
    for (std::int64_t i = lo; i < hi; ++i) {
      const Vec<D> xi = p.position[i];
      const Vec<D> vi = p.velocity[i];
      const AngVec<D> wi = p.angular_velocity[i];
      const double ri = p.radius[i];
      const double inv_mi = p.inv_mass[i];
      const auto mat_i = p.material[i];
      Vec<D> f = p.force[i];
      AngVec<D> t = p.torque[i];
      for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
        const std::uint32_t j = L.neighbour[k];
        const bool is_cross = j >= hi;
        const Vec<D> d = separation(p.position[j], xi);
        const double rj = p.radius[j];
        const double reach = ri + rj;
        const double dist2 = d.squaredNorm();
        const double inv_m = inv_mi + p.inv_mass[j];
        auto apply = [&](const ContactForce<D>& c) {
          f += c.force_on_i;
          t += c.torque_i;
          if (measure) magnitude_sum += std::sqrt(c.force_on_i.squaredNorm());
          touching += 1.0;
          if (recording) pair_force_[k] = c.force_on_i;
          if (row_moments) pair_moment_[i] += d.cwiseProduct(c.force_on_i);
          if (is_cross) {
            L.cross_force[slot] = -c.force_on_i;
            L.cross_torque[slot] = c.torque_j;
            ++slot;
          } else {
            p.force[j] -= c.force_on_i;
            p.torque[j] += c.torque_j;
          }
        };
        // Pair geometry for a contact (bonded or touching).
        auto contact_at = [&] {
          const double inv_dist = 1.0 / std::sqrt(dist2);
          const Vec<D> nrm = d * inv_dist;
          const double overlap = reach - dist2 * inv_dist;
          const double arm_i = ri - 0.5 * overlap;
          const double arm_j = rj - 0.5 * overlap;
          const AngVec<D> wj = p.angular_velocity[j];
          Vec<D> v_rel = vi - p.velocity[j] + cross(AngVec<D>(wi * arm_i + wj * arm_j), nrm);
          // A deforming cell's field: j's image moves at rate (x) d more than i.
          if constexpr (Periodic) v_rel -= rate.cwiseProduct(d);
          return std::tuple{nrm, overlap, arm_i, arm_j, v_rel, wj};
        };
        if (bonds && L.bonded[k] != 0 && inv_m != 0.0) {
          const auto [nrm, overlap, arm_i, arm_j, v_rel, wj] = contact_at();
          bool held = false;
          const PairParameters& pp = contact_table(mat_i, p.material[j]);
          const auto c = evaluate_bond<D>(pp, nrm, overlap, arm_i, arm_j, v_rel, wi - wj,
                                          std::sqrt(1.0 / inv_m), ri * rj / reach, dt, L.tangential[k],
                                          pp.bond_has_moment() ? &L.bond_rotation[k] : nullptr,
                                          pp.bond_strength_varies() ? L.bond_strength[k] : 1.0, held);
          if (held) {
            if constexpr (Rolling) L.rolling[k].setZero();
            apply(c);
            continue;
          }
          // Broken: from here on an unbonded pair, this step included.
          L.bonded[k] = 0;
#pragma omp atomic
          ++broken_bonds;
        }
        if (dist2 >= reach * reach || inv_m == 0.0) {
          L.tangential[k].setZero();
          if constexpr (Rolling) L.rolling[k].setZero();
          if (is_cross) {
            L.cross_force[slot].setZero();
            L.cross_torque[slot].setZero();
            ++slot;
          }
          continue;
        }
        const auto [nrm, overlap, arm_i, arm_j, v_rel, wj] = contact_at();
        const double sqrt_m_eff = std::sqrt(1.0 / inv_m);
        const double r_eff = ri * rj / reach;
        apply(evaluate_contact<D, Law>(contact_table(mat_i, p.material[j]), nrm, overlap, arm_i, arm_j, v_rel,
                                       wi - wj, sqrt_m_eff, r_eff, dt, L.tangential[k],
                                       Rolling ? &L.rolling[k] : nullptr));
      }
      wall_contacts(i, xi, vi, wi, f, t, magnitude_sum, touching);
      p.force[i] = f;
      p.torque[i] = t;
    }
    block_sums_[b] = {magnitude_sum, touching};
  };
  // The same pass for linear contacts without rolling resistance, a batch of
  // pairs at a time (contact_batch.hpp): rows are walked in order, each
  // batch's results added in pair order, so the sums are the same whatever
  // the thread count.
  auto batched_block_pass = [&](std::int64_t b) {
    const std::int64_t lo = L.block_begin(b);
    const auto hi = static_cast<std::uint32_t>(L.block_end(b, n));
    zero_block(lo, hi);
    thread_local LinearContactBatch<D> batch;
    constexpr std::uint32_t no_slot = 0xFFFFFFFFU;
    std::uint32_t pair_i[LinearContactBatch<D>::capacity];
    std::uint32_t pair_k[LinearContactBatch<D>::capacity];
    std::uint32_t pair_slot[LinearContactBatch<D>::capacity];
    std::uint32_t slot = L.cross_begin[b];
    double magnitude_sum = 0.0;
    double touching = 0.0;
    // The flush adds each touching pair's results in pair order: i's share
    // straight into i, j's into j or, across blocks, into the pair's slot
    // (zeroed by the gather). Both targets are chosen without a branch:
    // whether the next pair has a new i, and whether it crosses blocks, are
    // close to random in a settled bed.
    auto flush = [&] {
      batch.evaluate(dt, uniform);
      Vec<D>* force = p.force.data();
      AngVec<D>* torque = p.torque.data();
      Vec<D>* cross_force = L.cross_force.data();
      AngVec<D>* cross_torque = L.cross_torque.data();
      for (int q = 0; q < batch.size; ++q) {
        const std::uint32_t i = pair_i[q];
        const std::uint32_t k = pair_k[q];
        const std::uint32_t j = L.neighbour[k];
        const bool cross = pair_slot[q] != no_slot;
        const std::uint32_t slot = cross ? pair_slot[q] : 0;
        Vec<D> fq;
        AngVec<D> tiq;
        AngVec<D> tjq;
        for (int c = 0; c < D; ++c) {
          fq[c] = batch.f[c][q];
          L.tangential[k][c] = batch.h_new[c][q];
        }
        for (int c = 0; c < rotation_dim<D>; ++c) {
          tiq[c] = batch.ti[c][q];
          tjq[c] = batch.tj[c][q];
        }
        force[i] += fq;
        torque[i] += tiq;
        if (recording) pair_force_[k] = fq;
        if (row_moments) {
          Vec<D> dq;
          for (int c = 0; c < D; ++c) dq[c] = batch.d[c][q];
          pair_moment_[i] += dq.cwiseProduct(fq);
        }
        if (measure) magnitude_sum += std::sqrt(fq.squaredNorm());
        Vec<D>* fj = cross ? cross_force + slot : force + j;
        AngVec<D>* tj = cross ? cross_torque + slot : torque + j;
        *fj -= fq;
        *tj += tjq;
      }
      batch.size = 0;
    };
    // Gather: every pair is written at the batch's end, which advances only
    // if the pair touches (compaction without a branch: about a third of the
    // pairs of a settled bed are within the skin but apart). Every history
    // is zeroed here; the flush writes the touching pairs' results. The
    // arrays are reached through local pointers and the batch's fill count
    // is a local, so that the stores into the batch do not force the
    // compiler to reload them every pair.
    const Vec<D>* __restrict x = p.position.data();
    const Vec<D>* __restrict vel = p.velocity.data();
    const AngVec<D>* __restrict omega = p.angular_velocity.data();
    const double* __restrict radius = p.radius.data();
    const double* __restrict inv_mass = p.inv_mass.data();
    const std::uint32_t* __restrict row = L.row_offset.data();
    const std::uint32_t* __restrict neighbour = L.neighbour.data();
    Vec<D>* __restrict history = L.tangential.data();
    int q = 0;
    std::int64_t touched = 0;
    // The block's cross slots start at zero; the flush adds the touching
    // pairs' shares.
    std::fill(L.cross_force.begin() + L.cross_begin[b], L.cross_force.begin() + L.cross_begin[b + 1],
              Vec<D>::Zero());
    std::fill(L.cross_torque.begin() + L.cross_begin[b], L.cross_torque.begin() + L.cross_begin[b + 1],
              AngVec<D>::Zero());
    for (std::int64_t i = lo; i < hi; ++i) {
      const Vec<D> xi = x[i];
      const Vec<D> vi = vel[i];
      const AngVec<D> wi = omega[i];
      const double ri = radius[i];
      const double inv_mi = inv_mass[i];
      const std::uint32_t row_end = row[i + 1];
      for (std::uint32_t k = row[i]; k < row_end; ++k) {
        const std::uint32_t j = neighbour[k];
        const std::uint32_t cross = j >= hi ? 1U : 0U;
        const std::uint32_t pair_slot_k = cross != 0U ? slot : no_slot;
        slot += cross;
        pair_i[q] = static_cast<std::uint32_t>(i);
        pair_k[q] = k;
        pair_slot[q] = pair_slot_k;
        const Vec<D> d = separation(x[j], xi);
        Vec<D> dv = vi - vel[j];
        if constexpr (Periodic) dv -= rate.cwiseProduct(d);
        const AngVec<D> wj = omega[j];
        const Vec<D> h = history[k];
        for (int c = 0; c < D; ++c) {
          batch.d[c][q] = d[c];
          batch.v[c][q] = dv[c];
          batch.h[c][q] = h[c];
        }
        for (int c = 0; c < rotation_dim<D>; ++c) {
          batch.wi[c][q] = wi[c];
          batch.wj[c][q] = wj[c];
        }
        const double rj = radius[j];
        const double inv_m = inv_mi + inv_mass[j];
        batch.ri[q] = ri;
        batch.rj[q] = rj;
        batch.inv_m[q] = inv_m;
        if (uniform == nullptr) batch.set_parameters(q, contact_table(p.material[i], p.material[j]));
        // Whether the pair touches, as 0 or 1 from the sign bit of
        // |d|^2 - (r_i + r_j)^2 (negative exactly when |d|^2 is smaller), so
        // that the compiler cannot turn it into a branch.
        const double reach = ri + rj;
        const double reach2 = reach * reach;
        const auto apart = std::bit_cast<std::uint64_t>(d.squaredNorm() - reach2);
        const auto touch = static_cast<int>(apart >> 63U) & static_cast<int>(inv_m > 0.0);
        // The history has been copied into the batch: zero it in the list,
        // where the flush writes the new history of a touching pair, and a
        // pair that stopped touching keeps the zero. (Testing whether it is
        // zero already would be a branch on whether the pair touches, which
        // mispredicts in a third of the pairs of a settled bed.)
        history[k].setZero();
        q += touch;
        touched += touch;
        if (q == LinearContactBatch<D>::capacity) {
          batch.size = q;
          flush();
          q = 0;
        }
      }
    }
    batch.size = q;
    flush();
    touching += static_cast<double>(touched);
    // Walls, particle by particle, after the pairs (only particles with a
    // wall within reach: most have none).
    for (std::int64_t i = lo; i < hi; ++i) {
      if (W.offset[i] == W.offset[i + 1]) continue;
      Vec<D> f = p.force[i];
      AngVec<D> t = p.torque[i];
      wall_contacts(i, p.position[i], p.velocity[i], p.angular_velocity[i], f, t, magnitude_sum, touching);
      p.force[i] = f;
      p.torque[i] = t;
    }
    block_sums_[b] = {magnitude_sum, touching};
  };
  constexpr bool batched = std::is_same_v<Law, LinearSpringDashpot> && !Rolling;

  const std::int64_t blocks = L.block_count();
  auto pass = [&](std::int64_t b) {
    if constexpr (batched) {
      // Bonded pairs need the general pass (the batch has no bonds).
      if (bonds) {
        block_pass(b);
      } else {
        batched_block_pass(b);
      }
    } else {
      block_pass(b);
    }
  };

  // Pass 2: each particle adds its cross shares in slot order, then gravity,
  // external forces and the force field; in a step it takes its second half
  // kick, and inside advance() at once the next step's first half kick and
  // drift (the same operations as separate sweeps, one sweep fewer).
  const Vec<D> g = gravity;
  force_gravity_ = g;
  const bool field = force_field != nullptr;
  const bool external = !p.external_force.empty();
  const double half_dt = 0.5 * dt;
  const bool referenced = L.reference().size() == p.size();
  auto finish_one = [&](std::int64_t j) {
    Vec<D> f = p.force[j];
    AngVec<D> t = p.torque[j];
    for (std::uint32_t q = L.cross_offset[j]; q < L.cross_offset[j + 1]; ++q) {
      const std::uint32_t s = L.cross_slot[q];
      f += L.cross_force[s];
      t += L.cross_torque[s];
    }
    if (external) f += p.external_force[j];
    if (field) f += field_force_[j];
    if (p.inv_mass[j] > 0.0) f += g / p.inv_mass[j];
    p.force[j] = f;
    p.torque[j] = t;
  };
  // Four particles at a time (kick.hpp): their forces, then the kicks and
  // the drift. Blocks hold whole groups of four (verlet_list.cpp).
  auto finish_group = [&](std::int64_t group) {
    const auto first = static_cast<std::size_t>(4 * group);
    const auto last = std::min<std::int64_t>(4 * group + 4, n);
    for (auto j = static_cast<std::int64_t>(first); j < last; ++j) finish_one(j);
    if (finish == Finish::none) return 0.0;
    kick_group(first, half_dt);
    if (finish == Finish::kick) return 0.0;
    kick_group(first, half_dt);
    return drift_group(first, referenced);
  };
  auto finish_block = [&](std::int64_t b) {
    double moved2 = 0.0;
    const std::int64_t end = (L.block_end(b, n) + 3) / 4;
    for (std::int64_t k = L.block_begin(b) / 4; k < end; ++k) moved2 = std::max(moved2, finish_group(k));
    return moved2;
  };

  // Each thread takes a run of consecutive blocks and, right after a block's
  // pass 1, its pass 2 while the block's particles are still in the
  // processor's cache, unless the block has cross pairs from another
  // thread's blocks (they may not be written yet, and those blocks read this
  // block's particles): such blocks wait for all pass 1 to end. A block's
  // pass 1 reads and writes only its own and later particles, so no other
  // block needs a finished block's old state. Each particle's sums are the
  // same whatever the order, so results do not depend on the thread count.
  auto run_blocks = [&](std::int64_t first, std::int64_t last, auto&& wait) {
    double moved2 = 0.0;
    for (std::int64_t b = first; b < last; ++b) {
      pass(b);
      if (L.earliest_source(b) >= first) moved2 = std::max(moved2, finish_block(b));
    }
    wait();
    for (std::int64_t b = first; b < last; ++b) {
      if (L.earliest_source(b) < first) moved2 = std::max(moved2, finish_block(b));
    }
    return moved2;
  };
  // The field's forces, unless it holds those it gave last (to this
  // simulation, for as many particles).
  if (field && (field_force_.size() != p.size() || field_forces_from_ != force_field ||
                !force_field->forces_current(p, gravity, field_force_))) {
    field_force_.resize(p.size());
    force_field->particle_forces(p, gravity, field_force_);
    field_forces_from_ = force_field;
  }
  double moved2 = 0.0;
  if (blocks > 1) {
#pragma omp parallel reduction(max : moved2)
    {
      const std::int64_t threads = omp_get_num_threads();
      const std::int64_t t = omp_get_thread_num();
      moved2 = run_blocks(blocks * t / threads, blocks * (t + 1) / threads, [] {
#pragma omp barrier
      });
    }
  } else {
    moved2 = run_blocks(0, blocks, [] {});
  }

  // A moment only about an axis (a 3D plane or box never turned has none:
  // its torque stays 0), a radial load only on a cylinder.
  bool moments = false;
  bool cylinders = false;
  for (auto& w : walls) {
    w.force.setZero();
    w.torque = 0.0;
    w.radial_load = 0.0;
    moments = moments || w.has_axis();
    cylinders = cylinders || w.is_cylinder();
  }
  for (std::int64_t i = 0; i < n; ++i) {
    for (std::uint32_t k = W.offset[i]; k < W.offset[i + 1]; ++k) {
      Wall<D>& w = walls[W.wall[k]];
      w.force -= W.force_on_particle[k];
      // The contact's action on the particle about the axis: its force at
      // the particle's centre and its torque about that centre; and its
      // push on a cylinder's surface, along the normal from the wall to the
      // particle.
      if (moments && w.has_axis())
        w.torque -= w.moment_about_axis(p.position[i], W.force_on_particle[k], W.torque_on_particle[k]);
      if (cylinders && w.is_cylinder() && W.force_on_particle[k] != Vec<D>::Zero())
        w.radial_load += W.force_on_particle[k].dot(w.cylinder_touch(p.position[i]).normal);
    }
  }
  return std::sqrt(moved2);
}

namespace {
// How much stiffer than k_n on the mass m the fastest mode of a linear
// contact is. Against a wall (the stiffest case) the normal mode has
// omega^2 = k_n/m. A sticking tangential spring also turns the grain: the
// contact point has the mass 1/(1/m + r^2/I) = m/(1 + 1/alpha), I = alpha m r^2,
// so omega^2 = k_t (1 + 1/alpha)/m (3.5 k_t/m for spheres, 3 k_t/m for discs).
// A rolling spring k_r = 2.25 k_n mu_r^2 r^2 on I alone gives
// omega^2 = 2.25 mu_r^2 k_n/(alpha m). Both springs on one grain: the largest
// omega^2 is at most the sum (the trace of M^-1 K, K positive semidefinite),
// which is exact when either is absent. Between two free grains every
// omega^2 doubles, the ratios stay.
template <int D>
double linear_mode_factor(const PairParameters& pp) {
  double turning = 0.0;
  // A bond's tangential spring acts without friction too.
  if (pp.friction > 0.0 || pp.bondable) turning += pp.tangential_ratio * (1.0 + 1.0 / inertia_factor<D>);
  if (pp.rolling_friction > 0.0)
    turning += 2.25 * pp.rolling_friction * pp.rolling_friction / inertia_factor<D>;
  // A bond's bending and twisting springs, ratio k_n R*^2 with R* <= r, on I
  // alone (R* = r bounds a small grain bonded to a much larger one).
  if (pp.bond_has_moment()) turning += (pp.bond_bending_ratio + pp.bond_twisting_ratio) / inertia_factor<D>;
  return std::max(1.0, turning);
}
}  // namespace

template <int D>
double Simulation<D>::critical_time_step() const {
  const std::size_t nm = materials.size();
  std::vector<double> m_min(nm, std::numeric_limits<double>::infinity());
  std::vector<double> r_min(nm, std::numeric_limits<double>::infinity());
  std::vector<bool> used(nm, false);
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const auto mat = particles.material[i];
    used[mat] = true;
    r_min[mat] = std::min(r_min[mat], particles.radius[i]);
    if (particles.inv_mass[i] > 0.0 && particles.fixed[i] != ParticleData<D>::clump_member)
      m_min[mat] = std::min(m_min[mat], 1.0 / particles.inv_mass[i]);
  }
  // A clump's member moves with the clump: a contact on it drives the
  // clump's mass and inertia, felt at its arm.
  for (std::size_t c = 0; c < clumps.size(); ++c) {
    if (clumps.fixed[c] != 0) continue;
    for (std::uint32_t k = clumps.first[c]; k < clumps.first[c + 1]; ++k) {
      const std::uint32_t i = clumps.member_index[k];
      const auto mat = particles.material[i];
      m_min[mat] = std::min(m_min[mat], clumps.contact_mass(c, k));
    }
  }
  std::vector<bool> wall_used(nm, false);
  for (const auto& w : walls) wall_used[w.material] = true;
  double dt = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < nm; ++a) {
    if (!used[a] || !std::isfinite(m_min[a])) continue;
    for (std::size_t b = 0; b < nm; ++b) {
      if (!used[b] && !wall_used[b]) continue;
      const PairParameters& pp = contact_table(a, b);
      if (pp.law == NormalLaw::linear) {
        dt = std::min(dt, std::sqrt(m_min[a] / (pp.normal_stiffness * linear_mode_factor<D>(pp))));
      } else {
        const Material& m = materials[a];
        const double shear = m.youngs_modulus / (2.0 * (1.0 + m.poisson_ratio));
        const double rayleigh =
            std::numbers::pi * r_min[a] * std::sqrt(m.density / shear) / (0.1631 * m.poisson_ratio + 0.8766);
        dt = std::min(dt, rayleigh);
      }
    }
  }
  return dt;
}

template <int D>
double Simulation<D>::kinetic_energy() const {
  const auto& p = particles;
  // A clump's members count as its body: 1/2 M v^2 + 1/2 w.L (with
  // overlapping members not their sum).
  const double loose = deterministic_sum(static_cast<std::int64_t>(p.size()), [&](std::int64_t i) {
    if (p.inv_mass[i] == 0.0 || p.fixed[i] == ParticleData<D>::clump_member) return 0.0;
    return 0.5 * p.velocity[i].squaredNorm() / p.inv_mass[i] +
           0.5 * p.angular_velocity[i].squaredNorm() / p.inv_inertia[i];
  });
  return clumps.empty() ? loose : loose + clumps.kinetic_energy();
}

template <int D>
double Simulation<D>::gravitational_energy() const {
  const auto& p = particles;
  return deterministic_sum(static_cast<std::int64_t>(p.size()), [&](std::int64_t i) {
    if (p.inv_mass[i] == 0.0) return 0.0;
    // A fixed clump's members, as fixed particles, hold none.
    if (p.fixed[i] == ParticleData<D>::clump_member &&
        clumps.fixed[static_cast<std::size_t>(clumps.clump_of[static_cast<std::size_t>(i)])] != 0)
      return 0.0;
    return -gravity.dot(p.position[i]) / p.inv_mass[i];
  });
}

namespace {
template <int D, class F>
void for_each_touching(const ParticleData<D>& p, const VerletList<D>& L, const PeriodicCell<D>& cell, F&& f) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
      const std::uint32_t j = L.neighbour[k];
      const double overlap = p.radius[i] + p.radius[j] - cell.shortest(p.position[j] - p.position[i]).norm();
      if (overlap > 0.0) f(i, j, k, overlap, false);
    }
  }
}
}  // namespace

template <int D>
std::size_t Simulation<D>::contact_count() const {
  std::size_t count = 0;
  for_each_touching(particles, list_, periodic,
                    [&](std::size_t, std::uint32_t, std::uint32_t, double, bool) { ++count; });
  for (std::size_t i = 0; i < particles.size(); ++i) {
    for_each_wall_touch<D>(walls, wall_list_, i, particles.position[i], particles.radius[i],
                           [&](std::uint32_t, const auto& touch, bool counts) {
                             if (counts && touch.gap < particles.radius[i]) ++count;
                           });
  }
  return count;
}

template <int D>
double Simulation<D>::mean_coordination() const {
  if (particles.size() == 0) return 0.0;
  std::size_t pp = 0;
  for_each_touching(particles, list_, periodic,
                    [&](std::size_t, std::uint32_t, std::uint32_t, double, bool) { ++pp; });
  const std::size_t all = contact_count();
  return static_cast<double>(2 * pp + (all - pp)) / static_cast<double>(particles.size());
}

template <int D>
std::vector<std::vector<Vec<D>>> Simulation<D>::facet_forces() const {
  std::vector<std::vector<Vec<D>>> out(walls.size());
  for (std::size_t w = 0; w < walls.size(); ++w) {
    if (walls[w].is_mesh()) out[w].assign(walls[w].mesh->triangle.size(), Vec<D>::Zero());
  }
  const auto& W = wall_list_;
  for (std::size_t k = 0; k < W.wall.size(); ++k) {
    auto& facets = out[W.wall[k]];
    if (!facets.empty()) facets[W.facet[k]] -= W.force_on_particle[k];
  }
  return out;
}

template <int D>
double Simulation<D>::max_overlap() const {
  double m = 0.0;
  for_each_touching(particles, list_, periodic,
                    [&](std::size_t, std::uint32_t, std::uint32_t, double o, bool) { m = std::max(m, o); });
  for (std::size_t i = 0; i < particles.size(); ++i) {
    for_each_wall_touch<D>(walls, wall_list_, i, particles.position[i], particles.radius[i],
                           [&](std::uint32_t, const auto& touch, bool counts) {
                             if (counts) m = std::max(m, particles.radius[i] - touch.gap);
                           });
  }
  return m;
}

template <int D>
double Simulation<D>::unbalanced_force_ratio() const {
  if (!measure_contact_forces) {
    throw std::logic_error("unbalanced_force_ratio() needs measure_contact_forces = true");
  }
  const auto& p = particles;
  double resultant = 0.0;
  std::size_t free_count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    // A clump's members pass forces to each other: the clump's resultant counts.
    if (p.inv_mass[i] == 0.0 || p.fixed[i] == ParticleData<D>::clump_member) continue;
    resultant += p.force[i].norm();
    ++free_count;
  }
  for (std::size_t c = 0; c < clumps.size(); ++c) {
    if (clumps.fixed[c] != 0) continue;
    resultant += clumps.force[c].norm();
    ++free_count;
  }
  double contact = 0.0;
  double contacts = 0.0;
  for (const auto& [sum, count] : block_sums_) {
    contact += sum;
    contacts += count;
  }
  if (free_count == 0) return 0.0;
  if (contacts == 0.0 || contact == 0.0) return std::numeric_limits<double>::infinity();
  return (resultant / static_cast<double>(free_count)) / (contact / contacts);
}

template <int D>
std::size_t Simulation<D>::memory_bytes() const {
  return particles.memory_bytes() + list_.memory_bytes() + wall_list_.memory_bytes() +
         field_force_.capacity() * sizeof(Vec<D>) + block_sums_.capacity() * sizeof(block_sums_[0]);
}

template <int D>
double Simulation<D>::elastic_energy() const {
  double e = 0.0;
  auto normal_energy = [&](const PairParameters& pp, double overlap, double r_eff) {
    if (pp.law == NormalLaw::linear) return 0.5 * pp.normal_stiffness * overlap * overlap;
    return 0.4 * (4.0 / 3.0) * pp.hertz_modulus * std::sqrt(r_eff) * std::pow(overlap, 2.5);
  };
  // The rolling spring (linear law): 1/2 k_r theta^2.
  auto rolling_energy = [](const PairParameters& pp, double r_eff, const AngVec<D>& theta) {
    return 0.5 * pp.rolling_stiffness(pp.normal_stiffness, r_eff) * theta.squaredNorm();
  };
  const auto& p = particles;
  // Particles added since the lists were built (an inlet's, placed where
  // they touch nothing) are not in them yet: the rows that are.
  const std::size_t pair_rows =
      std::min(p.size(), list_.row_offset.empty() ? 0 : list_.row_offset.size() - 1);
  const std::size_t wall_rows =
      std::min(p.size(), wall_list_.offset.empty() ? 0 : wall_list_.offset.size() - 1);
  for (std::size_t i = 0; i < std::max(pair_rows, wall_rows); ++i) {
    const std::uint32_t pairs_end = i < pair_rows ? list_.row_offset[i + 1] : 0;
    for (std::uint32_t k = i < pair_rows ? list_.row_offset[i] : 0; k < pairs_end; ++k) {
      const std::uint32_t j = list_.neighbour[k];
      const double reach = p.radius[i] + p.radius[j];
      const double overlap = reach - periodic.shortest(p.position[j] - p.position[i]).norm();
      // A bonded pair (linear) stores 1/2 k_n d^2 in tension too.
      if (overlap <= 0.0 && !list_.is_bonded(k)) continue;
      const auto& pp = contact_table(p.material[i], p.material[j]);
      e += normal_energy(pp, overlap, p.radius[i] * p.radius[j] / reach);
      if (pp.law == NormalLaw::linear) {
        e += 0.5 * pp.tangential_ratio * pp.normal_stiffness * list_.tangential[k].squaredNorm();
        if (!list_.rolling.empty())
          e += rolling_energy(pp, p.radius[i] * p.radius[j] / reach, list_.rolling[k]);
      }
      if (pp.bond_has_moment() && list_.is_bonded(k)) {
        // 1/2 k theta^2 of the bond's bending and twisting springs.
        const double r_eff = p.radius[i] * p.radius[j] / reach;
        const auto& rot = list_.bond_rotation[k];
        e += 0.5 * (pp.bond_bending_stiffness(r_eff) * rot.bending.squaredNorm() +
                    pp.bond_twisting_stiffness(r_eff) * rot.twist * rot.twist);
      }
    }
    if (i >= wall_rows) continue;
    for_each_wall_touch<D>(walls, wall_list_, i, p.position[i], p.radius[i],
                           [&](std::uint32_t k, const auto& touch, bool counts) {
                             const auto& w = walls[wall_list_.wall[k]];
                             const double overlap = p.radius[i] - touch.gap;
                             if (overlap <= 0.0 || !counts) return;
                             const auto& pp = contact_table(p.material[i], w.material);
                             e += normal_energy(pp, overlap, p.radius[i]);
                             if (pp.law == NormalLaw::linear) {
                               e += 0.5 * pp.tangential_ratio * pp.normal_stiffness *
                                    wall_list_.tangential[k].squaredNorm();
                               if (!wall_list_.rolling.empty())
                                 e += rolling_energy(pp, p.radius[i], wall_list_.rolling[k]);
                             }
                           });
  }
  return e;
}

template class Simulation<2>;
template class Simulation<3>;

}  // namespace darcydem
