// The B check of a triaxial test (examples/fluid_cases/undrained_cell.toml):
// a cubic lattice of 3 x 3 x 3 frictionless spheres sealed in a cell of six
// plane platens that displace the pore water, each a stress servo on its
// total load, grains plus water; then drained through the top.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

TEST(UndrainedCell, TakesSkemptonsBAndDrainsToTheSkeleton) {
  // Expected, by hand (independent of the run): with incompressible grains,
  // Biot's B = 1 / (1 + n K_d / K_f). The lattice's porosity is the box's
  // less the spheres', n = 1 - pi / 6; its drained bulk modulus: along each
  // axis N columns of N spheres, each N + 1 contacts in series, so a
  // stress sigma' shortens a side 2 r N by (N + 1) sigma' (2 r)^2 / k_n and
  // K_d = N k_n / (6 (N + 1) r) = 250 kPa (N = 3, r = 0.5 mm, k_n = 1e3
  // N/m); K_f = 119 kPa, so B = 0.49979. Sealed and loaded by 100 Pa all
  // round, the water takes u = B 100 Pa everywhere and the skeleton the
  // rest: each side shortened by (N + 1) (1 - B) 100 Pa (2 r)^2 / k_n.
  // Drained through the top (c_v / H^2 about 1e6 1/s), u falls to 0 and
  // each side shortens by (N + 1) 100 Pa (2 r)^2 / k_n = 0.4 um.
  // Tolerances: the pressure 1e-3 of B dsigma (the servo's residual, 1e-4
  // of the load, and the geometry's change, strains of 1e-4; measured
  // 2.2e-5); the squeezes 1e-3 of theirs (the servos take the stress over
  // the present cross-section, 2.7e-4 smaller than the first; measured
  // 1.4e-4 and 2.7e-4). Before session 46 the platens' solids were summed,
  // so that where they meet at the cell's edges their overlap counted
  // twice, and each took the water's thrust over the grid's whole face:
  // B was then 1.2e-5 off the other way, the undrained squeeze 2.5e-4; the pressure uniform to 1e-6 of it,
  // undrained; the drained pressure below 1e-4 of the load. Before session 45 a platen's first 1e-5 of a cell
  // of motion into the grid displaced no water (the face of its solid was held there): then u came out 5 %
  // low (47.48 Pa); now that sliver shrinks as the plane crosses the first layer.
  const std::string out = darcydem::testing::temp_dir("undrained_cell");
  ASSERT_FALSE(
      darcydem::testing::run_example<3>("examples/fluid_cases/undrained_cell.toml", out).interrupted);
  const auto probes = darcydem::testing::read_probes(out + "/probes.csv");
  const auto& t = probes.at("time");

  const int n = 3;
  const double r = 0.0005, kn = 1e3, kf = 1.19e5, load = 100.0;
  const double porosity = 1.0 - std::numbers::pi / 6.0;
  const double k_drained = n * kn / (6.0 * (n + 1) * r);
  const double b = 1.0 / (1.0 + porosity * k_drained / kf);
  auto squeeze_under = [&](double effective) { return (n + 1) * effective * 4.0 * r * r / kn; };
  auto side = [&](const char* axis, std::size_t j) {
    return probes.at(std::string(axis) + "_high_" + axis)[j] -
           probes.at(std::string(axis) + "_low_" + axis)[j];
  };
  // The undrained stage's end (it lasts 0.05 s) and the run's end.
  std::size_t end_undrained = 0;
  while (t[end_undrained + 1] <= 0.05 - 1e-9) ++end_undrained;
  const std::size_t last = t.size() - 1;

  const double u = probes.at("centre_pressure")[end_undrained];
  const double u_corner = probes.at("corner_pressure")[end_undrained];
  const double squeeze_z = 2.0 * n * r - side("z", end_undrained);
  const double squeeze_x = 2.0 * n * r - side("x", end_undrained);
  const double drained_z = 2.0 * n * r - side("z", last);
  std::printf(
      "undrained cell: B = %.6f (closed form %.6f); the sides shortened by %.6e and %.6e m (closed form "
      "%.6e); drained: u = %.2e Pa, the side by %.6e m (closed form %.6e)\n",
      u / load, b, squeeze_z, squeeze_x, squeeze_under((1.0 - b) * load), probes.at("centre_pressure")[last],
      drained_z, squeeze_under(load));
  EXPECT_NEAR(u / (b * load), 1.0, 1e-3);
  EXPECT_NEAR(u_corner / u, 1.0, 1e-6);
  EXPECT_NEAR(squeeze_z / squeeze_under((1.0 - b) * load), 1.0, 1e-3);
  EXPECT_NEAR(squeeze_x / squeeze_under((1.0 - b) * load), 1.0, 1e-3);
  EXPECT_LT(std::abs(probes.at("centre_pressure")[last]), 1e-4 * load);
  EXPECT_NEAR(drained_z / squeeze_under(load), 1.0, 1e-3);
}

TEST(UndrainedCell, OneSealedCellLeavesTheWatersStiffnessOutOfTheStep) {
  // A grid of one cell never drained keeps a uniform pressure: every
  // face's gradient is zero (no flow) or a flux's own, so no grain feels
  // the water's stiffness and the critical step is the contacts' (the
  // drag's relaxation time, rho_s (1 - n) / (n^2 mu / kappa), is 1e-3 s
  // here, far above). The CU triaxial test of 500 spheres: K_f = 2.2 GPa,
  // one cell, drained only through a [[fluid.source]].
  const std::string path = "examples/fluid_cases/undrained_triaxial_packing.toml";
  const auto sealed = darcydem::testing::load_scene<3>(path);
  const double dry = sealed.simulation.critical_time_step();
  EXPECT_TRUE(sealed.fluid->uniform_pressure);
  EXPECT_NEAR(sealed.critical_time_step / dry, 1.0, 1e-12);  // 1/sqrt(1/dt^2): round-off only
  EXPECT_NEAR(sealed.simulation.time_step, 0.2 * dry, 1e-12 * dry);
  // Drained through a side in any stage, or split in two cells, its
  // pressure varies and the water's undrained stiffness counts again:
  // (K_f/n) A/h against the lightest sphere brings the step to 3.0e-7 s,
  // 0.09 of the contacts'.
  const auto drained = darcydem::testing::scene_from_text<3>(
      darcydem::testing::temp_dir("one_cell_drained"), "scene.toml",
      darcydem::testing::scene_variant(
          path, {{"[stage.fluid.sources]\ndrainage = { pressure = 0.0 }",
                  "[stage.fluid.boundary]\nz_max = { type = \"drained\", pressure = 0.0 }\n"
                  "[stage.fluid.sources]\ndrainage = { pressure = 0.0 }"}}));
  EXPECT_FALSE(drained.fluid->uniform_pressure);
  EXPECT_LT(drained.critical_time_step, 0.2 * dry);
  const auto split = darcydem::testing::scene_from_text<3>(
      darcydem::testing::temp_dir("one_cell_split"), "scene.toml",
      darcydem::testing::scene_variant(path, {{"cells = [1, 1, 1]", "cells = [1, 1, 2]"}}));
  EXPECT_FALSE(split.fluid->uniform_pressure);
  EXPECT_LT(split.critical_time_step, 0.2 * dry);
}
