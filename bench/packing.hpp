#pragma once
// The benchmark packing shared by the DEM and coupled benchmarks: a
// face-centred cubic stack of touching monodisperse spheres (d = 1 mm,
// 2650 kg/m^3, linear contacts k_n = 1000 N/m, friction 0.5, restitution
// 0.5) in a box under gravity, settled for 300 steps with local damping.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace bench {

using darcydem::Simulation;
using darcydem::Vec;

inline Simulation<3> make_packing(std::int64_t target, int settle_steps = 300) {
  Simulation<3> sim;
  darcydem::Material grain{"grain", 2650.0, 0.0, 0.0};
  sim.materials.push_back(grain);
  darcydem::ContactSpec spec;
  spec.normal_stiffness = 1000.0;
  spec.friction = 0.5;
  spec.restitution = 0.5;
  sim.contact_table = darcydem::ContactTable(1);
  sim.contact_table.set(0, 0, darcydem::make_pair_parameters(grain, grain, spec));
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
  sim.prepare();
  for (int s = 0; s < settle_steps; ++s) sim.step();  // settle onto the contacts
  return sim;
}

}  // namespace bench
