// The 3D oedometer (examples/fluid_cases/oedometer.toml): Terzaghi's 1D
// consolidation of a random packing of 850 spheres, run as a user runs it,
// against the closed form with the drained stiffness that the same load
// step gives when the water leaves at once (the same scene with a
// permeability 1000 times larger).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "darcydem/analysis/seepage_analytic.hpp"
#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

namespace {

/// oedometer.toml with each of `swaps` made (its bed file by its full
/// path, as the variant is written elsewhere), run; its probes, and the
/// first row of the load stage.
struct OedometerRun {
  Scene<3> scene;
  std::map<std::string, std::vector<double>> probes;
  std::size_t i0 = 0;
};
OedometerRun run_oedometer(std::vector<std::pair<std::string, std::string>> swaps, const std::string& name) {
  swaps.emplace_back("file = \"oedometer_bed.csv\"", "file = \"" + std::string(DARCYDEM_SOURCE_DIR) +
                                                         "/examples/fluid_cases/oedometer_bed.csv\"");
  const std::string dir = darcydem::testing::temp_dir(name + "_scene");
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/oedometer.toml";
  std::ofstream(path) << darcydem::testing::scene_variant("examples/fluid_cases/oedometer.toml", swaps);
  OedometerRun run{darcydem::testing::load_scene_file<3>(path), {}, 0};
  RunOptions options;
  options.out_dir = darcydem::testing::temp_dir(name);
  run_scene(run.scene, options);
  run.probes = darcydem::testing::read_probes(options.out_dir + "/probes.csv");
  const auto& t = run.probes.at("time");
  const double load_start = run.scene.stages.front().duration;
  while (t[run.i0] < load_start - 1e-9) ++run.i0;
  return run;
}

}  // namespace

TEST(FluidScenes, OedometerFollowsTerzaghi) {
  // The bed rests under the platen's 1 kPa (0.036 N on 6 x 6 mm), then
  // the servo raises the load to 2 kPa. Grid: 16 layers of 1.05 mm, sealed
  // floor, drained top at H = 16.8 mm, constant k = 2e-4 m/s, K_f = 2e5 Pa.
  //
  // Expected, independent of the coupled run: the drained twin (k x 1000,
  // the water leaves at once) gives the skeleton's settlement S_d under the
  // step, so m_v = S_d / (H_bed dsigma) with H_bed the platen's height; then
  // Terzaghi with the storage m_v + n/K_f (n: the bed's porosity at the
  // step): the settlement S_d U(Tv), U including the immediate (1 - B) part
  // (consolidation_degree), and the floor's pressure (the probe at the
  // bottom cells' centre, 0.525 mm up) consolidation_pressure, B = m_v /
  // (m_v + n/K_f).
  //
  // Tolerances. Terzaghi's skeleton is linear elastic; the packing is not
  // quite: contacts open and close and spheres roll (friction 10 only
  // keeps them from sliding), so its stiffness depends on the path. The
  // drained twin loaded slowly (the servo at 2 mm/s) settles 1.3 % less
  // (44.06 against 44.62 um, session 25), and the coupled run, whose
  // effective stress grows from the top down, fits c_v 10 % above the twin's
  // best (floor pressure RMS 1.5 % instead of 3.3 %). So: RMS of the
  // settlement and of the floor's pressure over the load stage, 5 % of S_d
  // and of B dsigma (measured 3.0 % and 3.3 %); the final settlement 1.5 %
  // of S_d. Ignoring the water's compressibility (B = 1) misses both by
  // more than that (5.9 % and 7.1 %), checked below so that this test
  // resolves the storage term. Fluid volume balance: to round-off.
  const double area = 0.006 * 0.006;
  const double dsigma = (0.072 - 0.036) / area;  // the servo's targets, N, over the platen
  const auto drained = run_oedometer(
      {{"hydraulic_conductivity = [2e-4, 2e-4, 2e-4]", "hydraulic_conductivity = [0.2, 0.2, 0.2]"},
       {"name = \"load\"\nduration = 0.15", "name = \"load\"\nduration = 0.05"}},
      "oedometer_drained");
  const auto run = run_oedometer({}, "oedometer");
  const auto& pd = drained.probes;
  const double s_drained = pd.at("platen_z")[drained.i0 - 1] - pd.at("platen_z").back();

  const auto& f = *run.scene.fluid;
  const auto& pr = run.probes;
  const auto& t = pr.at("time");
  const std::size_t i0 = run.i0;
  const double t0 = t[i0 - 1];
  const double z0 = pr.at("platen_z")[i0 - 1];
  SeepageColumnParameters p;
  p.height = f.grid.upper().z() - f.grid.origin.z();
  p.unit_weight = f.fluid.unit_weight();
  p.conductivity = f.permeability_field()[0].z() * p.unit_weight / f.fluid.viscosity;
  p.compressibility = s_drained / (z0 * dsigma);
  p.fluid_storage = pr.at("porosity")[i0 - 1] / f.fluid.bulk_modulus;
  const double b = p.compressibility / (p.compressibility + p.fluid_storage);
  const double probe_depth = p.height - 0.000525;  // from the drained top

  // RMS errors of the settlement and the floor's pressure over the stage,
  // against the closed form with the storage `storage` (1/Pa).
  auto rms_errors = [&](double storage) {
    SeepageColumnParameters q = p;
    q.fluid_storage = storage;
    const double bq = q.compressibility / (q.compressibility + q.fluid_storage);
    double settle = 0.0;
    double pressure = 0.0;
    int n_settle = 0;
    int n_pressure = 0;
    for (std::size_t j = i0; j < t.size(); ++j) {
      const double time = t[j] - t0;
      const double e = (z0 - pr.at("platen_z")[j]) - s_drained * consolidation_degree(q, time);
      settle += e * e;
      ++n_settle;
      // From 5 ms: the servo first brings the load up (95 % of the step at
      // 5 ms), while the closed form takes it at once.
      if (time < 0.005) continue;
      const double u = pr.at("floor_pressure")[j] - consolidation_pressure(q, dsigma, probe_depth, time);
      pressure += u * u;
      ++n_pressure;
    }
    return std::pair{std::sqrt(settle / n_settle) / s_drained,
                     std::sqrt(pressure / n_pressure) / (bq * dsigma)};
  };
  const auto [rms_settle, rms_pressure] = rms_errors(p.fluid_storage);
  const auto [rms_settle_rigid, rms_pressure_rigid] = rms_errors(0.0);
  const double s_final = z0 - pr.at("platen_z").back();
  const double s_expected = s_drained * consolidation_degree(p, t.back() - t0);
  std::printf(
      "oedometer: drained S_d %.3f um, m_v %.4e 1/Pa, n %.4f, B %.4f, c_v %.4e m^2/s; final %.3f um "
      "(expected %.3f); RMS settlement %.2f %% of S_d, floor pressure %.2f %% of B dsigma (B = 1: %.2f %%, "
      "%.2f %%)\n",
      s_drained * 1e6, p.compressibility, pr.at("porosity")[i0 - 1], b, p.consolidation_coefficient(),
      s_final * 1e6, s_expected * 1e6, 100.0 * rms_settle, 100.0 * rms_pressure, 100.0 * rms_settle_rigid,
      100.0 * rms_pressure_rigid);
  EXPECT_LT(rms_settle, 0.05);
  EXPECT_LT(rms_pressure, 0.05);
  EXPECT_NEAR(s_final, s_expected, 0.015 * s_drained);
  EXPECT_GT(std::max(rms_settle_rigid, rms_pressure_rigid), 0.05);
  // The water squeezed out of the bed, A S_d = 1.6e-9 m^3, is accounted
  // for to round-off (measured 1e-22 m^3).
  EXPECT_LT(std::abs(pr.at("fluid_balance").back()), 1e-9 * area * s_drained);
}
