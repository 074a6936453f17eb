// Kozeny-Carman's default diameter for grains of several sizes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "darcydem/fluid/fluid_laws.hpp"

namespace darcydem {
namespace {

TEST(FluidLaws, SpecificSurfaceDiameterOfEqualGrainsIsTheirs) {
  const std::vector<double> radius(7, 0.00045);
  EXPECT_DOUBLE_EQ(specific_surface_diameter<2>(radius), 0.0009);
  EXPECT_DOUBLE_EQ(specific_surface_diameter<3>(radius), 0.0009);
  EXPECT_EQ(specific_surface_diameter<3>({}), 0.0);
}

TEST(FluidLaws, SpecificSurfaceDiameterOfTwoSizesByHand) {
  // d = 1 and 2 mm: sum d^3 / sum d^2 = 9/5 mm in 3D, sum d^2 / sum d =
  // 5/3 mm in 2D; the arithmetic mean would be 1.5 mm.
  const std::vector<double> radius{0.0005, 0.001};
  EXPECT_NEAR(specific_surface_diameter<3>(radius), 1.8e-3, 1e-15);
  EXPECT_NEAR(specific_surface_diameter<2>(radius), 5.0e-3 / 3.0, 1e-15);
}

TEST(FluidLaws, ErgunBalanceDiameterOfTwoSizesByHand) {
  // Ergun's viscous drag on a grain goes as V_p / d_p^2: d = 1 and 2 mm
  // spheres give d^2 = (1 + 8) / (1 + 2) = 3 mm^2, so sqrt(3) mm, below
  // the specific-surface 1.8 mm; discs d^2 = (1 + 4) / 2 = 2.5 mm^2. Equal
  // grains: their own diameter.
  const std::vector<double> radius{0.0005, 0.001};
  EXPECT_NEAR(ergun_balance_diameter<3>(radius), std::sqrt(3.0) * 1e-3, 1e-15);
  EXPECT_NEAR(ergun_balance_diameter<2>(radius), std::sqrt(2.5) * 1e-3, 1e-15);
  EXPECT_DOUBLE_EQ(ergun_balance_diameter<3>(std::vector<double>(5, 0.00045)), 0.0009);
  EXPECT_EQ(ergun_balance_diameter<2>({}), 0.0);
}

TEST(FluidLaws, SpecificSurfaceDiameterHasTheMixturesSurfacePerVolume) {
  // Equal grains of diameter d have surface / volume 6/d (spheres) and
  // 4/d (discs); the mixture's, summed from each grain's area and volume,
  // must be that of its diameter. Round-off only: 1e-12.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> size(0.0001, 0.001);
  std::vector<double> radius(500);
  for (double& r : radius) r = size(rng);
  constexpr double pi = std::numbers::pi;
  double area3 = 0.0, volume3 = 0.0, perimeter2 = 0.0, area2 = 0.0;
  for (double r : radius) {
    area3 += 4.0 * pi * r * r;
    volume3 += 4.0 / 3.0 * pi * r * r * r;
    perimeter2 += 2.0 * pi * r;
    area2 += pi * r * r;
  }
  EXPECT_NEAR(6.0 / specific_surface_diameter<3>(radius), area3 / volume3, 1e-12 * area3 / volume3);
  EXPECT_NEAR(4.0 / specific_surface_diameter<2>(radius), perimeter2 / area2, 1e-12 * perimeter2 / area2);
}

}  // namespace
}  // namespace darcydem
