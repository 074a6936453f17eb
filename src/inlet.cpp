#include "darcydem/generation/inlet.hpp"

#include <algorithm>
#include <cmath>

namespace darcydem {

template <int D>
double inlet_grain_mass(const Inlet<D>& inlet, const Simulation<D>& sim, double radius) {
  const double density = sim.materials[inlet.material].density;
  if (inlet.clump) return density * inlet.clump->volume * std::pow(radius, D);
  return ParticleData<D>::mass_of(density, radius);
}

template <int D>
InsertionResult insert_due(Inlet<D>& inlet, Simulation<D>& sim) {
  InsertionResult result;
  const bool by_count = inlet.rate > 0.0;
  inlet.budget += (by_count ? inlet.rate : inlet.mass_rate) * inlet.interval;
  inlet.next_time += inlet.interval;
  if (inlet.next_radius <= 0.0) inlet.next_radius = inlet.radii.sample(inlet.rng);
  // The particles that can touch a grain in the box: their centres within
  // their radius plus the largest new grain's of it (nearest image).
  const double reach = inlet.radii.largest();
  const Vec<D> centre = 0.5 * (inlet.lower + inlet.upper);
  const Vec<D> half = 0.5 * (inlet.upper - inlet.lower);
  const auto& cell = sim.periodic;
  auto separation = [&](const Vec<D>& d) { return cell.any() ? cell.shortest(d) : d; };
  std::vector<Vec<D>> near_x;
  std::vector<double> near_r;
  const auto& p = sim.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec<D> d = separation(p.position[i] - centre);
    double outside2 = 0.0;
    for (int k = 0; k < D; ++k) {
      const double e = std::max(0.0, std::abs(d[k]) - half[k]);
      outside2 += e * e;
    }
    const double r = p.radius[i] + reach;
    if (outside2 < r * r) {
      near_x.push_back(p.position[i]);
      near_r.push_back(p.radius[i]);
    }
  }
  auto fits = [&](const Vec<D>& x, double r) {
    for (std::size_t j = 0; j < near_x.size(); ++j) {
      const double reach_j = r + near_r[j];
      if (separation(near_x[j] - x).squaredNorm() < reach_j * reach_j) return false;
    }
    return std::all_of(sim.walls.begin(), sim.walls.end(), [&](const Wall<D>& w) { return w.gap(x) >= r; });
  };
  // A clump's members where it would stand: centre of mass x, size r, turned by q.
  std::vector<Vec<D>> member_x;
  std::vector<double> member_r;
  auto members = [&](const Vec<D>& x, double r, const Orientation<D>& q) {
    const auto rot = rotation_matrix(compose(q, inlet.clump->principal));
    member_x.clear();
    member_r.clear();
    for (std::size_t k = 0; k < inlet.clump->centre.size(); ++k) {
      member_x.push_back(x + rot * Vec<D>(r * inlet.clump->centre[k]));
      member_r.push_back(r * inlet.clump->radius[k]);
    }
  };
  auto clump_fits = [&] {
    for (std::size_t k = 0; k < member_x.size(); ++k)
      if (!fits(member_x[k], member_r[k])) return false;
    return true;
  };
  // Due: a whole grain (by count), or the next grain's mass (by mass), to
  // a relative 1e-9 (a rate x interval of 10 may sum to 9.999999999).
  constexpr double slack = 1e-9;
  while (!inlet.exhausted()) {
    const double r = inlet.next_radius;
    const double m = inlet_grain_mass(inlet, sim, r);
    if (inlet.budget < (by_count ? 1.0 : m) * (1.0 - slack)) break;
    Vec<D> x = Vec<D>::Zero();
    Orientation<D> q = ClumpShape<D>::identity_orientation();
    bool placed = false;
    for (std::int64_t a = 0; a < inlet.max_attempts && !placed; ++a) {
      if (inlet.cylinder) {
        x = inlet.cylinder->sample(r, inlet.rng);
      } else {
        for (int k = 0; k < D; ++k) {
          x[k] = inlet.lower[k] + r + unit_random(inlet.rng) * (inlet.upper[k] - inlet.lower[k] - 2.0 * r);
        }
      }
      if (!inlet.clump) {
        placed = fits(x, r);
        continue;
      }
      if (!inlet.aligned) q = random_orientation<D>(inlet.rng);
      members(x, r, q);
      placed = clump_fits();
    }
    if (!placed) {
      result.short_of_room = true;
      ++inlet.short_events;
      break;
    }
    double added_mass = m;
    if (inlet.clump) {
      const std::size_t c = sim.add_clump(*inlet.clump, r, x, q, inlet.material, inlet.velocity);
      added_mass = sim.clumps.mass[c];
      near_x.insert(near_x.end(), member_x.begin(), member_x.end());
      near_r.insert(near_r.end(), member_r.begin(), member_r.end());
    } else {
      sim.add_particle(x, r, inlet.material, inlet.velocity);
      near_x.push_back(x);
      near_r.push_back(r);
    }
    inlet.budget -= by_count ? 1.0 : added_mass;
    ++inlet.inserted;
    inlet.inserted_mass += added_mass;
    ++result.added;
    inlet.next_radius = inlet.radii.sample(inlet.rng);
  }
  return result;
}

template <int D>
void insert_all_due(std::vector<Inlet<D>>& inlets, Simulation<D>& sim) {
  for (auto& in : inlets) {
    while (in.active && !in.exhausted() && sim.time >= in.next_time - 0.5 * sim.time_step)
      insert_due(in, sim);
  }
}

template <int D>
double next_insertion_time(const std::vector<Inlet<D>>& inlets) {
  double t = 1e300;
  for (const auto& in : inlets) {
    if (in.active && !in.exhausted()) t = std::min(t, in.next_time);
  }
  return t;
}

template <int D>
bool box_beside(const Vec<D>& lo, const Vec<D>& hi, const Vec<D>& grid_lo, const Vec<D>& grid_hi,
                const PeriodicCell<D>& cell) {
  for (int k = 0; k < D; ++k) {
    if (!cell.periodic[k] && (hi[k] <= grid_lo[k] || lo[k] >= grid_hi[k])) return true;
  }
  return false;
}

template double inlet_grain_mass<2>(const Inlet<2>&, const Simulation<2>&, double);
template double inlet_grain_mass<3>(const Inlet<3>&, const Simulation<3>&, double);
template InsertionResult insert_due<2>(Inlet<2>&, Simulation<2>&);
template InsertionResult insert_due<3>(Inlet<3>&, Simulation<3>&);
template void insert_all_due<2>(std::vector<Inlet<2>>&, Simulation<2>&);
template void insert_all_due<3>(std::vector<Inlet<3>>&, Simulation<3>&);
template double next_insertion_time<2>(const std::vector<Inlet<2>>&);
template double next_insertion_time<3>(const std::vector<Inlet<3>>&);
template bool box_beside<2>(const Vec<2>&, const Vec<2>&, const Vec<2>&, const Vec<2>&,
                            const PeriodicCell<2>&);
template bool box_beside<3>(const Vec<3>&, const Vec<3>&, const Vec<3>&, const Vec<3>&,
                            const PeriodicCell<3>&);

}  // namespace darcydem
