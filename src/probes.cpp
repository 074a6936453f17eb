#include "darcydem/output/probes.hpp"

#include <array>
#include <limits>

#include "darcydem/fluid/ball_overlap.hpp"

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
double box_porosity(const ParticleData<D>& particles, const Vec<D>& lo, const Vec<D>& hi) {
  std::array<double, D> a{};
  std::array<double, D> b{};
  for (int k = 0; k < D; ++k) {
    a[k] = lo[k];
    b[k] = hi[k];
  }
  double solid = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double r = particles.radius[i];
    const Vec<D>& x = particles.position[i];
    bool apart = false;
    bool within = true;
    for (int k = 0; k < D; ++k) {
      apart = apart || x[k] + r <= lo[k] || x[k] - r >= hi[k];
      within = within && x[k] - r >= lo[k] && x[k] + r <= hi[k];
    }
    if (apart) continue;
    if (within) {
      solid += particle_volume<D>(r);
      continue;
    }
    std::array<double, D> c{};
    for (int k = 0; k < D; ++k) c[k] = x[k];
    solid += ball_overlap::in_box<D>(r, c, a, b);
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
    for (int k = 0; k < D; ++k) c[k] = grid.cell_along(k, sim.particles.position[i][k]);
    if (grid.inside(c)) sum[grid.index(c)] += moments[i];
  }
  const double volume = grid.cell_volume();
  for (auto& m : sum) m = -0.5 * (m + m.transpose()) / volume;
  return sum;
}

template <int D>
double evaluate_probe(const ProbeSpec& probe, const Simulation<D>& sim, const PoreFluid<D>* fluid) {
  auto pick = [&](const Vec<D>& v) { return probe.component < 0 ? v.norm() : v[probe.component]; };
  const auto& p = sim.particles;
  switch (probe.quantity) {
    case ProbeQuantity::particle_position:
    case ProbeQuantity::particle_velocity: {
      const std::size_t i =
          probe.particle < 0 ? topmost_particle(p) : p.index_of(static_cast<std::uint32_t>(probe.particle));
      return pick(probe.quantity == ProbeQuantity::particle_position ? p.position[i] : p.velocity[i]);
    }
    case ProbeQuantity::wall_position:
      return pick(sim.walls[probe.wall].point);
    case ProbeQuantity::wall_force:
      return pick(sim.walls[probe.wall].force);
    case ProbeQuantity::kinetic_energy:
      return sim.kinetic_energy();
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
    case ProbeQuantity::fluid_inflow:
      if (fluid == nullptr) return 0.0;
      return probe.side < 2 * D ? fluid->side_inflow(probe.side)
                                : fluid->patch_inflow(static_cast<std::size_t>(probe.side - 2 * D));
    case ProbeQuantity::fluid_balance:
      return fluid != nullptr ? fluid->total_balance().imbalance() : 0.0;
    case ProbeQuantity::fluid_iterations:
      return fluid != nullptr ? fluid->last_solve().iterations : 0.0;
    case ProbeQuantity::stress:
    case ProbeQuantity::porosity: {
      Vec<D> lo;
      Vec<D> hi;
      for (int k = 0; k < D; ++k) {
        lo[k] = probe.box_min[k];
        hi[k] = probe.box_max[k];
      }
      if (probe.quantity == ProbeQuantity::porosity) return box_porosity<D>(p, lo, hi);
      const auto s = sim.contact_stress(lo, hi);
      return probe.tensor[0] < 0 ? s.trace() / D : s(probe.tensor[0], probe.tensor[1]);
    }
    case ProbeQuantity::particles_in_box:
    case ProbeQuantity::mean_particle_position: {
      double count = 0.0;
      double sum = 0.0;
      for (std::size_t i = 0; i < p.size(); ++i) {
        bool inside = true;
        for (int k = 0; k < D; ++k) {
          inside = inside && p.position[i][k] >= probe.box_min[k] && p.position[i][k] <= probe.box_max[k];
        }
        if (inside) {
          count += 1.0;
          sum += p.position[i][probe.component];
        }
      }
      if (probe.quantity == ProbeQuantity::particles_in_box) return count;
      return count > 0.0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return 0.0;
}

template double evaluate_probe<2>(const ProbeSpec&, const Simulation<2>&, const PoreFluid<2>*);
template double evaluate_probe<3>(const ProbeSpec&, const Simulation<3>&, const PoreFluid<3>*);
template double box_porosity<2>(const ParticleData<2>&, const Vec<2>&, const Vec<2>&);
template double box_porosity<3>(const ParticleData<3>&, const Vec<3>&, const Vec<3>&);
template std::vector<Simulation<2>::Moment> cell_contact_stress<2>(const Simulation<2>&, const FluidGrid<2>&);
template std::vector<Simulation<3>::Moment> cell_contact_stress<3>(const Simulation<3>&, const FluidGrid<3>&);
template std::size_t topmost_particle<2>(const ParticleData<2>&);
template std::size_t topmost_particle<3>(const ParticleData<3>&);

}  // namespace darcydem
