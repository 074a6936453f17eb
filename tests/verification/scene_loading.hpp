#pragma once
// Loads scene files from the source tree, as a user would run them.
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "darcydem/scene/scene.hpp"
#include "darcydem/scene/toml_reader.hpp"
#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"

namespace darcydem::testing {

/// Loads the scene file at `path` (any folder), as `darcydem run` does.
template <int D>
Scene<D> load_scene_file(const std::string& path) {
  std::string text;
  const toml::table root = parse_toml_file(path, text);
  return build_scene<D>(root, path, text);
}

/// Writes `text` as dir/name (making dir) and loads it.
template <int D>
Scene<D> scene_from_text(const std::string& dir, const std::string& name, const std::string& text) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return load_scene_file<D>(path);
}

/// Loads a scene file from the source tree (path relative to it).
template <int D>
Scene<D> load_scene(const std::string& relative) {
  return load_scene_file<D>(std::string(DARCYDEM_SOURCE_DIR) + "/" + relative);
}

/// A file's bytes (empty if it cannot be read).
inline std::string file_contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// `text` with each of `swaps` (a text, its replacement) made at its first
/// place; throws std::logic_error naming a text it lacks (`what`: whose).
inline std::string text_variant(std::string text,
                                const std::vector<std::pair<std::string, std::string>>& swaps,
                                const std::string& what = "the scene") {
  for (const auto& [from, to] : swaps) {
    const auto at = text.find(from);
    if (at == std::string::npos) throw std::logic_error(what + " has no \"" + from + "\"");
    text.replace(at, from.size(), to);
  }
  return text;
}

/// The text of a scene file of the source tree (path relative to it) with
/// each of `swaps` made at its first place (text_variant).
inline std::string scene_variant(const std::string& relative,
                                 const std::vector<std::pair<std::string, std::string>>& swaps) {
  return text_variant(file_contents(std::string(DARCYDEM_SOURCE_DIR) + "/" + relative), swaps, relative);
}

/// Runs every stage without writing output (stop conditions honoured).
template <int D>
void run_stages(Scene<D>& scene) {
  auto& sim = scene.simulation;
  bool prepared = false;
  for (const auto& stage : scene.stages) {
    if (stage.gravity) sim.gravity = *stage.gravity;
    if (stage.local_damping) sim.damping.local = *stage.local_damping;
    if (stage.viscous_damping) sim.damping.viscous = *stage.viscous_damping;
    if (!prepared) {
      sim.prepare();
      prepared = true;
    }
    const auto n = static_cast<long>(std::round(stage.duration / sim.time_step));
    for (long s = 0; s < n; ++s) {
      sim.step();
      if ((s + 1) % stage.check_interval == 0) {
        if (stage.kinetic_energy_below && sim.kinetic_energy() < *stage.kinetic_energy_below) break;
        if (stage.unbalanced_force_below && sim.unbalanced_force_ratio() < *stage.unbalanced_force_below)
          break;
      }
    }
  }
}

/// Runs a scene file of the source tree (path relative to it) as `darcydem
/// run` does, its output in `out_dir`.
template <int D>
RunSummary run_example(const std::string& relative, const std::string& out_dir) {
  Scene<D> scene = load_scene<D>(relative);
  RunOptions options;
  options.out_dir = out_dir;
  return run_scene<D>(scene, options);
}

/// Writes `text` as a scene in a fresh folder named for `name`, runs it as
/// `darcydem run` does (its log kept from the terminal) and returns its
/// probes.csv by column (its log in *log_text if given; run.json stays in
/// temp_path(name)/out); throws if the run was interrupted.
template <int D>
std::map<std::string, std::vector<double>> run_scene_probes(const std::string& name, const std::string& text,
                                                            std::string* log_text = nullptr) {
  const std::string dir = temp_dir(name);
  Scene<D> scene = scene_from_text<D>(dir, "scene.toml", text);
  RunOptions options;
  options.out_dir = dir + "/out";
  std::ostringstream log;
  options.log = &log;
  if (run_scene<D>(scene, options).interrupted) throw std::runtime_error(name + ": the run was interrupted");
  if (log_text != nullptr) *log_text = log.str();
  return read_probes(options.out_dir + "/probes.csv");
}

}  // namespace darcydem::testing
