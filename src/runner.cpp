#include "darcydem/simulation/runner.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <ostream>
#include <stdexcept>

#include <fmt/format.h>

#include "darcydem/core/quoted.hpp"
#include "darcydem/generation/generators.hpp"
#include "darcydem/output/checkpoint_archive.hpp"
#include "darcydem/output/probes.hpp"
#include "darcydem/output/vtk.hpp"
#include "darcydem/particles/grading.hpp"
#include "darcydem/simulation/run_checkpoint.hpp"
#include "darcydem/version.hpp"

namespace darcydem {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string json_string(const std::string& s) { return quoted(s); }

/// JSON strings, comma-separated (an array's inside).
std::string json_strings(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + json_string(s);
  return out;
}

/// Which of the stage's stop conditions holds now ("" if none).
template <int D>
std::string stop_condition_met(const Scene<D>& scene, const Stage<D>& stage) {
  const Simulation<D>& sim = scene.simulation;
  if (stage.kinetic_energy_below) {
    const double e = sim.kinetic_energy();
    if (e < *stage.kinetic_energy_below)
      return fmt::format("kinetic energy {:.6g} J below {:.6g} J", e, *stage.kinetic_energy_below);
  }
  if (stage.unbalanced_force_below) {
    const double r = sim.unbalanced_force_ratio();
    if (r < *stage.unbalanced_force_below)
      return fmt::format("unbalanced force ratio {:.6g} below {:.6g}", r, *stage.unbalanced_force_below);
  }
  if (stage.stop_probe) {
    const ProbeSpec& probe = scene.output.probes[*stage.stop_probe];
    const double v = evaluate_probe(probe, sim, scene.fluid.get(), &scene.inlets);
    if (stage.probe_above && v > *stage.probe_above)
      return fmt::format("probe {} = {:.10g} above {:.10g}", probe.name, v, *stage.probe_above);
    if (stage.probe_below && v < *stage.probe_below)
      return fmt::format("probe {} = {:.10g} below {:.10g}", probe.name, v, *stage.probe_below);
  }
  return {};
}

class Progress {
 public:
  explicit Progress(const RunOptions& o) : opt_(o), start_(Clock::now()), last_(start_) {}
  void update(const std::string& stage, double t, double t_end, std::uint64_t steps, bool force = false) {
    if (opt_.log == nullptr) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    const double every = opt_.terminal ? 0.2 : opt_.progress_every;
    if (!force && since < every) return;
    const double elapsed = std::chrono::duration<double>(now - last_).count();
    const double rate = elapsed > 0 ? static_cast<double>(steps - last_steps_) / elapsed : 0.0;
    const double sim_rate = elapsed > 0 ? (t - last_t_) / elapsed : 0.0;
    // Not below zero: the last step may end a hair past t_end.
    const double eta = sim_rate > 0 ? std::max(0.0, (t_end - t) / sim_rate) : 0.0;
    last_ = now;
    last_steps_ = steps;
    last_t_ = t;
    if (opt_.terminal) {
      const int width = 30;
      const double frac = t_end > 0 ? std::min(1.0, t / t_end) : 1.0;
      const int filled = static_cast<int>(frac * width);
      *opt_.log << fmt::format("\r{:<12} [{}{}] t = {:.4g} s  {:.3g} steps/s  ETA {:.0f} s   ", stage,
                               std::string(filled, '#'), std::string(width - filled, '.'), t, rate, eta)
                << std::flush;
    } else {
      *opt_.log << fmt::format("stage {}: t = {:.6g} s of {:.6g} s, {} steps, {:.3g} steps/s, ETA {:.0f} s\n",
                               stage, t, t_end, steps, rate, eta)
                << std::flush;
    }
  }
  void end_line() {
    if (opt_.log != nullptr && opt_.terminal) *opt_.log << "\n";
  }

 private:
  const RunOptions& opt_;
  Clock::time_point start_;
  Clock::time_point last_;
  std::uint64_t last_steps_ = 0;
  double last_t_ = 0.0;
};

/// The end state as a packing that a new scene can start from (a bed
/// settled once, then used by several runs): OUT/particles_final.csv. The
/// scene check refuses overlaps above initial_overlap_tolerance (a fraction
/// of the smaller radius), so the header says what this packing needs.
template <int D>
void write_final_particles(const fs::path& out, const Scene<D>& scene, bool interrupted) {
  const auto& sim = scene.simulation;
  const std::string path = (out / "particles_final.csv").string();
  if (sim.particles.size() == 0) {  // all removed by a [domain], or an inlet that has added none yet
    write_packing_csv<D>(
        path, sim.particles,
        fmt::format("darcydem {}: no particles in {} at t = {:.17g} s (step {}, {})", version_string,
                    scene.file, sim.time, sim.steps, interrupted ? "interrupted" : "completed"));
    return;
  }
  const double r_min = *std::min_element(sim.particles.radius.begin(), sim.particles.radius.end());
  const double overlap = sim.max_overlap();
  // A clump's members where the clump puts them, about its centre of mass
  // in the period (the list builds put members back into it one by one):
  // read back, each clump stands whole.
  ParticleData<D> particles = sim.particles;
  const auto& clumps = sim.clumps;
  for (std::size_t c = 0; c < clumps.size(); ++c) {
    const Vec<D> x = sim.periodic.any() ? sim.periodic.wrap(clumps.position[c]) : clumps.position[c];
    const auto turn = rotation_matrix(clumps.orientation[c]);
    for (std::uint32_t k = clumps.first[c]; k < clumps.first[c + 1]; ++k)
      particles.position[clumps.member_index[k]] = x + turn * clumps.offset[k];
  }
  write_packing_csv<D>(
      path, particles,
      fmt::format(
          "darcydem {}: the particles of {} at t = {:.17g} s (step {}, {})\n"
          "a scene starts from them with [[particles]] generator = \"csv\"; centres and radii{} only (no "
          "velocities, materials or contact histories)\n"
          "largest overlap {:.4g} m = {:.4g} of the smallest radius: the scene needs [simulation] "
          "initial_overlap_tolerance >= {:.2g} (walls where they were at the start)",
          version_string, scene.file, sim.time, sim.steps, interrupted ? "interrupted" : "completed",
          clumps.empty() ? "" : ", and each particle's clump (-1: none)", overlap, overlap / r_min,
          std::ceil(overlap / r_min * 1.05 * 1000.0) / 1000.0),
      clumps.empty() ? nullptr : &clumps.clump_of);
}

/// The energy budget since tracking began, for the run log at a stage's end.
template <int D>
std::string describe_energy(const Simulation<D>& sim) {
  const auto& e = sim.energy;
  const char* unit = D == 2 ? "J/m" : "J";
  // Grains added or removed bring or take kinetic energy: said when a
  // scene can do either.
  const std::string carried =
      sim.has_domain || sim.inserted_count > 0
          ? fmt::format("; kinetic energy brought in by inlets {:.6g}, taken out of the domain {:.6g}",
                        e.inserted_kinetic, e.removed_kinetic)
          : std::string();
  return fmt::format(
      "energy budget so far ({}): done on the grains by gravity {:.6g}, the fluid {:.6g}, external forces "
      "{:.6g}, moving boundaries {:.6g}; taken by damping {:.6g}, the contacts {:.6g}{}; kinetic {:.6g} and "
      "elastic {:.6g} now; unaccounted {:.3g}\n",
      unit, e.gravity_work, e.field_work, e.external_work, e.boundary_work, e.damping_dissipation(),
      sim.contact_dissipation(), carried, sim.kinetic_energy(), sim.elastic_energy(),
      sim.unaccounted_energy());
}

/// run.json: what ran, how long, how it ended, the fluid's balance and the analysis' verdict.
template <int D>
void write_run_json(const fs::path& path, const Scene<D>& scene, const RunSummary& summary,
                    const RunPosition& pos, const std::string& failure) {
  const auto& sim = scene.simulation;
  const PoreFluid<D>* fluid = scene.fluid.get();
  const double dt = sim.time_step;
  const std::uint64_t fluid_iterations = pos.fluid_iterations;
  const double fluid_residual = pos.fluid_residual;
  std::ofstream json(path);
  const std::string stages = json_strings(summary.stages_completed);
  json << "{\n"
       << fmt::format("  \"version\": {},\n", json_string(version_string))
       << fmt::format("  \"scene\": {},\n", json_string(scene.file))
       << fmt::format("  \"scene_hash\": \"fnv1a64:{}\",\n", scene.text_hash)
       << fmt::format("  \"overrides\": [{}],\n", json_strings(scene.overrides))
       << fmt::format("  \"dimension\": {},\n", D)
       << fmt::format("  \"particles\": {},\n", sim.particles.size())
       << fmt::format("  \"time_step\": {:.17g},\n", dt) << fmt::format("  \"steps\": {},\n", summary.steps)
       << fmt::format("  \"simulated_time\": {:.17g},\n", summary.simulated_time)
       << fmt::format("  \"wall_time\": {:.6f},\n", summary.wall_time)
       << fmt::format("  \"threads\": {},\n", omp_get_max_threads())
       << fmt::format("  \"resumes\": {},\n", pos.resumes);
  if (summary.checkpoint_written) json << "  \"checkpoint\": \"checkpoint.bin\",\n";
  if (sim.has_domain) {
    json << fmt::format("  \"removed\": {{\"particles\": {}, \"mass\": {:.17g}, \"volume\": {:.17g}}},\n",
                        sim.removed_count, sim.removed_mass, sim.removed_volume);
  }
  if (sim.contact_table.any_bondable()) {
    json << fmt::format("  \"bonds\": {{\"intact\": {}, \"broken\": {}}},\n", sim.bond_count(),
                        sim.broken_bonds);
  }
  if (!scene.inlets.empty()) {
    std::string inlets;
    for (const auto& in : scene.inlets) {
      // An inlet of clumps: its clumps, and their members as particles.
      const std::string clumps = in.clump ? fmt::format("\"clumps\": {}, ", in.inserted) : std::string();
      inlets +=
          fmt::format("{}{{\"name\": {}, {}\"particles\": {}, \"mass\": {:.17g}, \"short_of_room\": {}}}",
                      inlets.empty() ? "" : ", ", json_string(in.name), clumps, in.inserted_particles(),
                      in.inserted_mass, in.short_events);
    }
    json << fmt::format("  \"inserted\": {{\"particles\": {}, \"mass\": {:.17g}, \"inlets\": [{}]}},\n",
                        sim.inserted_count, sim.inserted_mass, inlets);
  }
  if (fluid != nullptr) {
    const auto& tb = fluid->total_balance();
    json << fmt::format(
        "  \"fluid\": {{\"cells\": {}, \"updates\": {}, \"solver\": \"{}\", \"preconditioner\": \"{}\", "
        "\"iterations\": {}, "
        "\"max_residual\": {:.6g}, \"inflow\": {:.17g}, \"stored\": {:.17g}, \"pore_change\": {:.17g}, "
        "\"imbalance\": {:.6g}, \"gross_flow\": {:.6g}, \"grains_outside_grid\": {}, "
        "\"grains_in_free_water\": {}}},\n",
        fluid->grid.size(), fluid->updates(), to_string(fluid->solver().kind()),
        fluid->solver().kind() == PressureSolverKind::cg
            ? to_string(fluid->solver().preconditioner_for(static_cast<Eigen::Index>(fluid->grid.size())))
            : "none",
        fluid_iterations, fluid_residual, tb.inflow, tb.stored, tb.pore_change, tb.imbalance(), tb.gross,
        fluid->grains_outside(sim.particles), fluid->grains_in_free_water(sim.particles));
  }
  if (summary.seepage_column) {
    const auto& r = *summary.seepage_column;
    json << fmt::format(
        "  \"seepage_column\": {{\"uplift_rms_error\": {:.6g}, \"pressure_max_error\": {:.6g}, "
        "\"passed\": {}}},\n",
        r.uplift_rms_error, r.pressure_max_error, r.passed ? "true" : "false");
  }
  if (sim.energy.started) {
    const auto& e = sim.energy;
    json << fmt::format(
        "  \"energy\": {{\"gravity_work\": {:.17g}, \"fluid_work\": {:.17g}, \"external_work\": {:.17g}, "
        "\"boundary_work\": {:.17g}, \"damping_dissipation\": {:.17g}, \"contact_dissipation\": {:.17g}, "
        "\"inserted_kinetic\": {:.17g}, \"removed_kinetic\": {:.17g}, "
        "\"kinetic\": {:.17g}, \"elastic\": {:.17g}, \"unaccounted\": {:.6g}}},\n",
        e.gravity_work, e.field_work, e.external_work, e.boundary_work, e.damping_dissipation(),
        sim.contact_dissipation(), e.inserted_kinetic, e.removed_kinetic, sim.kinetic_energy(),
        sim.elastic_energy(), sim.unaccounted_energy());
  }
  json << fmt::format("  \"status\": \"{}\",\n",
                      !failure.empty() ? "failed" : (summary.interrupted ? "interrupted" : "completed"));
  if (!failure.empty()) json << fmt::format("  \"failure\": {},\n", json_string(failure));
  json << fmt::format("  \"stages_completed\": [{}]\n", stages) << "}\n";
  json.close();
}

}  // namespace

template <int D>
void apply_stage(Simulation<D>& sim, PoreFluid<D>* fluid, const Stage<D>& stage) {
  if (fluid != nullptr) {
    if (stage.freeze_permeability) fluid->permeability_frozen = *stage.freeze_permeability;
    if (stage.fluid_steps_per_update) fluid->steps_per_update = *stage.fluid_steps_per_update;
    if (stage.fluid_hold_forces) fluid->hold_forces = *stage.fluid_hold_forces;
    if (stage.fluid_drained) fluid->drained = *stage.fluid_drained;
    for (const auto& [side, b] : stage.fluid_sides) {
      fluid->sides[side] = b;
      fluid->sides[side].value.start = sim.time;
    }
    for (const auto& [patch, b] : stage.fluid_patches) {
      auto& condition = fluid->patches[static_cast<std::size_t>(patch)].condition;
      condition = b;
      condition.value.start = sim.time;
    }
    for (const auto& change : stage.fluid_sources) {
      auto& source = fluid->sources[change.source];
      source.type = change.type;
      source.value = change.value;
      source.value.start = sim.time;
    }
  }
  if (stage.gravity) sim.gravity = *stage.gravity;
  if (stage.local_damping) sim.damping.local = *stage.local_damping;
  if (stage.viscous_damping) sim.damping.viscous = *stage.viscous_damping;
  for (const auto& c : stage.frictions) sim.contact_table.set_friction(c.first, c.second, c.friction);
  if (stage.cell) stage.cell->apply(sim.cell_motion);
  sim.cell_motion.reference_length = sim.periodic.length;  // cell_strain counts from here
  for (const auto& c : stage.walls) {
    auto& w = sim.walls[c.wall];
    w.motion = c.motion;
    w.velocity = c.motion == WallMotion::velocity ? c.velocity : Vec<D>::Zero();
    w.servo = c.servo;
    w.servo.schedule.start = sim.time;  // a servo's target counts from its stage's start
    w.servo_axis = c.servo_axis;
    w.spin = c.spin;
    // A plane or box keeps its last axis when it stops turning.
    if (!w.is_cylinder() && c.spin != 0.0) w.axis = c.spin_axis;
    w.radius_rate = c.radius_rate;
    w.oscillation = c.oscillation;
    w.oscillation.start = sim.time;
  }
}

template <int D>
void apply_inlet_changes(std::vector<Inlet<D>>& inlets, const Stage<D>& stage, double time) {
  for (const auto& [index, active] : stage.inlets) {
    auto& in = inlets[index];
    if (active && !in.active) in.next_time = time;
    in.active = active;
  }
}

std::string describe_critical_step(double seconds) {
  // Only fixed particles (or none free to move): nothing limits the step.
  if (std::isinf(seconds)) return "none (no particle is free to move)";
  return fmt::format("{:.4g} s", seconds);
}

bool output_dir_is_free(const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec)) return true;
  return fs::is_directory(dir, ec) && fs::is_empty(dir, ec);
}

template <int D>
RunSummary run_scene(Scene<D>& scene, const RunOptions& options) {
  auto& sim = scene.simulation;
  const fs::path out = options.out_dir;
  if (std::error_code ec; !fs::create_directories(out, ec) && ec) {
    throw std::runtime_error(
        fmt::format("cannot make the output directory '{}': {}", out.string(), ec.message()));
  }
  const fs::path checkpoint_path = out / "checkpoint.bin";
  const fs::path probes_path = out / "probes.csv";
  std::ofstream probes;
  PvdSeries series((out / "particles.pvd").string());
  PvdSeries fluid_series((out / "fluid.pvd").string());
  PvdSeries wall_series((out / "walls.pvd").string());
  PvdSeries contact_series((out / "contacts.pvd").string());
  PvdSeries source_series((out / "sources.pvd").string());
  PoreFluid<D>* fluid = scene.fluid.get();
  std::optional<SeepageColumnAnalysis<D>> seepage;
  if (scene.seepage_column) seepage.emplace(*scene.seepage_column, scene);
  // Where the run stands; a checkpoint stores it with the state.
  RunPosition pos;
  const RunState<D> state{pos,    sim,          scene.inlets, fluid,          seepage ? &*seepage : nullptr,
                          series, fluid_series, wall_series,  contact_series, source_series};
  auto write_probes = [&] {
    probes << fmt::format("{:.10g}", sim.time);
    for (const auto& p : scene.output.probes)
      probes << fmt::format(",{:.10g}", evaluate_probe(p, sim, scene.fluid.get(), &scene.inlets));
    probes << "\n";
  };
  auto write_snapshot = [&] {
    const std::string name = fmt::format("particles_{:05d}.vtu", pos.snapshot_index);
    write_particles_vtu<D>((out / name).string(), sim.particles,
                           fluid != nullptr ? &sim.field_forces() : nullptr,
                           sim.clumps.empty() ? nullptr : &sim.clumps.clump_of);
    series.add(sim.time, name);
    if (!sim.walls.empty()) {
      // Planes are drawn across the particles' box and the fluid grid's.
      Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
      Vec<D> hi = -lo;
      for (std::size_t i = 0; i < sim.particles.size(); ++i) {
        lo = lo.cwiseMin(sim.particles.position[i] - Vec<D>::Constant(sim.particles.radius[i]));
        hi = hi.cwiseMax(sim.particles.position[i] + Vec<D>::Constant(sim.particles.radius[i]));
      }
      if (fluid != nullptr) {
        lo = lo.cwiseMin(fluid->grid.origin);
        hi = hi.cwiseMax(fluid->grid.upper());
      }
      if (!lo.allFinite() || !hi.allFinite()) {  // no particles left (a domain removed them all)
        lo = Vec<D>::Zero();
        hi = Vec<D>::Zero();
      }
      const std::string wname = fmt::format("walls_{:05d}.vtu", pos.snapshot_index);
      const auto facet_forces = sim.facet_forces();
      write_walls_vtu<D>((out / wname).string(), sim.walls, lo, hi, &facet_forces);
      wall_series.add(sim.time, wname);
    }
    if (scene.output.contacts) {
      const std::string cname = fmt::format("contacts_{:05d}.vtu", pos.snapshot_index);
      write_contacts_vtu<D>((out / cname).string(), sim.particles, sim.contact_forces());
      contact_series.add(sim.time, cname);
    }
    if (fluid != nullptr) {
      const std::string fname =
          fmt::format("fluid_{:05d}.{}", pos.snapshot_index, fluid->grid.any_graded() ? "vtr" : "vti");
      const auto stress = cell_contact_stress<D>(sim, fluid->grid);
      write_fluid_vti<D>((out / fname).string(), *fluid, &stress);
      fluid_series.add(sim.time, fname);
      if (!fluid->sources.empty()) {
        const std::string sname = fmt::format("sources_{:05d}.vtu", pos.snapshot_index);
        write_sources_vtu<D>((out / sname).string(), *fluid);
        source_series.add(sim.time, sname);
      }
    }
    ++pos.snapshot_index;
  };

  RunSummary summary;
  const auto start = Clock::now();
  Progress progress(options);
  // The first stage's settings apply from the start. Contact force
  // magnitudes are summed only if a stop condition or a probe needs them.
  if (!scene.stages.empty()) apply_stage(sim, fluid, scene.stages.front());
  sim.measure_contact_forces =
      std::any_of(scene.stages.begin(), scene.stages.end(),
                  [](const auto& st) { return st.unbalanced_force_below.has_value(); }) ||
      std::any_of(scene.output.probes.begin(), scene.output.probes.end(),
                  [](const auto& p) { return p.quantity == ProbeQuantity::unbalanced_force; });
  sim.prepare();
  sim.cell_motion.reference_length = sim.periodic.length;  // the probes before the first stage
  if (options.resume) {
    // The scene built and prepared as at the start, then the state of the
    // interrupted run loaded over it; output goes on where it stopped.
    read_checkpoint(checkpoint_path.string(), scene, state);
    if (pos.probes_bytes == saved_by_model) {
      throw CheckpointError(fmt::format(
          "{}: saved by a Python model (model.save), which writes no output to go on with: load it with "
          "darcydem.load(scene, checkpoint=...) and go on in Python",
          checkpoint_path.string()));
    }
    ++pos.resumes;
    summary.resumed_at_step = sim.steps;
    summary.stages_completed = pos.stages_completed;
    std::error_code ec;
    if (!fs::exists(probes_path, ec) || fs::file_size(probes_path, ec) < pos.probes_bytes) {
      throw CheckpointError(
          fmt::format("{}: missing or shorter than when the checkpoint was written", probes_path.string()));
    }
    fs::resize_file(probes_path, pos.probes_bytes);
    probes.open(probes_path, std::ios::app);
  } else {
    // A new run in a used directory (--force): an old checkpoint there
    // belongs to another run and must not be resumed into this one's output.
    std::error_code ec;
    fs::remove(checkpoint_path, ec);
    fs::remove(fs::path(checkpoint_path.string() + ".part"), ec);
    probes.open(probes_path, std::ios::trunc);
  }
  if (!probes) throw std::runtime_error(fmt::format("{}: cannot write probes.csv", out.string()));
  const double dt = sim.time_step;
  if (!options.resume) {
    probes << "time";
    for (const auto& p : scene.output.probes) probes << "," << p.name;
    probes << "\n";
    write_probes();
    write_snapshot();
    pos.next_probe = sim.time + scene.output.probe_interval;
    pos.next_snapshot =
        scene.output.snapshot_interval > 0 ? sim.time + scene.output.snapshot_interval : 1e300;
  }
  double& next_probe = pos.next_probe;
  double& next_snapshot = pos.next_snapshot;
  const double wall_before = pos.wall_time;
  if (options.log != nullptr) {
    *options.log << fmt::format(
        "darcydem {}: {} particles, {}D, time step {:.4g} s (critical {})\n", version_string,
        sim.particles.size(), D, dt,
        describe_critical_step(!scene.inlets.empty() ? scene.critical_time_step
                               : fluid != nullptr
                                   ? fluid->critical_time_step(sim.particles, sim.critical_time_step())
                                   : sim.critical_time_step()));
    if (!sim.particles.radius.empty()) *options.log << describe_grading<D>(sim.particles.radius);
    for (const auto& set : scene.overrides) *options.log << "set: " << set << '\n';
    for (const auto& note : scene.notes) *options.log << "note: " << note << '\n';
    if (fluid != nullptr) {
      std::string sides;
      for (int k = 0; k < 2 * D; ++k)
        sides += fmt::format(" {}={}", side_names[k], to_string(fluid->sides[k].type));
      *options.log << fmt::format(
          "pore fluid: {} cells, K_f = {:.4g} Pa, {} solver, fluid step every {} DEM steps{}; sides:{}\n",
          fluid->grid.size(), fluid->fluid.bulk_modulus,
          fluid->solver().describe(static_cast<Eigen::Index>(fluid->grid.size())), fluid->steps_per_update,
          fluid->hold_forces && fluid->steps_per_update > 1 ? " (grain forces held between them)" : "",
          sides);
      *options.log << describe_grid(fluid->grid);
      *options.log << describe_permeability(*fluid, sim.particles);
      *options.log << describe_patches_and_barriers(*fluid, sim.walls);
    }
  }
  if (options.resume && options.log != nullptr) {
    *options.log << fmt::format("resumed from {} at t = {:.6g} s, step {} (stage {}, step {} of it)\n",
                                checkpoint_path.string(), sim.time, sim.steps,
                                pos.stage < scene.stages.size() ? scene.stages[pos.stage].name : "-",
                                pos.stage_steps);
  }
  std::uint64_t& fluid_iterations = pos.fluid_iterations;
  double& fluid_residual = pos.fluid_residual;
  // DEM steps since the last fluid step; the fluid step covers them all
  // (steps_per_update of them, or fewer where a stage changes the interval).
  std::uint64_t& since_update = pos.since_update;
  auto last_checkpoint = Clock::now();
  // Stores the state after `steps_done` steps of stage `stage_index`, with
  // the output as it stands (a resumed run cuts probes.csv back to here).
  auto save_checkpoint = [&](std::size_t stage_index, std::uint64_t steps_done) {
    probes.flush();
    pos.stage = stage_index;
    pos.stage_steps = steps_done;
    pos.probes_bytes = fs::file_size(probes_path);
    pos.wall_time = wall_before + std::chrono::duration<double>(Clock::now() - start).count();
    pos.stages_completed = summary.stages_completed;
    write_checkpoint(checkpoint_path.string(), scene, state);
    summary.checkpoint_written = true;
    last_checkpoint = Clock::now();
  };
  auto fluid_step = [&] {
    darcydem::fluid_step<D>(sim, *fluid, since_update);
    since_update = 0;
    fluid_iterations += static_cast<std::uint64_t>(fluid->last_solve().iterations);
    fluid_residual = std::max(fluid_residual, fluid->last_solve().residual);
  };

  // The inlets' insertions due now; an inlet's first shortage of room is
  // said once.
  auto insert_due_grains = [&] {
    std::vector<std::uint64_t> short_before;
    for (const auto& in : scene.inlets) short_before.push_back(in.short_events);
    insert_all_due(scene.inlets, sim);
    for (std::size_t k = 0; k < scene.inlets.size() && options.log != nullptr; ++k) {
      const auto& in = scene.inlets[k];
      if (short_before[k] == 0 && in.short_events > 0) {
        *options.log << fmt::format(
            "inlet {}: at t = {:.6g} s its box has no room for all the grains due ({} random places tried "
            "for a grain); the rest wait for the next insertion (said once; the run log counts them at "
            "each stage's end)\n",
            in.name, sim.time, in.max_attempts);
      }
    }
  };
  // A failure in a step (a blown-up simulation, a solver that does not
  // converge) ends the run, but what was computed is kept: probes, the last
  // snapshot, the analysis and run.json with the reason; then it is rethrown.
  // Steps from step s of a stage to the next one after which the loop below
  // has something to do. Output times are crossed by accumulating dt, so the
  // count stops one step short of the predicted crossing and the last steps
  // go one at a time.
  auto steps_to_next_event = [&](std::uint64_t s, std::uint64_t n_steps, std::uint64_t check_interval,
                                 double probe_time, double snapshot_time) {
    std::uint64_t run = n_steps - s;
    run = std::min(run, check_interval - s % check_interval);
    run = std::min(run, 256 - (s & 255U));
    if (fluid != nullptr)
      run = std::min(run, static_cast<std::uint64_t>(fluid->steps_per_update) - since_update);
    if (seepage) run = 1;  // it samples the column after every step
    for (double t : {probe_time, snapshot_time, next_insertion_time(scene.inlets)}) {
      const double ahead = std::floor((t - 0.5 * dt - sim.time) / dt) - 1.0;
      run =
          std::min(run, ahead >= 1.0 ? static_cast<std::uint64_t>(std::min(ahead, 1e18)) : std::uint64_t{1});
    }
    return std::max<std::uint64_t>(run, 1);
  };
  // Whether time t has reached an output time (within half a step).
  auto reached = [&](double t, double event) { return t >= event - 0.5 * dt; };
  const bool stress_probes =
      std::any_of(scene.output.probes.begin(), scene.output.probes.end(), [](const ProbeSpec& p) {
        return p.quantity == ProbeQuantity::stress || p.quantity == ProbeQuantity::cell_stress;
      });
  std::string failure;
  try {
    const std::size_t first_stage = options.resume ? pos.stage : 0;
    for (std::size_t k = first_stage; k < scene.stages.size(); ++k) {
      const auto& stage = scene.stages[k];
      // A resumed stage has had its start (held in the checkpoint).
      const bool resumed_here = options.resume && k == first_stage;
      if (!resumed_here) {
        if (starts_new_coupling_interval(fluid, stage) && since_update > 0) fluid_step();
        apply_stage(sim, fluid, stage);
        apply_inlet_changes(scene.inlets, stage, sim.time);
        if (stage.make_bonds) {
          const std::size_t made = sim.make_bonds(stage.bond_gap);
          if (options.log != nullptr) {
            *options.log << fmt::format("stage {}: {} pairs bonded ({} bonds intact)\n", stage.name, made,
                                        sim.bond_count());
          }
        }
        if (fluid != nullptr && options.log != nullptr &&
            (stage.fluid_steps_per_update || stage.fluid_hold_forces)) {
          *options.log << fmt::format("stage {}: fluid step every {} DEM steps{}\n", stage.name,
                                      fluid->steps_per_update,
                                      fluid->hold_forces ? ", grain forces held between them" : "");
        }
        if (seepage) seepage->stage_started(scene, stage.name);
      }
      const auto n_steps = static_cast<std::uint64_t>(std::max(1.0, std::round(stage.duration / dt)));
      const std::uint64_t first_step = resumed_here ? pos.stage_steps : 0;
      const double t_end = sim.time + static_cast<double>(n_steps - std::min(first_step, n_steps)) * dt;
      bool stopped_early = false;
      std::string stop_reason;
      const auto check_interval = static_cast<std::uint64_t>(stage.check_interval);
      const bool stops = stage.kinetic_energy_below.has_value() || stage.unbalanced_force_below.has_value() ||
                         stage.stop_probe.has_value();
      for (std::uint64_t s = first_step; s < n_steps; ++s) {
        insert_due_grains();
        // Advance to the next step at which anything below may act (fluid
        // update, output, stop check, progress): the steps in between run
        // fused (Simulation::advance), with the same results as one by one.
        const std::uint64_t run = steps_to_next_event(s, n_steps, check_interval, next_probe, next_snapshot);
        // Contact stresses and the contact network at the output this run
        // ends at use the forces its last step applies
        // (Simulation::record_contact_forces): a probe or snapshot time, or
        // where the stage may end (its last step, or a stop check).
        const double end = sim.time + static_cast<double>(run) * dt;
        const bool stage_may_end = s + run == n_steps || (stops && (s + run) % check_interval == 0);
        sim.record_contact_forces =
            (stress_probes && (stage_may_end || reached(end, next_probe))) ||
            ((fluid != nullptr || scene.output.contacts) && (stage_may_end || reached(end, next_snapshot)));
        sim.advance(run);
        s += run - 1;
        since_update += run;
        if (fluid != nullptr && since_update >= static_cast<std::uint64_t>(fluid->steps_per_update)) {
          fluid_step();
        }
        if (seepage) seepage->after_step(scene);
        if (reached(sim.time, next_probe)) {
          write_probes();
          next_probe += scene.output.probe_interval;
          if (next_probe < sim.time) next_probe = sim.time + scene.output.probe_interval;
        }
        if (reached(sim.time, next_snapshot)) {
          write_snapshot();
          next_snapshot += scene.output.snapshot_interval;
        }
        if ((s + 1) % check_interval == 0) {
          stop_reason = stop_condition_met(scene, stage);
          if (!stop_reason.empty()) {
            stopped_early = true;
            break;
          }
        }
        if (((s + 1) & 255U) == 0) {
          if ((options.interrupt != nullptr && options.interrupt->load()) ||
              (options.stop_at_step > 0 && sim.steps >= options.stop_at_step)) {
            summary.interrupted = true;
            save_checkpoint(k, s + 1);
            break;
          }
          if (options.checkpoint_every > 0 &&
              std::chrono::duration<double>(Clock::now() - last_checkpoint).count() >=
                  options.checkpoint_every) {
            save_checkpoint(k, s + 1);
          }
          progress.update(stage.name, sim.time, t_end, sim.steps);
        }
      }
      progress.update(stage.name, sim.time, t_end, sim.steps, true);
      progress.end_line();
      write_probes();
      write_snapshot();
      if (seepage) seepage->stage_ended(scene, stage.name, !summary.interrupted);
      for (const auto& in : scene.inlets) {
        if (options.log == nullptr) break;
        const std::string added =
            in.clump ? fmt::format("{} clumps ({} particles)", in.inserted, in.inserted_particles())
                     : fmt::format("{} grains", in.inserted);
        *options.log << fmt::format("inlet {}: {} added so far ({:.6g} kg{}){}{}\n", in.name, added,
                                    in.inserted_mass, D == 2 ? " per metre" : "",
                                    in.exhausted() ? ", all it may add" : "",
                                    in.short_events > 0 ? fmt::format("; {} insertions found no room for all "
                                                                      "that was due",
                                                                      in.short_events)
                                                        : "");
      }
      if (sim.contact_table.any_bondable() && options.log != nullptr) {
        *options.log << fmt::format("contact bonds: {} intact, {} broken so far\n", sim.bond_count(),
                                    sim.broken_bonds);
      }
      if (sim.has_domain && options.log != nullptr && sim.removed_count > 0) {
        *options.log << fmt::format(
            "{} particles have left the [domain] so far ({:.6g} kg, {:.6g} m^3 of grains): removed; {} "
            "remain\n",
            sim.removed_count, sim.removed_mass, sim.removed_volume, sim.particles.size());
      }
      if (fluid != nullptr && options.log != nullptr) {
        const auto& tb = fluid->total_balance();
        *options.log << fmt::format(
            "fluid balance so far: inflow {:.6g} m^3 = stored {:.6g} + pore change {:.6g}; imbalance {:.3g} "
            "m^3 "
            "({:.3g} of the gross flow); solver residual <= {:.3g}, {} iterations\n",
            tb.inflow, tb.stored, tb.pore_change, tb.imbalance(),
            tb.gross > 0 ? std::abs(tb.imbalance()) / tb.gross : 0.0, fluid_residual, fluid_iterations);
        const std::size_t outside = fluid->grains_outside(sim.particles);
        const std::size_t immersed = fluid->grains_in_free_water(sim.particles);
        if (outside > immersed) {
          *options.log << fmt::format(
              "{} of {} grains have their centres outside the fluid grid{}: no fluid force or buoyancy on "
              "them\n",
              outside - immersed, sim.particles.size(),
              std::isnan(fluid->water_level) ? "" : " and above [fluid] water_level");
        }
        if (immersed > 0) {
          *options.log << fmt::format(
              "{} of {} grains are outside the fluid grid below [fluid] water_level: in free water "
              "(buoyancy and a lone grain's drag)\n",
              immersed, sim.particles.size());
        }
      }
      if (sim.cell_motion.active() && options.log != nullptr) {
        const Vec<D> stress = sim.cell_stress().diagonal();
        Vec<D> strain;
        for (int k = 0; k < D; ++k) strain[k] = sim.cell_motion.strain(sim.periodic, k);
        *options.log << fmt::format(
            "periodic cell: lengths {:.6g} m, strains {:.6g} over the stage (volumetric {:.6g}), strain "
            "rates "
            "{:.4g} 1/s, normal stresses {:.6g} Pa (the contacts' mean over it){}\n",
            fmt::join(sim.periodic.length, ", "), fmt::join(strain, ", "),
            sim.cell_motion.strain(sim.periodic, -1), fmt::join(sim.cell_motion.strain_rate, ", "),
            fmt::join(stress, ", "),
            fluid != nullptr ? fmt::format(", mean excess pore pressure {:.6g} Pa", fluid->mean_pressure())
                             : "");
      }
      if (sim.energy.started && options.log != nullptr) *options.log << describe_energy(sim);
      if (summary.interrupted) break;
      summary.stages_completed.push_back(stage.name);
      if (options.log != nullptr && stopped_early) {
        *options.log << fmt::format("stage {}: stop condition met at t = {:.6g} s: {}\n", stage.name,
                                    sim.time, stop_reason);
      }
    }
  } catch (const std::exception& e) {
    failure = fmt::format("at t = {:.6g} s (step {}): {}", sim.time, sim.steps, e.what());
    try {
      write_probes();
      write_snapshot();
    } catch (const std::exception&) {
      // the state may not be writable (non-finite); what was written stays
    }
  }
  probes.flush();
  if (failure.empty()) write_final_particles(out, scene, summary.interrupted);
  if (seepage) summary.seepage_column = seepage->finish(scene, out.string(), options.log);

  summary.steps = sim.steps;
  summary.simulated_time = sim.time;
  summary.wall_time = wall_before + std::chrono::duration<double>(Clock::now() - start).count();
  {
    // A finished run has nothing to resume; a failed one keeps its last checkpoint.
    std::error_code ec;
    if (failure.empty() && !summary.interrupted) fs::remove(checkpoint_path, ec);
    summary.checkpoint_written = fs::exists(checkpoint_path, ec);
  }
  write_run_json(out / "run.json", scene, summary, pos, failure);
  if (!failure.empty())
    throw std::runtime_error(failure + " (the output written so far is kept in " + out.string() + ")");
  return summary;
}

template <int D>
std::string describe_grid(const FluidGrid<D>& grid) {
  std::string out = "fluid grid:";
  for (int k = 0; k < D; ++k) {
    const std::string width = grid.graded(k) ? fmt::format("graded, {:.4g} to {:.4g} m", grid.width(k, 0),
                                                           grid.width(k, grid.cells[k] - 1))
                                             : fmt::format("{:.4g} m", grid.spacing[k]);
    out += fmt::format("{} {} {} cells in [{:.6g}, {:.6g}] m ({})", k == 0 ? "" : ";", "xyz"[k],
                       grid.cells[k], grid.face_at(k, 0), grid.face_at(k, grid.cells[k]), width);
  }
  return out + "\n";
}

template <int D>
std::string describe_patches_and_barriers(const PoreFluid<D>& fluid, const std::vector<Wall<D>>& walls) {
  std::string out;
  for (std::size_t k = 0; k < fluid.patches.size(); ++k) {
    const auto& patch = fluid.patches[k];
    const double area = fluid.patch_area(k);
    out += fmt::format("patch {} on {}: {} faces, {:.6g} m^2, {}\n", patch.name, side_names[patch.side],
                       fluid.patch_faces(k), area, to_string(patch.condition.type));
  }
  for (std::size_t k = 0; k < fluid.sources.size(); ++k) {
    const auto& source = fluid.sources[k];
    const auto cell = fluid.grid.coords(fluid.source_cell(k));
    std::string at;
    std::string index;
    for (int a = 0; a < D; ++a) {
      at += fmt::format("{}{:.6g}", a == 0 ? "" : ", ", source.position[a]);
      index += fmt::format("{}{}", a == 0 ? "" : ", ", cell[a]);
    }
    if (source.screened()) {
      const auto cells = fluid.screen_well_indices(k);
      const int along = source.screen_axis;
      at.clear();
      index.clear();
      for (int a = 0; a < D; ++a) {
        const char* comma = a == 0 ? "" : ", ";
        if (a != along) at += fmt::format("{}{:.6g}", at.empty() ? "" : ", ", source.position[a]);
        index += a != along ? fmt::format("{}{}", comma, cell[a])
                            : fmt::format("{}{} to {}", comma, fluid.grid.coords(cells.front().first)[a],
                                          fluid.grid.coords(cells.back().first)[a]);
      }
      index += fmt::format("; screened from {} = {:.6g} to {:.6g} m", "xyz"[along], source.screen[0],
                           source.screen[1]);
    }
    const bool steady = source.value.times.size() == 1;
    const std::string unit =
        source.type == FluidSourceType::inflow ? fmt::format("m^{}/s", D) : std::string("Pa held");
    out += fmt::format(
        "source {} at ({}) m, into cell{} ({}): {}{}{}\n", source.name, at, source.screened() ? "s" : "",
        index,
        steady ? fmt::format("{:.6g} {}", source.value.at(0.0), unit)
               : fmt::format("{:.6g} to {:.6g} {} over {} points in time", source.value.values.front(),
                             source.value.values.back(), unit, source.value.values.size()),
        source.radius > 0.0
            ? fmt::format("; a well of radius {:.6g} m, its cell's equivalent radius {:.6g} m{}",
                          source.radius, fluid.equivalent_radius(k),
                          source.screened()
                              ? fmt::format(" across it, well index {:.6g} m^3/(s Pa) summed over "
                                            "its cells",
                                            fluid.well_index(k))
                              : std::string())
            : std::string(),
        source.drain ? "; a drain: it takes water out only, while the water around it stands above that"
                     : "");
  }
  for (std::size_t k = 0; k < fluid.barriers.size(); ++k) {
    const auto& b = fluid.barriers[k];
    out += fmt::format("barrier {}: {} faces normal to {} at {} = {:.6g} m\n", b.name, fluid.barrier_faces(k),
                       "xyz"[b.axis], "xyz"[b.axis], b.at);
  }
  for (std::size_t w : fluid.solid_walls) {
    const Wall<D>& wall = walls.at(w);
    const char* closed = fluid.is_impermeable(w) ? ", impermeable (closes the faces it covers)" : "";
    if (wall.is_box()) {
      out += fmt::format("wall {} displaces the fluid: a box{}\n", wall.name, closed);
      continue;
    }
    const int a = grid_axis_of<D>(wall.normal);
    const bool up = wall.normal[a] > 0.0;
    // Beyond the side it faces, the plane takes no room in the grid: the
    // water ends at that side, which stays where it is until the plane
    // moves into the grid (a platen meant to push the water must start
    // inside the grid, or the grid reach past it).
    const int side = 2 * a + (up ? 0 : 1);
    const double edge = up ? fluid.grid.origin[a] : fluid.grid.upper()[a];
    const bool beyond = up ? wall.point[a] < edge : wall.point[a] > edge;
    const std::string outside =
        beyond ? fmt::format(
                     "; now beyond the grid's {} side ({:.6g} m): it displaces no water until it moves into "
                     "the grid",
                     side_names[side], edge)
               : std::string();
    out += fmt::format("wall {} displaces the fluid: a plane, solid where {} {} {:.6g} m{}{}\n", wall.name,
                       "xyz"[a], up ? "<" : ">", wall.point[a], closed, outside);
  }
  return out;
}

template <int D>
std::string describe_permeability(const PoreFluid<D>& fluid, const ParticleData<D>& particles) {
  const auto& spec = fluid.permeability;
  std::string out = "permeability: ";
  if (spec.model == PermeabilityModel::kozeny_carman) {
    // Given or by default: said when it is the grains' (to round-off).
    const double grains = specific_surface_diameter<D>(particles.radius);
    const bool by_default = std::abs(spec.diameter - grains) <= 1e-9 * grains;
    out += fmt::format("Kozeny-Carman, d = {:.6g} m{}", spec.diameter,
                       by_default ? " (the grains' specific-surface diameter)" : "");
    if (spec.anisotropy != Vec<D>::Ones()) {
      out += ", anisotropy";
      for (int k = 0; k < D; ++k) out += fmt::format(" {:.4g}", spec.anisotropy[k]);
    }
  } else {
    out += "constant, k =";
    for (int k = 0; k < D; ++k)
      out += fmt::format(" {:.4g}", spec.intrinsic[k] * fluid.fluid.unit_weight() / fluid.fluid.viscosity);
    out += " m/s";
  }
  out += fmt::format("; porosity taken in [{:.4g}, {:.4g}]; drag {}{}\n", spec.min_porosity,
                     spec.max_porosity, fluid.drag == DragLaw::darcy ? "darcy" : "ergun",
                     fluid.drag_cells == DragCells::overlaps ? " over the overlapped cells" : "");
  // Ergun's drag follows Kozeny-Carman's pressure drop only for one d.
  if (fluid.drag == DragLaw::ergun && !particles.radius.empty()) {
    if (spec.model == PermeabilityModel::kozeny_carman) {
      const double balanced = ergun_balance_diameter<D>(particles.radius);
      const double excess = spec.diameter * spec.diameter / (balanced * balanced) - 1.0;
      if (std::abs(excess) > 0.01) {
        out += fmt::format(
            "note: with Ergun's drag each grain takes its own d, which balances Kozeny-Carman for "
            "d = {:.6g} m; at d = {:.6g} m the viscous drag is {:.1f} % {} what the pressure drop needs "
            "(drag \"darcy\" keeps the balance)\n",
            balanced, spec.diameter, 100.0 * std::abs(excess), excess > 0.0 ? "above" : "below");
      }
    } else {
      out +=
          "note: Ergun's drag does not follow a given permeability: the seepage force will not balance the "
          "pressure drop (drag \"darcy\" takes it from the permeability and does)\n";
    }
  }
  return out;
}

template std::string describe_permeability<2>(const PoreFluid<2>&, const ParticleData<2>&);
template std::string describe_permeability<3>(const PoreFluid<3>&, const ParticleData<3>&);
template std::string describe_patches_and_barriers<2>(const PoreFluid<2>&, const std::vector<Wall<2>>&);
template std::string describe_patches_and_barriers<3>(const PoreFluid<3>&, const std::vector<Wall<3>>&);
template std::string describe_grid<2>(const FluidGrid<2>&);
template std::string describe_grid<3>(const FluidGrid<3>&);
template <int D>
void fluid_step(Simulation<D>& sim, PoreFluid<D>& fluid, std::uint64_t steps) {
  fluid.update(sim.particles, static_cast<double>(steps) * sim.time_step, sim.time, sim.walls);
  for (std::size_t w : fluid.solid_walls) sim.walls[w].water_force = fluid.wall_thrust(sim.walls, w);
}

template void fluid_step<2>(Simulation<2>&, PoreFluid<2>&, std::uint64_t);
template void fluid_step<3>(Simulation<3>&, PoreFluid<3>&, std::uint64_t);
template void apply_stage<2>(Simulation<2>&, PoreFluid<2>*, const Stage<2>&);
template void apply_stage<3>(Simulation<3>&, PoreFluid<3>*, const Stage<3>&);
template void apply_inlet_changes<2>(std::vector<Inlet<2>>&, const Stage<2>&, double);
template void apply_inlet_changes<3>(std::vector<Inlet<3>>&, const Stage<3>&, double);
template RunSummary run_scene<2>(Scene<2>&, const RunOptions&);
template RunSummary run_scene<3>(Scene<3>&, const RunOptions&);

}  // namespace darcydem
