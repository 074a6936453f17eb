#include "darcydem/analysis/seepage_column.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <stdexcept>

#include <fmt/format.h>

namespace darcydem {
namespace {

namespace fs = std::filesystem;

std::ofstream open_for_writing(const fs::path& p) {
  std::ofstream out(p);
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write", p.string()));
  return out;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

template <int D>
SeepageColumnAnalysis<D>::SeepageColumnAnalysis(SeepageColumnSpec spec, const Scene<D>& scene)
    : spec_(std::move(spec)) {
  std::sort(spec_.pressure_times.begin(), spec_.pressure_times.end());
  const auto& g = scene.fluid->grid;
  base_ = g.origin[D - 1];
  top_ = g.upper()[D - 1];
  area_ = 1.0;
  for (int k = 0; k < D - 1; ++k) area_ *= g.length(k);
  for (double r : scene.simulation.particles.radius) solid_volume_ += particle_volume<D>(r);
}

template <int D>
double SeepageColumnAnalysis<D>::column_top(const Scene<D>& scene) const {
  const auto& p = scene.simulation.particles;
  double t = -1e300;
  for (std::size_t i = 0; i < p.size(); ++i) t = std::max(t, p.position[i][D - 1] + p.radius[i]);
  return t;
}

template <int D>
void SeepageColumnAnalysis<D>::stage_started(const Scene<D>& scene, const std::string& stage) {
  if (stage == spec_.settle_stage) top_initial_ = column_top(scene);
  if (stage == spec_.inflow_stage) {
    inflow_active_ = true;
    t0_ = scene.simulation.time;
    top_at_inflow_ = column_top(scene);
    inflow_ = scene.fluid->sides[2 * (D - 1)].value.at(t0_);
    // The column's vertical permeability as the grid has it: layers in series.
    const auto& f = *scene.fluid;
    const auto& g = f.grid;
    const int layers = g.cells[D - 1];
    std::vector<double> layer_kappa(static_cast<std::size_t>(layers), 0.0);
    // The cells of a layer side by side (in parallel): their mean kappa,
    // weighted by their areas.
    for (std::size_t c = 0; c < g.size(); ++c) {
      const auto cc = g.coords(c);
      layer_kappa[cc[D - 1]] += f.permeability_field()[c][D - 1] * g.face_area(D - 1, cc) / area_;
    }
    double resistance = 0.0;
    for (int j = 0; j < layers; ++j) resistance += g.width(D - 1, j) / layer_kappa[j];
    kappa_effective_ = (top_ - base_) / resistance;
    sample_time_ = {0.0};
    sample_uplift_ = {0.0};
    next_sample_ = spec_.uplift_interval;
    next_profile_ = 0;
  }
}

template <int D>
void SeepageColumnAnalysis<D>::stage_ended(const Scene<D>& scene, const std::string& stage, bool completed) {
  if (stage == spec_.settle_stage) {
    top_settled_ = column_top(scene);
    settle_done_ = completed;
  }
  if (stage == spec_.inflow_stage) {
    inflow_active_ = false;
    inflow_done_ = completed;
  }
}

template <int D>
void SeepageColumnAnalysis<D>::after_step(const Scene<D>& scene) {
  if (!inflow_active_) return;
  const double dt = scene.simulation.time_step;
  const double t = scene.simulation.time - t0_;
  if (t >= next_sample_ - 0.5 * dt) {
    sample_time_.push_back(next_sample_);
    sample_uplift_.push_back(column_top(scene) - top_at_inflow_);
    next_sample_ += spec_.uplift_interval;
  }
  while (next_profile_ < spec_.pressure_times.size() && t >= spec_.pressure_times[next_profile_] - 0.5 * dt) {
    const auto& f = *scene.fluid;
    const auto& g = f.grid;
    Profile pr{spec_.pressure_times[next_profile_], t, {}, {}};
    const int layers = g.cells[D - 1];
    // Each layer's mean pressure, weighted by the cells' areas.
    std::vector<double> sum(static_cast<std::size_t>(layers), 0.0);
    std::vector<double> weight(static_cast<std::size_t>(layers), 0.0);
    for (std::size_t c = 0; c < g.size(); ++c) {
      const auto cc = g.coords(c);
      const double w = g.face_area(D - 1, cc);
      sum[cc[D - 1]] += w * f.pressure()[c];
      weight[cc[D - 1]] += w;
    }
    for (int j = layers - 1; j >= 0; --j) {
      const double centre = g.centre_at(D - 1, j);
      pr.depth.push_back(top_ - centre);
      pr.pressure.push_back(sum[j] / weight[j]);
    }
    profiles_.push_back(std::move(pr));
    ++next_profile_;
  }
}

template <int D>
SeepageColumnResult SeepageColumnAnalysis<D>::finish(const Scene<D>& scene, const std::string& out_dir,
                                                     std::ostream* log) {
  const auto& sim = scene.simulation;
  const auto& fluid = *scene.fluid;
  SeepageColumnResult res;
  res.complete = settle_done_ && inflow_done_;

  // Parameters measured in the settling stage.
  const double h0 = top_initial_ - base_;
  res.settlement = top_initial_ - top_settled_;
  res.initial_porosity = 1.0 - solid_volume_ / (area_ * h0);
  res.settled_porosity = 1.0 - solid_volume_ / (area_ * (top_settled_ - base_));
  double mass = 0.0;
  for (double im : sim.particles.inv_mass) mass += im > 0.0 ? 1.0 / im : 0.0;
  const double g = sim.gravity.norm() > 0.0 ? sim.gravity.norm() : standard_gravity;
  const double submerged_weight = (mass - fluid.fluid.density * solid_volume_) * g;  // N
  // Settlement under own submerged weight: s = m_v (W'/(A H)) H^2 / 2.
  SeepageColumnParameters& p = res.parameters;
  p.height = top_ - base_;
  p.inflow = inflow_;
  p.unit_weight = fluid.fluid.unit_weight();
  p.compressibility = 2.0 * res.settlement * area_ / (submerged_weight * h0);
  if (fluid.permeability.model == PermeabilityModel::kozeny_carman) {
    const double n =
        std::clamp(res.settled_porosity, fluid.permeability.min_porosity, fluid.permeability.max_porosity);
    res.kozeny_carman_conductivity = kozeny_carman(fluid.permeability.diameter, n) *
                                     fluid.permeability.anisotropy[D - 1] * p.unit_weight /
                                     fluid.fluid.viscosity;
  }
  // k of the column as the run has it: its cells' permeabilities in series.
  p.conductivity = kappa_effective_ * p.unit_weight / fluid.fluid.viscosity;
  p.fluid_storage = res.settled_porosity / fluid.fluid.bulk_modulus;
  SeepageColumnParameters incompressible = p;
  incompressible.fluid_storage = 0.0;

  // Errors over 0..1 s (or the whole stage if shorter).
  const double s_final = p.final_uplift();
  const double p_ref = p.steady_bottom_pressure();
  double sq = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < sample_time_.size(); ++i) {
    if (sample_time_[i] > 1.0 + 1e-9) break;
    const double e = sample_uplift_[i] - seepage_uplift(p, sample_time_[i]);
    sq += e * e;
    ++n;
  }
  res.uplift_rms_error = n > 0 ? std::sqrt(sq / n) / s_final : 0.0;
  for (const auto& pr : profiles_) {
    for (std::size_t j = 0; j < pr.depth.size(); ++j) {
      const double e = std::abs(pr.pressure[j] - seepage_pressure(p, pr.depth[j], pr.actual_time));
      res.pressure_max_error = std::max(res.pressure_max_error, e / p_ref);
    }
  }
  res.final_uplift_simulated = sample_uplift_.empty() ? 0.0 : sample_uplift_.back();
  res.complete = res.complete && profiles_.size() == spec_.pressure_times.size();
  res.passed = res.complete && res.uplift_rms_error <= spec_.uplift_tolerance &&
               res.pressure_max_error <= spec_.pressure_tolerance;

  // Files.
  const fs::path out = out_dir;
  {
    auto f = open_for_writing(out / "uplift.csv");
    f << "time,uplift\n";
    for (std::size_t i = 0; i < sample_time_.size(); ++i)
      f << fmt::format("{:.6g},{:.10g}\n", sample_time_[i], sample_uplift_[i]);
  }
  {
    auto f = open_for_writing(out / "pressure.csv");
    f << "time,depth,pressure\n";
    for (const auto& pr : profiles_) {
      for (std::size_t j = 0; j < pr.depth.size(); ++j)
        f << fmt::format("{:.6g},{:.10g},{:.10g}\n", pr.nominal_time, pr.depth[j], pr.pressure[j]);
    }
  }
  {
    auto f = open_for_writing(out / "uplift_analytic.csv");
    f << "time,uplift,uplift_incompressible\n";
    const double t_end = sample_time_.empty() ? 1.0 : sample_time_.back();
    for (int i = 0; i <= 1000; ++i) {
      const double t = t_end * i / 1000.0;
      f << fmt::format("{:.6g},{:.10g},{:.10g}\n", t, seepage_uplift(p, t),
                       seepage_uplift(incompressible, t));
    }
  }
  {
    auto f = open_for_writing(out / "pressure_analytic.csv");
    f << "time,depth,pressure\n";
    for (const auto& pr : profiles_) {
      for (double d : pr.depth)
        f << fmt::format("{:.6g},{:.10g},{:.10g}\n", pr.nominal_time, d,
                         seepage_pressure(p, d, pr.actual_time));
    }
  }
  const std::string verdict = res.passed ? "PASS" : (res.complete ? "FAIL" : "INCOMPLETE");
  {
    auto f = open_for_writing(out / "report.md");
    f << fmt::format("# Seepage column: {}\n\n", scene.file);
    f << fmt::format("Fluid bulk modulus K_f = {:.4g} Pa. Verdict: **{}**.\n\n", fluid.fluid.bulk_modulus,
                     verdict);
    f << "## Stage 1: settling under gravity and buoyancy (measured)\n\n";
    f << "| quantity | this run | paper |\n|---|---|---|\n";
    f << fmt::format("| settlement | {:.4f} mm | 0.16 mm |\n", res.settlement * 1e3);
    f << fmt::format("| m_v from the settlement | {:.4e} 1/Pa | 1.012e-5 1/Pa |\n", p.compressibility);
    f << fmt::format("| initial porosity | {:.4f} | 0.2146 |\n", res.initial_porosity);
    f << fmt::format("| settled porosity | {:.4f} | 0.2121 |\n", res.settled_porosity);
    f << fmt::format("| k, Kozeny-Carman at the settled porosity | {:.4e} m/s | 0.001 m/s |\n",
                     res.kozeny_carman_conductivity);
    f << fmt::format("| k of the grid's cells in series (used below) | {:.4e} m/s | |\n", p.conductivity);
    f << fmt::format("| Cv = k/(gw (m_v + n/K_f)) | {:.5f} m^2/s | |\n", p.consolidation_coefficient());
    f << fmt::format("| Cv0 = k/(gw m_v) | {:.5f} m^2/s | 0.01008 |\n\n",
                     incompressible.consolidation_coefficient());
    f << "## Stage 2: inflow at the bottom\n\n";
    f << fmt::format("Inflow q = {:.4g} m/s, column H = {:.4g} m.\n\n", p.inflow, p.height);
    f << "| quantity | simulated | analytical | \n|---|---|---|\n";
    f << fmt::format("| final uplift | {:.5f} mm | {:.5f} mm (steady) |\n", res.final_uplift_simulated * 1e3,
                     s_final * 1e3);
    f << fmt::format("| steady bottom pressure | | {:.2f} Pa |\n\n", p_ref);
    f << "| error | value | tolerance |\n|---|---|---|\n";
    f << fmt::format("| RMS uplift error over 0..1 s / final uplift | {:.3f} % | {:.1f} % |\n",
                     100 * res.uplift_rms_error, 100 * spec_.uplift_tolerance);
    f << fmt::format("| max pressure error / steady bottom pressure | {:.3f} % | {:.1f} % |\n\n",
                     100 * res.pressure_max_error, 100 * spec_.pressure_tolerance);
    f << "Uplift samples (mm):\n\n| t (s) | simulated | analytical (storage m_v + n/K_f) | paper's "
         "(incompressible) |\n|---|---|---|---|\n";
    for (double t : {0.01, 0.05, 0.1, 0.2, 0.5, 1.0}) {
      auto it = std::find_if(sample_time_.begin(), sample_time_.end(),
                             [&](double s) { return std::abs(s - t) < 1e-9; });
      if (it == sample_time_.end()) continue;
      const double sim_s = sample_uplift_[static_cast<std::size_t>(it - sample_time_.begin())];
      f << fmt::format("| {} | {:.4f} | {:.4f} | {:.4f} |\n", t, sim_s * 1e3, seepage_uplift(p, t) * 1e3,
                       seepage_uplift(incompressible, t) * 1e3);
    }
    f << "\nFiles: uplift.csv, pressure.csv (simulated), uplift_analytic.csv, pressure_analytic.csv, "
         "uplift.png, pressure.png.\n";
  }
  {
    auto f = open_for_writing(out / "seepage.json");
    f << "{\n"
      << fmt::format("  \"bulk_modulus\": {:.17g},\n", fluid.fluid.bulk_modulus)
      << fmt::format("  \"settlement\": {:.17g},\n", res.settlement)
      << fmt::format("  \"compressibility\": {:.17g},\n", p.compressibility)
      << fmt::format("  \"initial_porosity\": {:.17g},\n", res.initial_porosity)
      << fmt::format("  \"settled_porosity\": {:.17g},\n", res.settled_porosity)
      << fmt::format("  \"conductivity\": {:.17g},\n", p.conductivity)
      << fmt::format("  \"height\": {:.17g},\n", p.height)
      << fmt::format("  \"inflow\": {:.17g},\n", p.inflow)
      << fmt::format("  \"final_uplift_analytic\": {:.17g},\n", s_final)
      << fmt::format("  \"steady_bottom_pressure\": {:.17g},\n", p_ref)
      << fmt::format("  \"uplift_rms_error\": {:.17g},\n", res.uplift_rms_error)
      << fmt::format("  \"pressure_max_error\": {:.17g},\n", res.pressure_max_error)
      << fmt::format("  \"verdict\": \"{}\"\n", verdict) << "}\n";
  }
  if (log != nullptr) {
    *log << fmt::format(
        "seepage column: settlement {:.4f} mm, m_v {:.4e} 1/Pa, n {:.4f}, k {:.4e} m/s; uplift RMS error "
        "{:.3f} % "
        "(<= {:.1f} %), pressure max error {:.3f} % (<= {:.1f} %): {}\n",
        res.settlement * 1e3, p.compressibility, res.settled_porosity, p.conductivity,
        100 * res.uplift_rms_error, 100 * spec_.uplift_tolerance, 100 * res.pressure_max_error,
        100 * spec_.pressure_tolerance, verdict);
  }
  if (spec_.plots && sample_time_.size() > 1) {
    const char* scripts = std::getenv("DARCYDEM_SCRIPTS_DIR");
    const char* python = std::getenv("DARCYDEM_PYTHON");
    const std::string script =
        std::string(scripts != nullptr ? scripts : DARCYDEM_SCRIPTS_DIR) + "/plot_seepage.py";
    const std::string cmd =
        fmt::format("{} {} {}", shell_quote(python != nullptr ? python : "/usr/bin/python3"),
                    shell_quote(script), shell_quote(out.string()));
    const int rc = std::system(cmd.c_str());
    if (rc != 0 && log != nullptr) {
      *log << fmt::format(
          "warning: the plots were not made ({} returned {}); the CSV files and report.md are "
          "written. Install python3-matplotlib (scripts/install-deps.sh).\n",
          cmd, rc);
    }
  }
  return res;
}

template class SeepageColumnAnalysis<2>;
template class SeepageColumnAnalysis<3>;

}  // namespace darcydem
