// Contact bonds with the pore fluid: a cemented bed heaved by upward
// seepage (examples/fluid_cases/cemented_bed_heave.toml). Checked against
// the force balance derived by hand: the bed lifts off its base when the
// water's uplift on it passes its submerged weight plus the tensile
// strength of the bonds that tie it to the base.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "darcydem/simulation/runner.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

namespace darcydem {
namespace {

// The example: 45 free discs (d = 1 mm, 5 columns x 9 rows, per metre of
// thickness) on a fixed row, every touching pair bonded with tensile
// strength T = 0.1 N/m; one disc per cell of 1 mm and a constant
// permeability, so at steady flow the excess pressure falls linearly from
// u_b at the bottom of the grid (y = 0) to 0 at its drained top (y = 10 mm)
// and the water pushes the free bed (y > 1 mm) up by u_b 9/10 x W, W = 5 mm.
// Its five bonds to the base hold until that uplift minus the submerged
// weight W' reaches 5 T:
//   u_c = (W' + 5 T) / (0.9 W),  W' = 45 m (1 - rho_f / rho_s) g.
TEST(FluidBonds, CementedBedHeavesWhenTheUpliftPassesItsWeightAndTheBondsStrength) {
  const std::string dir = testing::temp_dir("cemented_bed_heave");
  const RunSummary summary = testing::run_example<2>("examples/fluid_cases/cemented_bed_heave.toml", dir);
  ASSERT_FALSE(summary.interrupted);
  ASSERT_EQ(summary.stages_completed.size(), 2U);

  const double r = 0.5e-3;
  const double volume = std::numbers::pi * r * r;  // m^3 per metre
  const double m = 2650.0 * volume;
  const double g = 9.81;
  const double submerged = 45.0 * m * (1.0 - 1000.0 / 2650.0) * g;  // 0.5721 N/m
  const double buoyancy = 45.0 * 1000.0 * volume * g;               // 0.3467 N/m
  const double strength = 5.0 * 0.1;                                // the base's bonds, N/m
  const double width = 5e-3;
  const double u_c = (submerged + strength) / (0.9 * width);  // 238.24 Pa
  EXPECT_NEAR(u_c, 238.24, 0.01);                             // the example's comment

  const auto probes = testing::read_probes(dir + "/probes.csv");
  const auto& u_b = probes.at("bottom_pressure");
  const auto& uplift = probes.at("uplift");
  const auto& height = probes.at("bed_height");
  const auto& bonds = probes.at("bonds");
  const auto& broken = probes.at("broken");
  // The first probe row (0.2 ms, 0.8 Pa of the ramp apart) after the base's
  // bonds broke: all five in that interval, the bed's other 76 bonds whole.
  std::size_t first = 0;
  while (first < broken.size() && broken[first] == 0.0) ++first;
  ASSERT_LT(first, broken.size()) << "no bond broke";
  ASSERT_GT(first, 0U);
  EXPECT_EQ(broken[first], 5.0);
  EXPECT_EQ(bonds[first], 76.0);
  EXPECT_EQ(broken.back(), 5.0);
  EXPECT_EQ(bonds.back(), 76.0);
  // The breaking pressure lies between the two rows' bottom pressures.
  // Bound 2e-3 of u_c beyond them: the bed is quasi-static (the pressure's
  // departure from linear, from the grains' creep as the bonds stretch, is
  // about 1e-4; a bond stretches 1e-7 m before it breaks) and the ramp
  // moves about 0.01 Pa per step.
  EXPECT_GT(u_c, u_b[first - 1] - 2e-3 * u_c) << "broke at " << u_b[first - 1] << " to " << u_b[first];
  EXPECT_LT(u_c, u_b[first] + 2e-3 * u_c) << "broke at " << u_b[first - 1] << " to " << u_b[first];
  // Just before, the water's force on the free bed is its buoyancy plus the
  // drop of the excess pressure across it (the steady Darcy balance), within
  // 1e-3 (the same departure from steady, linear flow).
  const double seepage = 0.9 * width * u_b[first - 1];
  EXPECT_NEAR(uplift[first - 1] - buoyancy, seepage, 1e-3 * seepage);
  // Then it lifts off as one block: the stage ends when its mean height has
  // risen 1 mm (from 5.5 mm); the bonds within it hold.
  EXPECT_GT(height.back(), 6.5e-3);
  EXPECT_LT(height[first - 1], 5.51e-3);
}

}  // namespace
}  // namespace darcydem
