#pragma once
// The consolidation scenes (examples/fluid_cases/consolidation_*.toml): the
// paper's column settled, then loaded through a lid or a sealed piston; run
// as a user runs them, with Terzaghi's parameters of the run.
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "darcydem/analysis/seepage_analytic.hpp"
#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

namespace darcydem::testing {

/// Terzaghi's parameters of the paper's column (the grid one cell wide,
/// 25 high) under a load stress `stress` that settles it by
/// `final_settlement`: m_v = S_f / (stress H), H the grid's height; k the
/// cells in series; n the mean of the cells below the top one, which is
/// partly empty or partly a piston (the column is 0.4 mm shorter than the
/// grid).
inline SeepageColumnParameters terzaghi_parameters(const PoreFluid<2>& f, double final_settlement,
                                                   double stress) {
  SeepageColumnParameters p;
  p.height = f.grid.upper().y() - f.grid.origin.y();
  p.unit_weight = f.fluid.unit_weight();
  p.compressibility = final_settlement / (stress * p.height);
  double resistance = 0.0;
  double porosity = 0.0;
  const std::size_t cells = f.grid.size();
  for (std::size_t c = 0; c < cells; ++c) {
    resistance += f.grid.spacing.y() / f.permeability_field()[c].y();
    if (c + 1 < cells) porosity += f.porosity()[c] / static_cast<double>(cells - 1);
  }
  p.conductivity = p.height / resistance * p.unit_weight / f.fluid.viscosity;
  p.fluid_storage = porosity / f.fluid.bulk_modulus;
  return p;
}

/// A run of one of the consolidation scenes (a settling stage, then the
/// load stage): its probes, the first row of the load stage and the top
/// disc's height just before it.
struct ConsolidationRun {
  Scene<2> scene;
  std::map<std::string, std::vector<double>> probes;
  std::size_t i0 = 0;
  double y0 = 0.0;
};
inline ConsolidationRun run_consolidation(Scene<2> scene, const std::string& name) {
  ConsolidationRun run{std::move(scene), {}, 0, 0.0};
  RunOptions options;
  options.out_dir = temp_dir(name);
  run_scene(run.scene, options);
  run.probes = read_probes(options.out_dir + "/probes.csv");
  const auto& t = run.probes.at("time");
  const double stage_start = run.scene.stages.front().duration;  // the load stage starts here
  while (t[run.i0] < stage_start - 1e-9) ++run.i0;
  run.y0 = run.probes.at("top_y")[run.i0 - 1];
  return run;
}
inline ConsolidationRun run_consolidation(const std::string& path, const std::string& name) {
  return run_consolidation(load_scene<2>(path), name);
}

/// RMS over 0..1 s after `origin` of the top disc's settlement against
/// final_settlement U(t - origin), as a fraction of final_settlement.
inline double settlement_rms(const ConsolidationRun& run, const SeepageColumnParameters& p, double origin,
                             double final_settlement) {
  const auto& t = run.probes.at("time");
  const auto& top = run.probes.at("top_y");
  double sq = 0.0;
  int n = 0;
  for (std::size_t j = run.i0; j < t.size() && t[j] - origin <= 1.0; ++j) {
    const double e = (run.y0 - top[j]) - final_settlement * consolidation_degree(p, t[j] - origin);
    sq += e * e;
    ++n;
  }
  return std::sqrt(sq / n) / final_settlement;
}

/// consolidation_sealed_piston.toml with each of `swaps` (text, its
/// replacement) made, run as run_consolidation does; `name` names its files.
inline ConsolidationRun run_sealed_piston_variant(
    const std::vector<std::pair<std::string, std::string>>& swaps, const std::string& name) {
  const std::string text = scene_variant("examples/fluid_cases/consolidation_sealed_piston.toml", swaps);
  const std::string dir = temp_dir(name + "_scene");
  std::filesystem::create_directories(dir);
  const std::string scene = dir + "/" + name + ".toml";
  std::ofstream(scene) << text;
  return run_consolidation(load_scene_file<2>(scene), name);
}

}  // namespace darcydem::testing
