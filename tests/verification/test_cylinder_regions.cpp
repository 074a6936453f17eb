// Cylinders that a random cloud or an inlet fills instead of a box (a
// mould, a triaxial cell): every grain wholly inside, placed uniformly
// (checked against the moments of the uniform distribution over the
// region of allowed centres), none overlapping; a cloud to a porosity
// takes the cylinder's volume; a scene's cloud fills a cylinder wall to its
// rim, and an inlet rains into it without touching it.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "darcydem/generation/generators.hpp"
#include "darcydem/generation/inlet.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

namespace {

/// Distance of x from the cylinder's axis, and its offset along the axis.
std::pair<double, double> cylinder_coordinates(const Cylinder<3>& c, const Vec<3>& x) {
  Vec<3> d = x - c.centre;
  const double along = d[c.axis];
  d[c.axis] = 0.0;
  return {d.norm(), along};
}

}  // namespace

TEST(CylinderRegions, CentresAreDrawnUniformlyWhereTheGrainFitsWhole) {
  // 40 000 centres for a ball of r = 1 mm in a cylinder of R = 6 mm, 20 mm
  // long, along x: uniform over the disc of radius a = R - r across and
  // over L - 2r along. Moments of that distribution: E[rho^2] = a^2 / 2
  // (sd a^2 / sqrt(12)), E[s] = 0, E[s^2] = (L - 2r)^2 / 12, E[angle's
  // cosine] = 0; each mean within 5 of its standard errors (1 in 2 x 10^6
  // by chance). A square root left out of the distance would give a^2 / 3;
  // a box's corners, rho above a.
  Cylinder<3> c;
  c.centre = Vec<3>(0.1, -0.2, 0.3);
  c.radius = 0.006;
  c.axis = 0;
  c.length = 0.02;
  const double r = 0.001;
  const double a = c.radius - r;
  const double h = c.length - 2.0 * r;
  std::mt19937_64 rng(7);
  const int n = 40000;
  double rho2 = 0.0, s = 0.0, s2 = 0.0, cosine = 0.0;
  for (int i = 0; i < n; ++i) {
    const Vec<3> x = c.sample(r, rng);
    const auto [rho, along] = cylinder_coordinates(c, x);
    ASSERT_LE(rho, a * (1.0 + 1e-12));
    ASSERT_LE(std::abs(along), 0.5 * h * (1.0 + 1e-12));
    rho2 += rho * rho / n;
    s += along / n;
    s2 += along * along / n;
    cosine += (x[1] - c.centre[1]) / std::max(rho, 1e-300) / n;
  }
  const double se = 5.0 / std::sqrt(static_cast<double>(n));
  EXPECT_NEAR(rho2, 0.5 * a * a, se * a * a / std::sqrt(12.0));
  EXPECT_NEAR(s, 0.0, se * h / std::sqrt(12.0));
  EXPECT_NEAR(s2, h * h / 12.0, se * h * h / std::sqrt(180.0));
  EXPECT_NEAR(cosine, 0.0, se / std::sqrt(2.0));
  // Its box and volume by hand.
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(c.lower()[k], Vec<3>(0.09, -0.206, 0.294)[k], 1e-15);
    EXPECT_NEAR(c.upper()[k], Vec<3>(0.11, -0.194, 0.306)[k], 1e-15);
  }
  EXPECT_NEAR(c.volume(), std::numbers::pi * 36e-6 * 0.02, 1e-22);
}

TEST(CylinderRegions, ARandomCloudFillsTheCylinderWithoutOverlaps) {
  // 2D: 150 discs of 0.3-0.5 mm in a circle of 8 mm; 3D: a cloud to a
  // porosity of 0.7 in a cylinder along z, whose grains' volume is 0.3 of
  // the cylinder's to within half the largest grain.
  RadiusDistribution radii;
  radii.kind = RadiusDistribution::Kind::uniform;
  radii.min = 0.0003;
  radii.max = 0.0005;
  Cylinder<2> circle;
  circle.centre = Vec<2>(0.01, 0.02);
  circle.radius = 0.008;
  const auto disc_cloud = random_packing<2>(circle.lower(), circle.upper(), 150, radii, 3, 1000, {}, &circle);
  ASSERT_EQ(disc_cloud.position.size(), 150U);
  for (std::size_t i = 0; i < 150; ++i) {
    EXPECT_LE((disc_cloud.position[i] - circle.centre).norm() + disc_cloud.radius[i],
              circle.radius * (1 + 1e-12));
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_GE((disc_cloud.position[i] - disc_cloud.position[j]).norm(),
                disc_cloud.radius[i] + disc_cloud.radius[j]);
  }
  Cylinder<3> cell;
  cell.centre = Vec<3>(0.0, 0.0, 0.015);
  cell.radius = 0.004;
  cell.length = 0.03;
  const auto cloud =
      random_packing_to_porosity<3>(cell.lower(), cell.upper(), 0.7, radii, 5, 1000, {}, &cell);
  double solid = 0.0;
  for (std::size_t i = 0; i < cloud.position.size(); ++i) {
    const auto [rho, along] = cylinder_coordinates(cell, cloud.position[i]);
    EXPECT_LE(rho + cloud.radius[i], cell.radius * (1 + 1e-12));
    EXPECT_LE(std::abs(along) + cloud.radius[i], 0.5 * cell.length * (1 + 1e-12));
    solid += 4.0 / 3.0 * std::numbers::pi * std::pow(cloud.radius[i], 3);
  }
  EXPECT_NEAR(solid, 0.3 * cell.volume(), 0.5 * 4.0 / 3.0 * std::numbers::pi * std::pow(radii.max, 3));
}

TEST(CylinderRegions, ASceneFillsACylinderWallAndRainsIntoIt) {
  // examples/dem_cases/cylinder_cell.toml with its cloud in a cylinder as
  // wide as the cell (4 mm) instead of the box inscribed in it, and an
  // inlet above it raining into a cylinder of the cell's radius: every
  // grain clear of the wall (its gap at least its radius: the scene's
  // initial-overlap check passes, the inlet's places are checked).
  const std::string dir = darcydem::testing::temp_dir("cylinder_regions");
  const std::string text = darcydem::testing::scene_variant(
      "examples/dem_cases/cylinder_cell.toml",
      {{"min = [-0.0028, -0.0028, 0.0]\nmax = [0.0028, 0.0028, 0.03]",
        "cylinder = { centre = [0.0, 0.0, 0.015], radius = 0.004, length = 0.03 }"},
       {"[output]",
        "[[inlet]]\nname = \"rain\"\nmaterial = \"sand\"\n"
        "cylinder = { centre = [0.0, 0.0, 0.04], radius = 0.004, axis = \"z\", length = 0.01 }\n"
        "radius_min = 0.0004\nradius_max = 0.0006\nrate = 2000.0\ncount = 30\n\n[output]"}});
  Scene<3> scene = darcydem::testing::scene_from_text<3>(dir, "cell.toml", text);
  auto& sim = scene.simulation;
  ASSERT_EQ(sim.particles.size(), 300U);
  const Wall<3>& wall = sim.walls.at(1);
  ASSERT_TRUE(wall.is_cylinder());
  double widest = 0.0;
  for (std::size_t i = 0; i < 300; ++i) {
    const auto& x = sim.particles.position[i];
    EXPECT_GE(wall.gap(x), sim.particles.radius[i] * (1.0 - 1e-12)) << i;
    widest = std::max(widest, std::hypot(x[0], x[1]) + sim.particles.radius[i]);
  }
  EXPECT_GT(widest, 0.0028 * std::sqrt(2.0)) << "beyond the inscribed box's corners";
  bool noted = false;
  for (const auto& note : scene.notes)
    noted = noted || note.find(
                         "into a cylinder of radius 0.004 along z (within x in [-0.004, 0.004], y in "
                         "[-0.004, 0.004], z in [0.035, 0.045]) m") != std::string::npos;
  EXPECT_TRUE(noted) << "the run log says where the inlet rains";
  sim.prepare();
  auto& rain = scene.inlets.at(0);
  ASSERT_TRUE(rain.cylinder.has_value());
  const auto result = insert_due(rain, sim);
  EXPECT_EQ(result.added, 20U) << "2000 grains/s over 10 ms";
  for (std::size_t i = 300; i < sim.particles.size(); ++i) {
    const auto& x = sim.particles.position[i];
    const double ri = sim.particles.radius[i];
    EXPECT_LE(std::hypot(x[0], x[1]) + ri, 0.004 * (1 + 1e-12));
    EXPECT_GE(x[2] - ri, 0.035 - 1e-15);
    EXPECT_LE(x[2] + ri, 0.045 + 1e-15);
    EXPECT_GE(wall.gap(x), ri * (1.0 - 1e-12));
  }
  std::filesystem::remove_all(dir);
}
