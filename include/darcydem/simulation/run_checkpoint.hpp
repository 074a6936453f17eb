#pragma once
// Checkpoint files of a run (OUT/checkpoint.bin): where the run stands in its
// stages and output, and the whole state of the simulation, the pore fluid
// and the analysis, so that `darcydem run --resume` continues bit for bit.
// The header names the format, the dimension, the machine's number
// conventions, the version and the scene's hash; a checkpoint is only read
// back into the scene that wrote it.
#include <cstdint>
#include <string>
#include <vector>

#include "darcydem/analysis/seepage_column.hpp"
#include "darcydem/generation/inlet.hpp"
#include "darcydem/output/vtk.hpp"
#include "darcydem/scene/scene.hpp"

namespace darcydem {

/// Where a run stands: its stage, its output and its counters.
struct RunPosition {
  std::uint64_t stage = 0;         ///< index of the stage under way
  std::uint64_t stage_steps = 0;   ///< steps of that stage done
  std::uint64_t since_update = 0;  ///< DEM steps since the last fluid step
  double next_probe = 0.0;         ///< s
  double next_snapshot = 0.0;      ///< s
  std::int64_t snapshot_index = 0;
  std::uint64_t fluid_iterations = 0;
  double fluid_residual = 0.0;
  std::uint64_t probes_bytes = 0;  ///< length of probes.csv when written
  double wall_time = 0.0;          ///< s of wall time of the run so far
  std::uint64_t resumes = 0;       ///< how often the run was resumed
  std::vector<std::string> stages_completed;

  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(stage, stage_steps, since_update, next_probe, next_snapshot, snapshot_index, fluid_iterations,
       fluid_residual, probes_bytes, wall_time, resumes, stages_completed);
  }
};

/// RunPosition::probes_bytes of a checkpoint a Python model saved
/// (model.save): it has no output directory for `darcydem run --resume` to
/// go on with.
constexpr std::uint64_t saved_by_model = ~std::uint64_t{0};

/// Everything a checkpoint holds, by reference.
template <int D>
struct RunState {
  RunPosition& position;
  Simulation<D>& simulation;
  std::vector<Inlet<D>>& inlets;       ///< the scene's, with their counts and random state
  PoreFluid<D>* fluid;                 ///< null without [fluid]
  SeepageColumnAnalysis<D>* analysis;  ///< null without the analysis
  PvdSeries& particle_series;
  PvdSeries& fluid_series;
  PvdSeries& wall_series;
  PvdSeries& contact_series;
  PvdSeries& source_series;
};

/// Writes the checkpoint to `path` (through a temporary file renamed over
/// it, so a checkpoint is either whole or the previous one). Throws
/// std::runtime_error if it cannot be written.
template <int D>
void write_checkpoint(const std::string& path, const Scene<D>& scene, const RunState<D>& state);

/// Loads the checkpoint at `path` into a run built from the same scene and
/// prepared. Throws CheckpointError, naming the file and what does not
/// match, for a missing, damaged or foreign file.
template <int D>
void read_checkpoint(const std::string& path, const Scene<D>& scene, const RunState<D>& state);

}  // namespace darcydem
