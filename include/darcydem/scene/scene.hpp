#pragma once
// A scene: the simulation set up from a TOML file, with what to output and
// the list of stages to run. Documented key by key in docs/SCENE.md.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "darcydem/core/vec.hpp"
#include "darcydem/simulation/simulation.hpp"

namespace darcydem {

enum class ProbeQuantity {
  particle_position,
  particle_velocity,
  wall_position,
  wall_force,
  kinetic_energy,
  contact_count,
  coordination,
  max_overlap,
  unbalanced_force,
};

struct ProbeSpec {
  std::string name;
  ProbeQuantity quantity = ProbeQuantity::kinetic_energy;
  std::int64_t particle = -1;  ///< creation index; -1: the topmost particle
  int component = 0;           ///< 0..D-1, or -1 for the norm
  std::size_t wall = 0;
};

struct OutputSpec {
  double probe_interval = 0.0;     ///< s (0: every step)
  double snapshot_interval = 0.0;  ///< s (0: only at the end of each stage)
  std::vector<ProbeSpec> probes;
};

struct TimeStepSpec {
  bool automatic = true;
  double value = 0.0;          ///< s, when not automatic
  double safety_factor = 0.2;  ///< fraction of the critical step
};

template <int D>
struct WallChange {
  std::size_t wall = 0;
  WallMotion motion = WallMotion::fixed;
  Vec<D> velocity = Vec<D>::Zero();
  ServoControl servo;
};

template <int D>
struct Stage {
  std::string name;
  double duration = 0.0;  ///< s; the longest the stage runs
  std::optional<Vec<D>> gravity;
  std::optional<double> local_damping;
  std::optional<double> viscous_damping;
  std::optional<double> kinetic_energy_below;    ///< J: stop once below
  std::optional<double> unbalanced_force_below;  ///< -: stop once below
  std::int64_t check_interval = 100;             ///< steps between stop checks
  std::vector<WallChange<D>> walls;
};

template <int D>
struct Scene {
  std::string file;
  std::string text_hash;  ///< FNV-1a 64 of the scene file's bytes, hex
  Simulation<D> simulation;
  TimeStepSpec time_step;
  OutputSpec output;
  std::vector<Stage<D>> stages;
};

/// Reads `simulation.dimension` (2 or 3) from a parsed scene.
int scene_dimension(const toml::table& root, const std::string& file);

/// Builds a scene from a parsed file; throws SceneError on bad input. Sets
/// the time step (checked against the critical step).
template <int D>
Scene<D> build_scene(const toml::table& root, const std::string& file, const std::string& text);

std::string fnv1a_hex(const std::string& bytes);

}  // namespace darcydem
