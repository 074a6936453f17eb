#pragma once
// The benchmark packing shared by the DEM and coupled benchmarks: a
// face-centred cubic stack of touching monodisperse spheres (d = 1 mm,
// 2650 kg/m^3, linear contacts k_n = 1000 N/m, friction 0.5, restitution
// 0.5) in a box under gravity, settled for 300 steps with local damping.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace bench {

using darcydem::Simulation;
using darcydem::Vec;

/// One material (d = 1 mm grains) with the benchmark's linear contacts.
inline Simulation<3> grain_simulation() {
  Simulation<3> sim;
  darcydem::Material grain{"grain", 2650.0, 0.0, 0.0};
  sim.materials.push_back(grain);
  darcydem::ContactSpec spec;
  spec.normal_stiffness = 1000.0;
  spec.friction = 0.5;
  spec.restitution = 0.5;
  sim.contact_table = darcydem::ContactTable(1);
  sim.contact_table.set(0, 0, darcydem::make_pair_parameters(grain, grain, spec));
  return sim;
}

/// A floor and four side walls around [0, side]^2, gravity, local damping
/// 0.7, dt = 0.2 x critical; prepares the simulation.
inline void close_box(Simulation<3>& sim, double side) {
  auto wall = [&](Vec<3> p, Vec<3> nrm) {
    darcydem::Wall<3> w;
    w.point = p;
    w.normal = nrm;
    sim.walls.push_back(w);
  };
  wall(Vec<3>(0, 0, 0), Vec<3>(0, 0, 1));
  wall(Vec<3>(0, 0, 0), Vec<3>(1, 0, 0));
  wall(Vec<3>(side, 0, 0), Vec<3>(-1, 0, 0));
  wall(Vec<3>(0, 0, 0), Vec<3>(0, 1, 0));
  wall(Vec<3>(0, side, 0), Vec<3>(0, -1, 0));
  sim.gravity = Vec<3>(0, 0, -9.81);
  sim.damping.local = 0.7;
  sim.time_step = 0.2 * sim.critical_time_step();
  sim.measure_contact_forces = false;  // no stop condition on the unbalanced force
  sim.prepare();
}

inline Simulation<3> make_packing(std::int64_t target, int settle_steps = 300) {
  Simulation<3> sim = grain_simulation();
  const double d = 1e-3;
  const double r = 0.5 * d;
  const double a = std::sqrt(2.0) * d;  // FCC cube edge for touching spheres
  // A square base of n x n cubic cells, as many layers as needed.
  const int n = std::max(2, static_cast<int>(std::cbrt(static_cast<double>(target) / 4.0 / 2.0)));
  const Vec<3> basis[4] = {Vec<3>(0, 0, 0), Vec<3>(0.5 * a, 0.5 * a, 0), Vec<3>(0.5 * a, 0, 0.5 * a),
                           Vec<3>(0, 0.5 * a, 0.5 * a)};
  for (int k = 0; static_cast<std::int64_t>(sim.particles.size()) < target; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        for (const auto& b : basis) {
          if (static_cast<std::int64_t>(sim.particles.size()) >= target) break;
          const Vec<3> x = Vec<3>(r + i * a, r + j * a, r + k * a) + b;
          sim.particles.add(x, r, 2650.0, 0, false);
        }
      }
    }
  }
  const double side = n * a + 0.5 * a;
  close_box(sim, side);
  for (int s = 0; s < settle_steps; ++s) sim.step();  // settle onto the contacts
  return sim;
}

/// Settling the dropped bed takes minutes (9 at 10^5 on 2 cores). With the
/// environment variable DARCYDEM_BENCH_CACHE set to a folder, the settled
/// positions and velocities are saved there and reused by later runs, which
/// then only rebuild the contacts' tangential histories (2000 steps). For
/// development: the figures in docs/PERFORMANCE.md come from full settles.
inline std::string settled_cache_path(std::int64_t target) {
  const char* dir = std::getenv("DARCYDEM_BENCH_CACHE");
  if (dir == nullptr || *dir == 0) return {};
  return std::string(dir) + "/dropped_" + std::to_string(target) + ".bin";
}

/// Writes the particles' positions, velocities and angular velocities.
inline void save_state(const Simulation<3>& sim, const std::string& path) {
  std::ofstream out(path, std::ios::binary);
  if (!out) {
    std::fprintf(stderr, "DARCYDEM_BENCH_CACHE: cannot write %s (does the folder exist?); not cached\n",
                 path.c_str());
    return;
  }
  const auto& p = sim.particles;
  const std::uint64_t n = p.size();
  out.write(reinterpret_cast<const char*>(&n), sizeof n);
  for (std::uint64_t i = 0; i < n; ++i) {
    out.write(reinterpret_cast<const char*>(p.position[i].data()), 3 * sizeof(double));
    out.write(reinterpret_cast<const char*>(p.velocity[i].data()), 3 * sizeof(double));
    out.write(reinterpret_cast<const char*>(p.angular_velocity[i].data()), 3 * sizeof(double));
  }
}

/// Reads what save_state wrote into particles of the same count; false if
/// there is no such file or it does not match.
inline bool load_state(Simulation<3>& sim, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;  // not cached yet
  std::uint64_t n = 0;
  if (!in.read(reinterpret_cast<char*>(&n), sizeof n) || n != sim.particles.size()) {
    std::fprintf(stderr, "DARCYDEM_BENCH_CACHE: %s holds another packing; settling anew\n", path.c_str());
    return false;
  }
  // Into copies first: a truncated file leaves the lattice as it was.
  auto position = sim.particles.position;
  auto velocity = sim.particles.velocity;
  auto angular_velocity = sim.particles.angular_velocity;
  for (std::uint64_t i = 0; i < n; ++i) {
    in.read(reinterpret_cast<char*>(position[i].data()), 3 * sizeof(double));
    in.read(reinterpret_cast<char*>(velocity[i].data()), 3 * sizeof(double));
    in.read(reinterpret_cast<char*>(angular_velocity[i].data()), 3 * sizeof(double));
  }
  if (!in) {
    std::fprintf(stderr, "DARCYDEM_BENCH_CACHE: %s is truncated; settling anew\n", path.c_str());
    return false;
  }
  sim.particles.position = std::move(position);
  sim.particles.velocity = std::move(velocity);
  sim.particles.angular_velocity = std::move(angular_velocity);
  return true;
}

/// The workload: the same spheres and contacts dropped from a loose
/// simple-cubic lattice (spacing 1.1 d, each centre jittered by up to
/// +-0.045 d so the columns buckle) into a box under gravity, and settled
/// with local damping 0.7 until the grains' mean speed is below 1 mm/s
/// (kinetic energy checked every 500 steps) or for at most 300 000 steps
/// (1.4 s). The box is wide and the lattice 10 layers deep (a square base of
/// sqrt(N/10) grains a side): a tall lattice takes over an hour of 2 cores
/// to collapse into a bed at N = 10^5, a shallow one minutes.
inline Simulation<3> make_dropped_packing(std::int64_t target) {
  Simulation<3> sim = grain_simulation();
  const double d = 1e-3;
  const double r = 0.5 * d;
  const double s = 1.1 * d;
  const int n = std::max(2, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(target) / 10.0))));
  std::uint64_t state = 12345;
  auto jitter = [&] {  // a small deterministic generator (splitmix64)
    state += 0x9E3779B97F4A7C15ULL;
    std::uint64_t z = state;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    z ^= z >> 31;
    return (static_cast<double>(z >> 11) * 0x1.0p-53 - 0.5) * 0.09 * d;
  };
  for (int k = 0; static_cast<std::int64_t>(sim.particles.size()) < target; ++k) {
    for (int j = 0; j < n && static_cast<std::int64_t>(sim.particles.size()) < target; ++j) {
      for (int i = 0; i < n && static_cast<std::int64_t>(sim.particles.size()) < target; ++i) {
        const Vec<3> x(0.5 * s + i * s + jitter(), 0.5 * s + j * s + jitter(), 0.5 * s + k * s + jitter());
        sim.particles.add(x, r, 2650.0, 0, false);
      }
    }
  }
  const double side = n * s;
  // A settled bed cached by an earlier run (see settled_cache_path).
  const std::string cache = settled_cache_path(target);
  if (!cache.empty() && load_state(sim, cache)) {
    close_box(sim, side);
    for (int k = 0; k < 2000; ++k) sim.step();  // the contacts' histories build up again
    return sim;
  }
  close_box(sim, side);
  const double m = 2650.0 * darcydem::particle_volume<3>(r);
  const double threshold = 0.5 * m * 1e-3 * 1e-3 * static_cast<double>(sim.particles.size());
  for (std::int64_t k = 1; k <= 300'000; ++k) {
    sim.step();
    if (k % 500 == 0 && sim.kinetic_energy() < threshold) break;
  }
  if (!cache.empty()) save_state(sim, cache);
  return sim;
}

}  // namespace bench
