// Benchmark: the cost the pore fluid adds to a DEM step, and the pressure
// solve against the number of cells (issue 3).
//
//   BM_DemStep/N/threads            DEM alone on the benchmark packing (packing.hpp)
//   BM_CoupledStep/cells/solver/threads
//                                   the same packing (10^5 spheres) with a pore
//                                   fluid updated every DEM step (fluid step,
//                                   overlaps, solve, forces); solver 0 = Cholesky,
//                                   1 = CG with Jacobi, 2 = CG with multigrid
//   BM_CoupledInterval/cells/M/threads
//                                   the same with CG (Jacobi) and a fluid step
//                                   every M DEM steps (`fluid.steps_per_update`;
//                                   the grains' fluid forces still every step);
//                                   times are per DEM step, solver_iterations
//                                   per fluid step
//   BM_CoupledGraded/cells/threads  BM_CoupledStep with CG (Jacobi) on the same
//                                   grid graded along z (ratio 2)
//   BM_CoupledHeld/cells/M/threads  the same with the grains' fluid forces held
//                                   between fluid steps (`fluid.hold_forces`):
//                                   computed at the first DEM step after each
//                                   fluid step only
//   BM_PressureSolve/cells/solver   one fluid update alone (no DEM) on the packing
//                                   compacted uniformly, solver as above; solve_ms
//                                   is the linear solve's part
//   BM_Overlaps/cells               the exact grain/cell overlaps alone (solid
//                                   volumes, their velocities, face sections)
//   BM_GrainForces/cells/threads    the fluid's force on every grain alone
//                                   (PoreFluid::particle_forces, Ergun drag)
//   BM_OverlapsGraded/cells, BM_GrainForcesGraded/cells/threads
//                                   the same two on the grid graded along z
//   BM_GrainForcesOverlaps/cells/threads
//                                   BM_GrainForces with drag_cells = overlaps
//
// The grid covers the packing's base and is as tall as needed for the cell
// count (fluid above the bed), with cells at least one grain wide.
// The time per iteration is the time per step (or per update, per force
// evaluation); counters: fluid_update_ms (the update's part of a coupled
// step) and its parts (overlaps_ms, properties_ms, assembly_ms, solve_ms,
// fields_ms: FluidUpdateTimes), grain_forces_ms (the fluid's forces on the
// grains within the step), dem_part_ms (the rest of the step) and
// fluid_adds_percent = (grain forces + update) / DEM part, all measured in
// the same run; solver_iterations, particle_steps_per_second, ns_per_grain (in
// nanoseconds; the console prints it with a unit of seconds). JSON with
//   bench_coupled_step --benchmark_out=bench/results/coupled_step.json
#include <benchmark/benchmark.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"
#include "packing.hpp"

namespace {

using darcydem::PoreFluid;
using darcydem::Simulation;
using darcydem::Vec;
using Clock = std::chrono::steady_clock;

constexpr std::int64_t kGrains = 100'000;

/// A grid of about `cells` cells over the packing's base, at least 1 mm wide.
void shape_grid(PoreFluid<3>& f, const Simulation<3>& sim, std::int64_t cells) {
  Vec<3> lo = Vec<3>::Constant(1e300);
  Vec<3> hi = Vec<3>::Constant(-1e300);
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    lo = lo.cwiseMin(sim.particles.position[i] - Vec<3>::Constant(sim.particles.radius[i]));
    hi = hi.cwiseMax(sim.particles.position[i] + Vec<3>::Constant(sim.particles.radius[i]));
  }
  const Vec<3> size = hi - lo;
  // Cubic-ish cells of side h with nx ny nz ~ cells over the packing; if h
  // would fall below a grain diameter, keep h = 1 mm and extend the grid
  // upwards (fluid above the bed).
  double h = std::cbrt(size.prod() / static_cast<double>(cells));
  h = std::max(h, 1e-3);
  for (int k = 0; k < 2; ++k) f.grid.cells[k] = std::max(1, static_cast<int>(size[k] / h));
  f.grid.cells[2] =
      std::max(1, static_cast<int>(static_cast<double>(cells) / (f.grid.cells[0] * f.grid.cells[1])));
  for (int k = 0; k < 2; ++k) f.grid.spacing[k] = size[k] / f.grid.cells[k];
  f.grid.spacing[2] = std::max(1e-3, size[2] / f.grid.cells[2]);
  f.grid.origin = lo;
}

/// With `graded`, the same grid's layers along z graded, the top one
/// twice as tall as the bottom one (ratio 2), over the same height.
std::unique_ptr<PoreFluid<3>> make_fluid(const Simulation<3>& sim, std::int64_t cells, int solver,
                                         bool graded = false) {
  auto f = std::make_unique<PoreFluid<3>>(
      solver == 0 ? darcydem::PressureSolverKind::cholesky : darcydem::PressureSolverKind::cg, 1e-8,
      solver == 2 ? darcydem::CgPreconditioner::multigrid : darcydem::CgPreconditioner::jacobi);
  shape_grid(*f, sim, cells);
  if (graded) {
    const double bottom = f->grid.origin.z();
    f->grid.set_faces(2, darcydem::graded_faces(bottom, bottom + f->grid.cells[2] * f->grid.spacing[2],
                                                f->grid.cells[2], 2.0));
  }
  f->fluid = {1000.0, 1e-3, 1e5};
  f->drag = darcydem::DragLaw::ergun;
  f->permeability.model = darcydem::PermeabilityModel::kozeny_carman;
  f->permeability.diameter = 1e-3;
  f->sides[5] = {darcydem::FluidBoundaryType::drained, darcydem::TimeSeries::constant(0.0)};
  f->sides[4] = {darcydem::FluidBoundaryType::flux, darcydem::TimeSeries::constant(1e-4)};
  f->initialize(sim.particles);
  return f;
}

void BM_DemStep(benchmark::State& state) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  auto sim = bench::make_packing(state.range(0));
  for (auto _ : state) sim.step();
  state.counters["particle_steps_per_second"] =
      benchmark::Counter(static_cast<double>(sim.particles.size()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

// The coupled step, with a fluid step every `interval` DEM steps (the
// scene's `fluid.steps_per_update`); the figures are per DEM step.
void run_coupled(benchmark::State& state, std::int64_t cells, int solver, int threads, int interval,
                 bool hold = false, bool graded = false) {
  omp_set_num_threads(threads);
  auto sim = bench::make_packing(kGrains);
  auto fluid = make_fluid(sim, cells, solver, graded);
  fluid->steps_per_update = interval;
  fluid->hold_forces = hold;
  sim.force_field = fluid.get();
  sim.prepare();
  double fluid_seconds = 0.0;
  double step_seconds = 0.0;
  const double forces_before = fluid->force_time();
  darcydem::FluidUpdateTimes parts;
  long iterations = 0;
  long fluid_steps = 0;
  for (auto _ : state) {
    const auto t0 = Clock::now();
    sim.step();
    const auto t1 = Clock::now();
    step_seconds += std::chrono::duration<double>(t1 - t0).count();
    if (sim.steps % static_cast<std::uint64_t>(interval) != 0) continue;
    fluid->update(sim.particles, interval * sim.time_step, sim.time);
    fluid_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
    iterations += fluid->last_solve().iterations;
    ++fluid_steps;
    const auto& t = fluid->last_times();
    parts.overlaps += t.overlaps;
    parts.properties += t.properties;
    parts.assembly += t.assembly;
    parts.solve += t.solve;
    parts.fields += t.fields;
  }
  const double force_seconds = fluid->force_time() - forces_before;
  const double per_step_ms = 1e3 / static_cast<double>(state.iterations());
  // The fluid's share measured within the run itself (robust to the
  // machine's drift between runs): the DEM's part of the step is the step
  // without the grains' fluid forces.
  const double dem_seconds = step_seconds - force_seconds;
  state.counters["dem_part_ms"] = dem_seconds * per_step_ms;
  state.counters["grain_forces_ms"] = force_seconds * per_step_ms;
  state.counters["fluid_adds_percent"] = 100.0 * (force_seconds + fluid_seconds) / dem_seconds;
  state.counters["overlaps_ms"] = parts.overlaps * per_step_ms;
  state.counters["properties_ms"] = parts.properties * per_step_ms;
  state.counters["assembly_ms"] = parts.assembly * per_step_ms;
  state.counters["solve_ms"] = parts.solve * per_step_ms;
  state.counters["fields_ms"] = parts.fields * per_step_ms;
  state.counters["cells"] = static_cast<double>(fluid->grid.size());
  state.counters["fluid_update_ms"] = 1e3 * fluid_seconds / static_cast<double>(state.iterations());
  state.counters["solver_iterations"] =
      static_cast<double>(iterations) / static_cast<double>(std::max(fluid_steps, 1L));
  state.counters["particle_steps_per_second"] =
      benchmark::Counter(static_cast<double>(sim.particles.size()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate);
}

void BM_CoupledStep(benchmark::State& state) {
  run_coupled(state, state.range(0), static_cast<int>(state.range(1)), static_cast<int>(state.range(2)), 1);
}

// The coupled step on the same grid graded along z (make_fluid): what a
// graded axis costs (a search of its faces per grain, per-face geometry).
void BM_CoupledGraded(benchmark::State& state) {
  run_coupled(state, state.range(0), 1, static_cast<int>(state.range(1)), 1, false, true);
}

void BM_CoupledInterval(benchmark::State& state) {
  run_coupled(state, state.range(0), 1, static_cast<int>(state.range(2)), static_cast<int>(state.range(1)));
}

void BM_CoupledHeld(benchmark::State& state) {
  run_coupled(state, state.range(0), 1, static_cast<int>(state.range(2)), static_cast<int>(state.range(1)),
              true);
}

void BM_PressureSolve(benchmark::State& state) {
  omp_set_num_threads(1);
  // A packing compacted uniformly towards its floor, by 1e-7 of its height
  // per step of 1e-6 s (no DEM: only the fluid update runs), so that every
  // cell has a Biot source, as in consolidation. The time per iteration is
  // the whole update; solve_ms is the linear solve's part.
  auto sim = bench::make_packing(kGrains, 0);
  auto fluid = make_fluid(sim, state.range(0), static_cast<int>(state.range(1)));
  const double floor = fluid->grid.origin.z();
  double t = 0.0;
  double solve = 0.0;
  long iterations = 0;
  for (auto _ : state) {
    for (auto& x : sim.particles.position) x.z() = floor + (x.z() - floor) * (1.0 - 1e-7);
    t += 1e-6;
    fluid->update(sim.particles, 1e-6, t);
    solve += fluid->last_times().solve;
    iterations += fluid->last_solve().iterations;
  }
  const auto steps = static_cast<double>(state.iterations());
  state.counters["cells"] = static_cast<double>(fluid->grid.size());
  state.counters["solve_ms"] = 1e3 * solve / steps;
  state.counters["solver_iterations"] = static_cast<double>(iterations) / steps;
}

void overlaps(benchmark::State& state, bool graded) {
  omp_set_num_threads(1);
  static auto sim = bench::make_packing(kGrains, 0);
  auto fluid = make_fluid(sim, state.range(0), 1, graded);
  const auto& grid = fluid->grid;
  const auto& p = sim.particles;
  std::vector<double> solid(grid.size());
  std::vector<Vec<3>> flux(grid.size());
  std::array<std::vector<double>, 3> face;
  for (auto _ : state) {
    std::fill(solid.begin(), solid.end(), 0.0);
    std::fill(flux.begin(), flux.end(), Vec<3>::Zero());
    for (int k = 0; k < 3; ++k) face[k].assign(grid.face_count(k), 0.0);
    fluid->for_each_overlap(
        p,
        [&](std::size_t c, std::size_t i, double v) {
          solid[c] += v;
          flux[c] += v * p.velocity[i];
        },
        [&](int k, std::size_t f, std::size_t i, double a) { face[k][f] += a * p.velocity[i][k]; }, true);
    benchmark::DoNotOptimize(solid.data());
  }
  state.counters["ns_per_grain"] =
      benchmark::Counter(1e-9 * static_cast<double>(p.size()) * static_cast<double>(state.iterations()),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_Overlaps(benchmark::State& state) { overlaps(state, false); }
void BM_OverlapsGraded(benchmark::State& state) { overlaps(state, true); }

void grain_forces(benchmark::State& state, bool graded, bool overlaps = false) {
  omp_set_num_threads(static_cast<int>(state.range(1)));
  static auto sim = bench::make_packing(kGrains, 0);
  auto fluid = make_fluid(sim, state.range(0), 1, graded);
  if (overlaps) fluid->drag_cells = darcydem::DragCells::overlaps;
  // A flow through the bed, so that gradients and drag are not zero.
  fluid->update(sim.particles, 1e-3, 1e-3);
  std::vector<Vec<3>> force(sim.particles.size());
  for (auto _ : state) {
    fluid->particle_forces(sim.particles, sim.gravity, force);
    benchmark::DoNotOptimize(force.data());
  }
  state.counters["ns_per_grain"] = benchmark::Counter(
      1e-9 * static_cast<double>(sim.particles.size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

void BM_GrainForces(benchmark::State& state) { grain_forces(state, false); }
void BM_GrainForcesGraded(benchmark::State& state) { grain_forces(state, true); }
void BM_GrainForcesOverlaps(benchmark::State& state) { grain_forces(state, false, true); }

BENCHMARK(BM_DemStep)
    ->Args({kGrains, 1})
    ->Args({kGrains, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CoupledStep)
    ->ArgsProduct({{1'000, 10'000, 100'000}, {0, 1, 2}, {1}})
    ->Args({10'000, 1, 2})
    ->Args({100'000, 1, 2})
    ->Args({100'000, 2, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CoupledGraded)->Args({10'000, 1})->Unit(benchmark::kMillisecond)->MinTime(2.0)->UseRealTime();
BENCHMARK(BM_CoupledInterval)
    ->ArgsProduct({{10'000}, {2, 5, 10}, {1}})
    ->Args({10'000, 5, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_CoupledHeld)
    ->ArgsProduct({{10'000}, {2, 5}, {1}})
    ->Args({10'000, 2, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0)
    ->UseRealTime();
BENCHMARK(BM_PressureSolve)
    ->ArgsProduct({{1'000, 10'000, 30'000, 100'000}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK(BM_Overlaps)->Arg(10'000)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_GrainForces)
    ->Args({10'000, 1})
    ->Args({10'000, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK(BM_OverlapsGraded)->Arg(10'000)->Unit(benchmark::kMillisecond)->MinTime(1.0)->UseRealTime();
BENCHMARK(BM_GrainForcesGraded)
    ->Args({10'000, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();
BENCHMARK(BM_GrainForcesOverlaps)
    ->Args({10'000, 1})
    ->Args({10'000, 2})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
