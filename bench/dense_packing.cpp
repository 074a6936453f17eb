// Benchmark: DEM steps on a dense, settled 3D packing of monodisperse spheres
// (d = 1 mm, 2650 kg/m^3, linear contacts k_n = 1000 N/m, friction 0.5,
// restitution 0.5) in a box under gravity. The packing is a face-centred
// cubic stack of touching spheres (12 neighbours each, more than the ~6 of a
// random packing, so the contact work is on the heavy side), settled under
// gravity with local damping before timing.
//
// Counters: particle_steps_per_second, bytes_per_particle (arrays held by
// the simulation), peak_rss_bytes. Also the time to write and read a
// checkpoint of the stack (BM_Checkpoint), the stack cemented by
// contact bonds (BM_BondedPacking), with the energy budget tracked
// (BM_EnergyTracking), in a box of triangle meshes instead of planes
// (BM_MeshBox), paired into rigid dumbbells (BM_ClumpPacking), and in a
// periodic cell, fixed or deforming (BM_PeriodicCell). Write
// JSON with
//   bench_dense_packing --benchmark_out=bench/results/dense_packing.json
#include <benchmark/benchmark.h>
#include <omp.h>
#include <sys/resource.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include "darcydem/output/checkpoint_archive.hpp"
#include "packing.hpp"

namespace {

using bench::make_packing;
using darcydem::Simulation;
using darcydem::Vec;

/// Steps per timed iteration, run by Simulation::advance as a scene run does
/// between outputs (one sweep over the particles fewer per step than step()).
constexpr std::int64_t kStepsPerIteration = 10;

/// The counters both packings report.
void report(benchmark::State& state, const Simulation<3>& sim, int threads, std::size_t builds0) {
  const double particles = static_cast<double>(sim.particles.size());
  state.counters["particle_steps_per_second"] = benchmark::Counter(
      particles * static_cast<double>(kStepsPerIteration * state.iterations()), benchmark::Counter::kIsRate);
  state.counters["particles"] = particles;
  state.counters["threads"] = threads;
  state.counters["bytes_per_particle"] = static_cast<double>(sim.memory_bytes()) / particles;
  state.counters["cross_pair_share"] =
      static_cast<double>(sim.pair_list().cross_count()) / static_cast<double>(sim.pair_list().pair_count());
  state.counters["pairs_per_particle"] = static_cast<double>(sim.pair_list().pair_count()) / particles;
  state.counters["contacts_per_particle"] = static_cast<double>(sim.contact_count()) / particles;
  state.counters["list_builds"] = static_cast<double>(sim.list_builds() - builds0);
}

void BM_DensePacking(benchmark::State& state) {
  const auto n = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_packing(n);
  const auto builds0 = sim.list_builds();
  for (auto _ : state) {
    sim.advance(kStepsPerIteration);
  }
  report(state, sim, threads, builds0);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  state.counters["peak_rss_bytes"] = static_cast<double>(usage.ru_maxrss) * 1024.0;
}

// The FCC stack cemented: every pair within 0.1 r bonded (strengths far
// above its loads, so none breaks), the bonds carrying a moment or not
// (range(2) = 1: bending and twisting ratio 1). A scene with bonds goes
// through the pair-by-pair pass, not the batched one of BM_DensePacking.
void BM_BondedPacking(benchmark::State& state) {
  const auto n = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_packing(n);
  darcydem::ContactSpec spec;
  spec.normal_stiffness = 1000.0;
  spec.friction = 0.5;
  spec.restitution = 0.5;
  spec.bond_tensile_strength = 1.0;  // N: the stack's heaviest load is about 1e-3 N
  spec.bond_shear_strength = 1.0;
  if (state.range(2) != 0) {
    spec.bond_bending_stiffness_ratio = 1.0;
    spec.bond_bending_strength = 1.0;
    spec.bond_twisting_stiffness_ratio = 1.0;
    spec.bond_twisting_strength = 1.0;
  }
  sim.contact_table.set(0, 0, darcydem::make_pair_parameters(sim.materials[0], sim.materials[0], spec));
  sim.time_step = 0.2 * sim.critical_time_step();
  const double r = sim.particles.radius[0];
  state.counters["bonds_per_particle"] =
      static_cast<double>(sim.make_bonds(0.1 * r)) / static_cast<double>(sim.particles.size());
  const auto builds0 = sim.list_builds();
  for (auto _ : state) {
    sim.advance(kStepsPerIteration);
  }
  report(state, sim, threads, builds0);
  state.counters["broken_bonds"] = static_cast<double>(sim.broken_bonds);
}

// The workload: dropped from a loose lattice and settled (the
// settling is not timed; about 5 minutes at 10^5 on 2 cores, or read from
// DARCYDEM_BENCH_CACHE, see packing.hpp). The FCC stack below is the
// heavier dense case, also at 10^6.
void BM_DroppedPacking(benchmark::State& state) {
  const auto n = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  // Settle once per size on both cores (kept for the next thread count),
  // then time with `threads`.
  static std::map<std::int64_t, Simulation<3>> settled;
  omp_set_num_threads(2);
  if (settled.count(n) == 0) settled.emplace(n, bench::make_dropped_packing(n));
  auto sim = settled.at(n);
  omp_set_num_threads(threads);
  const auto builds0 = sim.list_builds();
  for (auto _ : state) sim.advance(kStepsPerIteration);
  report(state, sim, threads, builds0);
  state.counters["kinetic_energy_per_particle"] =
      sim.kinetic_energy() / static_cast<double>(sim.particles.size());
}

// A checkpoint of the FCC stack (what `run --resume` reads and an
// interrupted run writes): the simulation's whole state, particles, lists
// with contact histories and walls, written to a file (range(1) = 0) or
// read back from it (1). Counters: the file's bytes per particle and MB/s.
void BM_Checkpoint(benchmark::State& state) {
  const bool reading = state.range(1) == 1;
  omp_set_num_threads(2);
  auto sim = make_packing(state.range(0));
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("darcydem_bench_checkpoint_" + std::to_string(getpid()) + ".bin"))
                               .string();
  auto write = [&] {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    darcydem::CheckpointWriter ar(out, path);
    ar(sim);
  };
  write();
  const auto bytes = static_cast<double>(std::filesystem::file_size(path));
  for (auto _ : state) {
    if (reading) {
      std::ifstream in(path, std::ios::binary);
      darcydem::CheckpointReader ar(in, path);
      ar(sim);
    } else {
      write();
    }
  }
  std::filesystem::remove(path);
  state.counters["bytes_per_particle"] = bytes / static_cast<double>(sim.particles.size());
  state.counters["megabytes"] = bytes / 1e6;
  state.counters["megabytes_per_second"] =
      benchmark::Counter(bytes / 1e6 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

// The FCC stack with the energy budget tracked (range(2) = 1) or not (0),
// back to back: what Simulation::track_energy (a budget probe) costs a
// step. The tracked half kicks split each load, in parallel over the groups.
void BM_EnergyTracking(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_packing(state.range(0));
  sim.track_energy = state.range(2) == 1;
  const auto builds0 = sim.list_builds();
  for (auto _ : state) sim.advance(kStepsPerIteration);
  report(state, sim, threads, builds0);
}

/// A mesh wall: the rectangle origin + s u + t v (s, t in [0, 1]) in n_u x
/// n_v squares, each cut in two; its frame at the origin of the world.
darcydem::Wall<3> rectangle_mesh(const Vec<3>& origin, const Vec<3>& u, const Vec<3>& v, int n_u, int n_v) {
  auto mesh = std::make_shared<darcydem::TriangleMesh>();
  for (int j = 0; j <= n_v; ++j)
    for (int i = 0; i <= n_u; ++i)
      mesh->vertex.push_back(origin + (double(i) / n_u) * u + (double(j) / n_v) * v);
  auto id = [n_u](int i, int j) { return static_cast<std::uint32_t>(j * (n_u + 1) + i); };
  for (int j = 0; j < n_v; ++j)
    for (int i = 0; i < n_u; ++i) {
      mesh->triangle.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      mesh->triangle.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  if (const std::string why = mesh->finish(); !why.empty()) throw std::logic_error(why);
  darcydem::Wall<3> w;
  w.shape = darcydem::WallShape::mesh;
  w.mesh = std::move(mesh);
  return w;
}

// The FCC stack in its box of five planes (range(2) = 0), or of five flat
// meshes on the same planes (1) in squares of 2 mm (two grain diameters;
// 2 x 65^2 facets on the floor), back to back: what a mesh wall's contacts
// cost against a plane's. The grains against the walls (about 10 % of them)
// each touch a few facets' candidates, and the nearest-first rule sorts them.
void BM_MeshBox(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_packing(state.range(0));
  if (state.range(2) == 1) {
    double side = 0.0;
    double top = 0.0;
    for (const auto& w : sim.walls)
      if (w.normal[0] < 0.0) side = w.point[0];
    for (const auto& x : sim.particles.position) top = std::max(top, x[2]);
    top += 2e-3;
    const int n = static_cast<int>(std::ceil(side / 2e-3));
    const int h = static_cast<int>(std::ceil(top / 2e-3));
    sim.walls.clear();
    sim.walls.push_back(rectangle_mesh(Vec<3>(0, 0, 0), Vec<3>(side, 0, 0), Vec<3>(0, side, 0), n, n));
    sim.walls.push_back(rectangle_mesh(Vec<3>(0, 0, 0), Vec<3>(0, side, 0), Vec<3>(0, 0, top), n, h));
    sim.walls.push_back(rectangle_mesh(Vec<3>(side, 0, 0), Vec<3>(0, side, 0), Vec<3>(0, 0, top), n, h));
    sim.walls.push_back(rectangle_mesh(Vec<3>(0, 0, 0), Vec<3>(side, 0, 0), Vec<3>(0, 0, top), n, h));
    sim.walls.push_back(rectangle_mesh(Vec<3>(0, side, 0), Vec<3>(side, 0, 0), Vec<3>(0, 0, top), n, h));
    sim.prepare();
    std::size_t facets = 0;
    for (const auto& w : sim.walls) facets += w.mesh->triangle.size();
    state.counters["facets"] = static_cast<double>(facets);
  }
  const auto builds0 = sim.list_builds();
  for (auto _ : state) sim.advance(kStepsPerIteration);
  report(state, sim, threads, builds0);
}

// The FCC stack with its spheres paired into rigid dumbbells (range(2) = 1:
// in each cubic cell, the corner sphere with the face centre beside it in
// the base, and the two other face centres, each pair touching), or the
// same spheres loose (0), settled alike, back to back: what the clumps'
// serial pass (gather, kicks, drift, placing the members) costs a step.
darcydem::Simulation<3> make_clump_packing(std::int64_t target, bool clumps) {
  using darcydem::ClumpShape;
  Simulation<3> sim = bench::grain_simulation();
  const double d = 1e-3;
  const double r = 0.5 * d;
  const double a = std::sqrt(2.0) * d;
  const int n = std::max(2, static_cast<int>(std::cbrt(static_cast<double>(target) / 4.0 / 2.0)));
  const Vec<3> basis[4] = {Vec<3>(0, 0, 0), Vec<3>(0.5 * a, 0.5 * a, 0), Vec<3>(0.5 * a, 0, 0.5 * a),
                           Vec<3>(0, 0.5 * a, 0.5 * a)};
  const auto low = darcydem::make_clump_shape<3>({basis[0], basis[1]}, {r, r});
  const auto high = darcydem::make_clump_shape<3>({basis[2], basis[3]}, {r, r});
  const auto upright = ClumpShape<3>::identity_orientation();
  for (int k = 0; static_cast<std::int64_t>(sim.particles.size()) < target; ++k) {
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i) {
        if (static_cast<std::int64_t>(sim.particles.size()) + 4 > target) break;
        const Vec<3> corner(r + i * a, r + j * a, r + k * a);
        if (clumps) {
          sim.clumps.add(sim.particles, low, d, corner + 0.5 * (basis[0] + basis[1]), upright, 2650.0, 0,
                         false, Vec<3>::Zero());
          sim.clumps.add(sim.particles, high, d, corner + 0.5 * (basis[2] + basis[3]), upright, 2650.0, 0,
                         false, Vec<3>::Zero());
        } else {
          for (const auto& b : basis) sim.particles.add(corner + b, r, 2650.0, 0, false);
        }
      }
    }
  }
  bench::close_box(sim, n * a + 0.5 * a);
  for (int s = 0; s < 300; ++s) sim.step();
  return sim;
}

void BM_ClumpPacking(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_clump_packing(state.range(0), state.range(2) == 1);
  state.counters["clumps"] = static_cast<double>(sim.clumps.size());
  const auto builds0 = sim.list_builds();
  for (auto _ : state) sim.advance(kStepsPerIteration);
  report(state, sim, threads, builds0);
}

/// The FCC stack in a cell periodic along x, y and z (m^3 cubic cells of
/// 4 spheres), no walls or gravity, the spheres pressed together by a
/// thousandth of a diameter (every sphere's 12 contacts loaded).
Simulation<3> make_periodic_packing(std::int64_t target) {
  Simulation<3> sim = bench::grain_simulation();
  const double d = 1e-3;
  const double a = std::sqrt(2.0) * d * 0.999;  // FCC cube edge, 0.1 % closer than touching
  const int m = std::max(3, static_cast<int>(std::lround(std::cbrt(static_cast<double>(target) / 4.0))));
  const Vec<3> basis[4] = {Vec<3>(0, 0, 0), Vec<3>(0.5 * a, 0.5 * a, 0), Vec<3>(0.5 * a, 0, 0.5 * a),
                           Vec<3>(0, 0.5 * a, 0.5 * a)};
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        for (const auto& b : basis)
          sim.particles.add(Vec<3>(0.25 * a + i * a, 0.25 * a + j * a, 0.25 * a + k * a) + b, 0.5 * d, 2650.0,
                            0, false);
  for (int k = 0; k < 3; ++k) sim.periodic.set_axis(k, 0.0, m * a);
  sim.damping.local = 0.7;
  sim.time_step = 0.2 * sim.critical_time_step();
  sim.measure_contact_forces = false;
  sim.prepare();
  return sim;
}

// The periodic stack with its cell fixed (range(2) = 0: the fused step),
// strained at -0.01 /s along each axis (1: the deforming cell's step, the
// field in every drift and contact), or held by the servo at 1 kPa along
// each axis (2: also the pairs' moments summed in the force pass and the
// cell's stress added up every step): what a deforming cell costs a step.
void BM_PeriodicCell(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(1));
  omp_set_num_threads(threads);
  auto sim = make_periodic_packing(state.range(0));
  if (state.range(2) == 1) sim.cell_motion.strain_rate = Vec<3>::Constant(-0.01);
  if (state.range(2) == 2) {
    sim.cell_motion.by_stress = {true, true, true};
    sim.cell_motion.target_stress = Vec<3>::Constant(1e3);
    sim.cell_motion.gain = 1e-6;
    sim.cell_motion.max_strain_rate = 0.01;
  }
  const auto builds0 = sim.list_builds();
  for (auto _ : state) sim.advance(kStepsPerIteration);
  report(state, sim, threads, builds0);
}

BENCHMARK(BM_PeriodicCell)
    ->ArgsProduct({{100'000}, {1, 2}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_ClumpPacking)
    ->ArgsProduct({{100'000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_MeshBox)
    ->ArgsProduct({{100'000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_EnergyTracking)
    ->ArgsProduct({{100'000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_Checkpoint)
    ->ArgsProduct({{100'000}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_DroppedPacking)
    ->ArgsProduct({{10'000, 100'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_BondedPacking)
    ->ArgsProduct({{100'000}, {1, 2}, {0, 1}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

BENCHMARK(BM_DensePacking)
    ->ArgsProduct({{10'000, 100'000, 1'000'000}, {1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
