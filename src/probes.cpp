#include "darcydem/output/probes.hpp"

#include <array>
#include <limits>

#include "darcydem/fluid/ball_overlap.hpp"
#include "darcydem/walls/loaded_area.hpp"

namespace darcydem {

template <int D>
std::size_t topmost_particle(const ParticleData<D>& particles) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < particles.size(); ++i) {
    if (particles.position[i][D - 1] > particles.position[best][D - 1]) best = i;
  }
  return best;
}

template <int D>
double box_porosity(const ParticleData<D>& particles, const Vec<D>& lo, const Vec<D>& hi,
                    const PeriodicCell<D>& periodic) {
  std::array<double, D> a{};
  std::array<double, D> b{};
  for (int k = 0; k < D; ++k) {
    a[k] = lo[k];
    b[k] = hi[k];
  }
  // The solid of one grain (or image) centred at x.
  auto in_box = [&](const Vec<D>& x, double r) {
    bool apart = false;
    bool within = true;
    for (int k = 0; k < D; ++k) {
      apart = apart || x[k] + r <= lo[k] || x[k] - r >= hi[k];
      within = within && x[k] - r >= lo[k] && x[k] + r <= hi[k];
    }
    if (apart) return 0.0;
    if (within) return particle_volume<D>(r);
    std::array<double, D> c{};
    for (int k = 0; k < D; ++k) c[k] = x[k];
    return ball_overlap::in_box<D>(r, c, a, b);
  };
  double solid = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double r = particles.radius[i];
    const Vec<D>& x = particles.position[i];
    const double scale = particles.volume_scale.empty() ? 1.0 : particles.volume_scale[i];
    if (!periodic.any()) {
      solid += scale * in_box(x, r);
      continue;
    }
    // Along each periodic axis the whole periods n that bring an image
    // within reach of the box; every combination of them.
    std::array<int, D> first{};
    std::array<int, D> count{};
    int images = 1;
    for (int k = 0; k < D; ++k) {
      count[k] = 1;
      if (!periodic.periodic[k]) continue;
      const double L = periodic.length[k];
      first[k] = static_cast<int>(std::ceil((lo[k] - r - x[k]) / L));
      count[k] = std::max(0, static_cast<int>(std::floor((hi[k] + r - x[k]) / L)) - first[k] + 1);
      images *= count[k];
    }
    for (int m = 0; m < images; ++m) {
      Vec<D> image = x;
      int rest = m;
      for (int k = 0; k < D; ++k) {
        image[k] += (first[k] + rest % count[k]) * periodic.length[k];
        rest /= count[k];
      }
      solid += scale * in_box(image, r);
    }
  }
  return 1.0 - solid / (hi - lo).prod();
}

template <int D>
std::vector<typename Simulation<D>::Moment> cell_contact_stress(const Simulation<D>& sim,
                                                                const FluidGrid<D>& grid) {
  using Moment = typename Simulation<D>::Moment;
  std::vector<Moment> sum(grid.size(), Moment::Zero());
  const auto moments = sim.contact_moments();
  for (std::size_t i = 0; i < moments.size(); ++i) {
    std::array<int, D> c{};
    const Vec<D> x = sim.periodic.wrap(sim.particles.position[i]);
    for (int k = 0; k < D; ++k) c[k] = grid.cell_along(k, x[k]);
    if (grid.inside(c)) sum[grid.index(c)] += moments[i];
  }
  for (std::size_t c = 0; c < sum.size(); ++c) {
    auto& m = sum[c];
    m = -0.5 * (m + m.transpose()) / grid.cell_volume(grid.coords(c));
  }
  return sum;
}

template <int D>
double evaluate_probe(const ProbeSpec& probe, const Simulation<D>& sim, const PoreFluid<D>* fluid,
                      const std::vector<Inlet<D>>* inlets) {
  auto pick = [&](const Vec<D>& v) { return probe.component < 0 ? v.norm() : v[probe.component]; };
  const auto& p = sim.particles;
  switch (probe.quantity) {
    case ProbeQuantity::particle_position:
    case ProbeQuantity::particle_velocity:
    case ProbeQuantity::particle_fluid_force: {
      const std::size_t i =
          probe.particle < 0 ? topmost_particle(p) : p.index_of(static_cast<std::uint32_t>(probe.particle));
      // A particle that has left the [domain], or none left at all.
      if (i >= p.size()) return std::numeric_limits<double>::quiet_NaN();
      if (probe.quantity == ProbeQuantity::particle_fluid_force) {
        const auto& f = sim.field_forces();
        return f.size() == p.size() ? pick(f[i]) : 0.0;  // no fluid force evaluated yet: none acted
      }
      return pick(probe.quantity == ProbeQuantity::particle_position ? p.position[i] : p.velocity[i]);
    }
    case ProbeQuantity::wall_position:
      return pick(sim.walls[probe.wall].point);
    case ProbeQuantity::wall_force:
      return pick(sim.walls[probe.wall].force);
    case ProbeQuantity::wall_torque:
      return sim.walls[probe.wall].torque;
    case ProbeQuantity::wall_radius:
      return sim.walls[probe.wall].radius;
    case ProbeQuantity::wall_stress:
      // Walls that have crossed leave no area: nan, as the servo stops the run.
      return wall_stress(sim.walls, probe.wall, sim.periodic);
    case ProbeQuantity::wall_target: {
      // Taken at the start of the last step (Simulation::update_servo_targets).
      const Wall<D>& w = sim.walls[probe.wall];
      if (w.motion != WallMotion::servo) return std::numeric_limits<double>::quiet_NaN();
      return w.servo.by_stress ? w.servo.target_stress : w.servo.target_force;
    }
    case ProbeQuantity::wall_fluid_force:
      if (fluid == nullptr) return 0.0;
      return pick(probe.barrier >= 0 ? fluid->barrier_thrust(static_cast<std::size_t>(probe.barrier))
                                     : fluid->wall_thrust(sim.walls, probe.wall));
    case ProbeQuantity::kinetic_energy:
      return sim.kinetic_energy();
    case ProbeQuantity::elastic_energy:
      return sim.elastic_energy();
    case ProbeQuantity::gravitational_energy:
      return sim.gravitational_energy();
    case ProbeQuantity::gravity_work:
      return sim.energy.gravity_work;
    case ProbeQuantity::fluid_work:
      return sim.energy.field_work;
    case ProbeQuantity::boundary_work:
      return sim.energy.boundary_work;
    case ProbeQuantity::damping_dissipation:
      return sim.energy.damping_dissipation();
    case ProbeQuantity::contact_dissipation:
      return sim.contact_dissipation();
    case ProbeQuantity::removed_particles:
      return static_cast<double>(sim.removed_count);
    case ProbeQuantity::removed_mass:
      return sim.removed_mass;
    case ProbeQuantity::inserted_particles:
      if (inlets != nullptr && probe.inlet >= 0) {
        // An inlet of clumps: their members, as the total counts them.
        const auto& in = (*inlets)[static_cast<std::size_t>(probe.inlet)];
        return static_cast<double>(in.inserted_particles());
      }
      return static_cast<double>(sim.inserted_count);
    case ProbeQuantity::inserted_mass:
      if (inlets != nullptr && probe.inlet >= 0)
        return (*inlets)[static_cast<std::size_t>(probe.inlet)].inserted_mass;
      return sim.inserted_mass;
    case ProbeQuantity::bonds:
      return static_cast<double>(sim.bond_count());
    case ProbeQuantity::broken_bonds:
      return static_cast<double>(sim.broken_bonds);
    case ProbeQuantity::cell_length:
      return sim.periodic.length[probe.component];
    case ProbeQuantity::cell_strain_rate:
      return sim.cell_motion.strain_rate[probe.component];
    case ProbeQuantity::cell_strain:
      return sim.cell_motion.strain(sim.periodic, probe.component);
    case ProbeQuantity::cell_stress: {
      const auto s = sim.cell_stress();
      return probe.tensor[0] < 0 ? s.trace() / D : s(probe.tensor[0], probe.tensor[1]);
    }
    case ProbeQuantity::contact_count:
      return static_cast<double>(sim.contact_count());
    case ProbeQuantity::coordination:
      return sim.mean_coordination();
    case ProbeQuantity::max_overlap:
      return sim.max_overlap();
    case ProbeQuantity::unbalanced_force:
      return sim.unbalanced_force_ratio();
    case ProbeQuantity::pore_pressure: {
      Vec<D> x;
      for (int k = 0; k < D; ++k) x[k] = probe.position[k];
      return fluid != nullptr ? fluid->pressure_at(x) : 0.0;
    }
    case ProbeQuantity::fluid_inflow: {
      if (fluid == nullptr) return 0.0;
      if (probe.side < 2 * D) return fluid->side_inflow(probe.side);
      const auto i = static_cast<std::size_t>(probe.side - 2 * D);
      return i < fluid->patches.size() ? fluid->patch_inflow(i)
                                       : fluid->source_inflow(i - fluid->patches.size());
    }
    case ProbeQuantity::side_pressure: {
      if (fluid == nullptr) return 0.0;
      // A source's: the pressure in the cell it feeds (a piezometer in the
      // well), or with a radius at its bore.
      const auto i = static_cast<std::size_t>(std::max(probe.side - 2 * D, 0));
      if (probe.side >= 2 * D && i >= fluid->patches.size())
        return fluid->well_pressure(i - fluid->patches.size());
      return fluid->side_pressure(probe.side);
    }
    case ProbeQuantity::screen_inflow: {
      if (fluid == nullptr) return 0.0;
      const auto i = static_cast<std::size_t>(probe.side - 2 * D) - fluid->patches.size();
      return fluid->screen_inflows(i).at(probe.screen_cell);
    }
    case ProbeQuantity::fluid_balance:
      return fluid != nullptr ? fluid->total_balance().imbalance() : 0.0;
    case ProbeQuantity::fluid_iterations:
      return fluid != nullptr ? fluid->last_solve().iterations : 0.0;
    case ProbeQuantity::stress:
    case ProbeQuantity::fabric:
    case ProbeQuantity::porosity: {
      Vec<D> lo;
      Vec<D> hi;
      for (int k = 0; k < D; ++k) {
        lo[k] = probe.box_min[k];
        hi[k] = probe.box_max[k];
      }
      if (probe.quantity == ProbeQuantity::porosity) return box_porosity<D>(p, lo, hi, sim.periodic);
      if (probe.quantity == ProbeQuantity::fabric)
        return sim.contact_fabric(lo, hi)(probe.tensor[0], probe.tensor[1]);
      const auto s = sim.contact_stress(lo, hi);
      return probe.tensor[0] < 0 ? s.trace() / D : s(probe.tensor[0], probe.tensor[1]);
    }
    case ProbeQuantity::particles_in_box:
    case ProbeQuantity::mean_particle_position:
    case ProbeQuantity::fluid_force: {
      double count = 0.0;
      double sum = 0.0;
      Vec<D> force = Vec<D>::Zero();
      const auto& f = sim.field_forces();
      const bool forces = f.size() == p.size();
      Vec<D> lo;
      Vec<D> hi;
      for (int k = 0; k < D; ++k) {
        lo[k] = probe.box_min[k];
        hi[k] = probe.box_max[k];
      }
      // Along a periodic axis, the centre's image in the box.
      Vec<D> image;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (sim.periodic.image_in_box(p.position[i], lo, hi, &image)) {
          count += 1.0;
          if (probe.component >= 0) sum += image[probe.component];
          if (forces) force += f[i];
        }
      }
      if (probe.quantity == ProbeQuantity::fluid_force) return pick(force);
      if (probe.quantity == ProbeQuantity::particles_in_box) return count;
      return count > 0.0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return 0.0;
}

template double evaluate_probe<2>(const ProbeSpec&, const Simulation<2>&, const PoreFluid<2>*,
                                  const std::vector<Inlet<2>>*);
template double evaluate_probe<3>(const ProbeSpec&, const Simulation<3>&, const PoreFluid<3>*,
                                  const std::vector<Inlet<3>>*);
template double box_porosity<2>(const ParticleData<2>&, const Vec<2>&, const Vec<2>&, const PeriodicCell<2>&);
template double box_porosity<3>(const ParticleData<3>&, const Vec<3>&, const Vec<3>&, const PeriodicCell<3>&);
template std::vector<Simulation<2>::Moment> cell_contact_stress<2>(const Simulation<2>&, const FluidGrid<2>&);
template std::vector<Simulation<3>::Moment> cell_contact_stress<3>(const Simulation<3>&, const FluidGrid<3>&);
template std::size_t topmost_particle<2>(const ParticleData<2>&);
template std::size_t topmost_particle<3>(const ParticleData<3>&);

}  // namespace darcydem
