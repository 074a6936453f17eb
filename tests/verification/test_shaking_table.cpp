// A saturated loose bed on a shaking table (examples/fluid_cases/
// shaking_table.toml): 300 discs, 28 mm deep, shaken horizontally at 10 Hz
// and 0.5 g for 0.8 s, then left to drain. Terzaghi's principle holds
// through it (the table carries the submerged weight less the excess pore
// pressure's thrust), the pore pressure stays below the effective stress
// it can take away and reaches it near the surface (liquefaction), and
// after the shaking the water drains up through the surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

TEST(ShakingTable, TheTableCarriesTheSubmergedWeightLessTheWatersThrustAndTheTopLiquefies) {
  const std::string out = darcydem::testing::temp_dir("shaking_table");
  auto scene = darcydem::testing::load_scene<2>("examples/fluid_cases/shaking_table.toml");
  // The submerged weight, by hand from the discs' radii, N per metre.
  double area = 0.0;
  for (const double r : scene.simulation.particles.radius) area += std::numbers::pi * r * r;
  const double weight = area * (2650.0 - 1000.0) * 9.81;
  const double width = 0.01;
  RunOptions options;
  options.out_dir = out;
  ASSERT_FALSE(run_scene<2>(scene, options).interrupted);
  const auto probes = darcydem::testing::read_probes(out + "/probes.csv");
  const auto& t = probes.at("time");
  // What the table carries, the grains' push on it plus the excess pore
  // pressure on it: the bed's submerged weight.
  auto total = [&](std::size_t j) {
    return -probes.at("floor_load")[j] + probes.at("base_pressure")[j] * width;
  };
  const double rest_end = 0.1, shake_end = 0.9;
  // At rest in still water (the bed made under the gravity it feels
  // there): bound 1 %. The base pressure is the bottom cell's, at its
  // centre 1 mm up, and the bed has had 0.1 s to settle onto its springs in
  // the water. Measured: 0.43 %.
  std::size_t j = 0;
  while (t[j + 1] <= rest_end + 1e-9) ++j;
  EXPECT_NEAR(total(j) / weight, 1.0, 1e-2);
  // Each shaking cycle, on average (20 probe rows a cycle): the bed's
  // vertical momentum comes back each cycle, so the grains' inertia
  // averages out, and the base pressure is taken 1 mm up, where the
  // seepage's gradient differs from the base's by about 0.4 % of the
  // weight (as after the shaking, below). Bound 2 %; measured 0.61 %.
  // The pore pressure over the effective stress it starts from, r_u = u /
  // sigma'_v0, sigma'_v0 the submerged weight above each probe (the bed's
  // height from its grains' mean height, as if of uniform porosity): it
  // cannot exceed 1 by much on a cycle's average (the water would carry
  // more than the grains above weigh, and heave them): bound 1.1, measured
  // at most 0.89. Near the surface (3 and 9 mm deep) over the last three
  // cycles it passes 0.7: the sand there has liquefied (measured 0.80 to
  // 0.89; a bed whose water drained freely, or without Biot's source,
  // would stay near 0: with k = 1e-2 m/s, 0.02).
  const double height = 2.0 * probes.at("bed_height")[0];
  const double ys[5] = {0.001, 0.007, 0.013, 0.019, 0.025};
  double worst_total = 0.0, highest_ru = 0.0, lowest_top_ru = 1e9;
  for (int cycle = 0; cycle < 8; ++cycle) {
    const double from = rest_end + 0.1 * cycle, to = from + 0.1;
    double sum = 0.0;
    double ru[5] = {};
    int count = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (t[i] <= from + 1e-9 || t[i] > to + 1e-9) continue;
      sum += total(i);
      for (int k = 0; k < 5; ++k) ru[k] += probes.at("u_" + std::to_string(k))[i];
      ++count;
    }
    ASSERT_GE(count, 19);
    worst_total = std::max(worst_total, std::abs(sum / count / weight - 1.0));
    for (int k = 0; k < 5; ++k) {
      const double effective = weight / width * (height - ys[k]) / height;
      ru[k] /= count * effective;
      highest_ru = std::max(highest_ru, ru[k]);
      if (cycle >= 5 && k >= 3) lowest_top_ru = std::min(lowest_top_ru, ru[k]);
    }
    std::printf(
        "cycle %d: the table's load %.4f of the submerged weight; r_u at 27, 21, 15, 9, 3 mm deep: "
        "%.2f %.2f %.2f %.2f %.2f\n",
        cycle + 1, sum / count / weight, ru[0], ru[1], ru[2], ru[3], ru[4]);
  }
  EXPECT_LT(worst_total, 2e-2);
  EXPECT_LT(highest_ru, 1.1);
  EXPECT_GT(lowest_top_ru, 0.7);
  // Reconsolidation, from 0.2 s after the table stops (the bed rings for
  // 0.1-0.15 s, its free vibration undamped): the water drains up through
  // the surface (out at every row), the base pressure falls over every
  // 0.05 s, and the table carries the weight less the water's thrust at
  // every row, not only on average: bound 1 % (the bottom cell's centre
  // sits above the base by half a cell, where the draining water's
  // gradient, 1.4 kPa/m by hand from the profile, gives 1.4 Pa of the 380
  // Pa: 0.36 %). Measured: at most 0.3 %. The bed settles.
  std::size_t k = 0;
  while (t[k] <= shake_end + 0.2 + 1e-9) ++k;
  double worst_after = 0.0;
  for (std::size_t i = k; i < t.size(); ++i) {
    worst_after = std::max(worst_after, std::abs(total(i) / weight - 1.0));
    EXPECT_LT(probes.at("outflow")[i], 0.0) << "t = " << t[i];
    if (t[i] >= t[k] + 0.05 - 1e-9) {
      EXPECT_LT(probes.at("base_pressure")[i], probes.at("base_pressure")[i - 10]) << "t = " << t[i];
    }
  }
  EXPECT_LT(worst_after, 1e-2);
  EXPECT_LT(probes.at("bed_height").back(), probes.at("bed_height")[j]);
  // The water balance: round-off, of the 2.5e-7 m^2 per metre that leaves.
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_LT(std::abs(probes.at("fluid_balance")[i]), 1e-15);
  std::printf(
      "shaking table: at rest %.4f, shaking cycles within %.4f, draining within %.4f of the submerged "
      "weight %.4f N/m; base pressure %.1f Pa at the end of the shaking, %.1f Pa at the end\n",
      total(j) / weight, worst_total, worst_after, weight, probes.at("base_pressure")[k],
      probes.at("base_pressure").back());
}
