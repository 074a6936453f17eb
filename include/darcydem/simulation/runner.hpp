#pragma once
// Runs a scene's stages in order and writes its output directory:
//   probes.csv           time,<probe names>
//   particles_NNNNN.vtu  snapshots, with particles.pvd as the series
//   fluid_NNNNN.vti      pore-fluid snapshots (with [fluid]), fluid.pvd the series
//   run.json             version, scene hash, steps, wall time, how it ended
//   particles_final.csv  the end state as a packing for the csv generator
//   seepage files        with [analysis] kind = "seepage_column" (seepage_column.hpp)
//   checkpoint.bin       when interrupted (and every checkpoint_every s): the
//                        whole state, for resuming (run_checkpoint.hpp)
// The run can be interrupted (the caller's flag); what was computed is kept,
// run.json says so, and the run can be resumed from its checkpoint.
#include <atomic>
#include <cstdint>
#include <iosfwd>
#include <string>

#include "darcydem/analysis/seepage_column.hpp"
#include "darcydem/scene/scene.hpp"

namespace darcydem {

struct RunOptions {
  std::string out_dir;
  const std::atomic<bool>* interrupt = nullptr;  ///< set by a signal handler
  std::ostream* log = nullptr;                   ///< progress and messages (nullptr: quiet)
  bool terminal = false;                         ///< progress bar (true) or plain lines
  double progress_every = 10.0;                  ///< s of wall time between plain lines
  /// Continue the run in out_dir from its checkpoint.bin: the same scene,
  /// the same results bit for bit as a run that never stopped.
  bool resume = false;
  /// s of wall time between checkpoints (0: only when interrupted).
  double checkpoint_every = 0.0;
  /// Stop as if interrupted once this many steps are done in all (0: never).
  /// Checked where the interrupt flag is, every 256 steps of a stage.
  std::uint64_t stop_at_step = 0;
};

struct RunSummary {
  std::uint64_t steps = 0;
  double simulated_time = 0.0;  ///< s
  double wall_time = 0.0;       ///< s
  bool interrupted = false;
  bool checkpoint_written = false;    ///< out_dir/checkpoint.bin holds the state at the end
  std::uint64_t resumed_at_step = 0;  ///< with RunOptions::resume: the step the run went on from
  std::vector<std::string> stages_completed;
  std::optional<SeepageColumnResult> seepage_column;  ///< with [analysis] kind = "seepage_column"
};

/// Applies a stage's settings (gravity, damping, wall motions, the pore
/// fluid's conditions and coupling), as a run does when the stage starts;
/// the fluid's time series count from now.
template <int D>
void apply_stage(Simulation<D>& sim, PoreFluid<D>* fluid, const Stage<D>& stage);

/// Switches the inlets a stage names on or off; one switched on inserts
/// from `time` on.
template <int D>
void apply_inlet_changes(std::vector<Inlet<D>>& inlets, const Stage<D>& stage, double time);

/// One fluid step covering the `steps` DEM steps since the last one: the
/// pore fluid's update with the walls where they are now, then the water's
/// thrust on each wall that displaces it (Wall::water_force, which a servo
/// with `load = "total"` counts). The runner and the Python module step
/// alike through it.
template <int D>
void fluid_step(Simulation<D>& sim, PoreFluid<D>& fluid, std::uint64_t steps);

/// Whether the stage sets a coupling interval other than the fluid's
/// current one: a new interval starts afresh, so the DEM steps since the
/// last fluid step get theirs before the stage applies.
template <int D>
[[nodiscard]] bool starts_new_coupling_interval(const PoreFluid<D>* fluid, const Stage<D>& stage) {
  return fluid != nullptr && stage.fluid_steps_per_update &&
         *stage.fluid_steps_per_update != fluid->steps_per_update;
}

/// Throws std::runtime_error when the output directory cannot be written.
template <int D>
RunSummary run_scene(Scene<D>& scene, const RunOptions& options);

/// One line per boundary patch of the pore fluid (its name, side, faces,
/// area and condition), per barrier (its name, plane and faces) and per
/// wall among `walls` that displaces the fluid (a box, or a plane and the
/// side of it that is solid); the run log and `darcydem check` print them.
template <int D>
std::string describe_patches_and_barriers(const PoreFluid<D>& fluid, const std::vector<Wall<D>>& walls);
/// The fluid grid's cells along each axis, its extent and the cells' width
/// (the first and last along a graded axis), one line for the run log.
template <int D>
std::string describe_grid(const FluidGrid<D>& grid);

/// The permeability model and the drag law, one line for the run log and
/// `darcydem check`: Kozeny-Carman's d (saying when it is the grains'
/// specific-surface diameter, the default) or the constant k per axis.
template <int D>
std::string describe_permeability(const PoreFluid<D>& fluid, const ParticleData<D>& particles);

/// "1.256e-05 s", or what an infinite critical step means (no free particle).
std::string describe_critical_step(double seconds);

/// True when dir does not exist or is an empty directory.
bool output_dir_is_free(const std::string& dir);

}  // namespace darcydem
