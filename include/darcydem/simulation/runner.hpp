#pragma once
// Runs a scene's stages in order and writes its output directory:
//   probes.csv           time,<probe names>
//   particles_NNNNN.vtu  snapshots, with particles.pvd as the series
//   fluid_NNNNN.vti      pore-fluid snapshots (with [fluid]), fluid.pvd the series
//   run.json             version, scene hash, steps, wall time, how it ended
//   seepage files        with [analysis] kind = "seepage_column" (seepage_column.hpp)
// The run can be interrupted (the caller's flag); what was computed is kept
// and run.json says so.
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
};

struct RunSummary {
  std::uint64_t steps = 0;
  double simulated_time = 0.0;  ///< s
  double wall_time = 0.0;       ///< s
  bool interrupted = false;
  std::vector<std::string> stages_completed;
  std::optional<SeepageColumnResult> seepage_column;  ///< with [analysis] kind = "seepage_column"
};

/// Throws std::runtime_error when the output directory cannot be written.
template <int D>
RunSummary run_scene(Scene<D>& scene, const RunOptions& options);

/// True when dir does not exist or is an empty directory.
bool output_dir_is_free(const std::string& dir);

}  // namespace darcydem
