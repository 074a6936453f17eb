// Grading curves: the random generator's sizes drawn from a sieve curve by
// mass or by number. The expectation is the curve itself, read the way a
// sieve analysis is: the mass (or number) of the grains finer than a
// diameter over the whole. Between sieves the curve is linear in log d, so
// at the geometric mean of two sieves it passes the mean of their fractions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "darcydem/generation/generators.hpp"
#include "darcydem/particles/grading.hpp"

namespace darcydem {
namespace {

/// The fraction finer than x of the grains d, each weighing d^power (a
/// sphere's mass goes as d^3, a disc's of unit thickness as d^2; 0 counts
/// them), and its standard error. The fraction is a ratio of sums, so the
/// delta method gives var = sum w^2 (1[d < x] - F)^2 / (sum w)^2.
struct Finer {
  double fraction = 0.0;
  double sigma = 0.0;
};
Finer finer_than(const std::vector<double>& d, double x, int power) {
  double total = 0.0;
  double below = 0.0;
  for (double di : d) {
    const double w = std::pow(di, power);
    total += w;
    below += di < x ? w : 0.0;
  }
  const double f = below / total;
  double var = 0.0;
  for (double di : d) {
    const double w = std::pow(di, power) / total;
    const double e = (di < x ? 1.0 : 0.0) - f;
    var += w * w * e * e;
  }
  return {f, std::sqrt(var)};
}

std::vector<double> draw_diameters(const RadiusDistribution& g, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<double> d(static_cast<std::size_t>(n));
  for (double& x : d) x = 2.0 * g.sample(rng);
  return d;
}

/// Checks the drawn diameters against the curve at every sieve and at the
/// geometric mean of every two: within 5 standard errors (the draws are
/// seeded, so this either always passes or always fails; 5 sigma makes a
/// correct sampler's failure a 1-in-10^6 accident of the seed), and the
/// error small enough (`resolution`) for the check to mean something.
void expect_follows_the_curve(const std::vector<double>& d, const std::vector<double>& sieves,
                              const std::vector<double>& passing, int power, double resolution) {
  const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
  EXPECT_GE(*lo, sieves.front());
  EXPECT_LE(*hi, sieves.back());
  for (std::size_t i = 0; i < sieves.size(); ++i) {
    std::vector<std::pair<double, double>> points = {{sieves[i], passing[i]}};
    if (i + 1 < sieves.size()) {
      points.emplace_back(std::sqrt(sieves[i] * sieves[i + 1]), 0.5 * (passing[i] + passing[i + 1]));
    }
    for (const auto& [x, expected] : points) {
      const Finer f = finer_than(d, x, power);
      EXPECT_NEAR(f.fraction, expected, 5.0 * f.sigma + 1e-12) << "finer than " << x << " m";
      EXPECT_LT(f.sigma, resolution) << "finer than " << x << " m";
    }
  }
}

/// A random packing's grains lie inside [lo, hi], do not overlap (to
/// round-off of the coordinates) and come largest first.
void expect_placed_largest_first(const Packing<3>& pk, const Vec<3>& lo, const Vec<3>& hi) {
  for (std::size_t i = 0; i < pk.radius.size(); ++i) {
    const double r = pk.radius[i];
    if (i > 0) {
      EXPECT_LE(r, pk.radius[i - 1]);
    }
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(pk.position[i][k] - r, lo[k] - 1e-15);
      EXPECT_LE(pk.position[i][k] + r, hi[k] + 1e-15);
    }
    for (std::size_t j = 0; j < i; ++j) {
      ASSERT_GE((pk.position[i] - pk.position[j]).norm(), r + pk.radius[j] - 1e-15) << i << " and " << j;
    }
  }
}

/// A well-graded sand, 0.2 to 2 mm by mass (Cu about 3): the coarse grains
/// are few by number but carry the mass, the case a sampler by number gets
/// wrong. Its D_x, read by hand, are in the tests below.
const std::vector<double> sand_sieves = {0.2e-3, 0.5e-3, 1.0e-3, 2.0e-3};
const std::vector<double> sand_passing = {0.0, 0.3, 0.7, 1.0};

TEST(Grading, SpheresFollowACurveByMass) {
  const std::vector<double>& sieves = sand_sieves;
  const std::vector<double>& passing = sand_passing;
  const auto g = RadiusDistribution::grading(sieves, passing, 3);
  EXPECT_DOUBLE_EQ(g.largest(), 1.0e-3);
  // 400 000 draws: the mass above 1 mm rests on about 0.9 % of the grains,
  // which puts the standard error there at 0.0043.
  const auto d = draw_diameters(g, 400000, 3);
  expect_follows_the_curve(d, sieves, passing, 3, 0.005);
  // By number the same grains are mostly fine. By hand: between sieves a
  // and b the mass dP spread evenly in log d holds dP / ln(b/a) * (a^-3 -
  // b^-3) / 3 grains (per unit of mass / d^3), which is 12.769, 1.3465 and
  // 0.12624 mm^-3 for the three intervals, so 0.89659 of the grains are
  // finer than 0.5 mm; binomial sigma 0.00047, allowed 5 sigma.
  EXPECT_NEAR(finer_than(d, 0.5e-3, 0).fraction, 0.89659, 0.0024);
}

TEST(Grading, TheRunLogsSummaryReadsTheCurveBack) {
  // The summary's D10 ... D60 of 400 000 grains drawn from the curve above,
  // against the curve read on its semi-log chart by hand: D10 = 0.2 x
  // 2.5^(1/3) = 0.2714 mm, D30 = 0.5 mm (a sieve), D50 = 0.5 x 2^(1/2) =
  // 0.7071 mm, D60 = 0.5 x 2^(3/4) = 0.8409 mm. A standard error of 0.0043
  // in the fraction moves D_x by 0.0043 / (dP / d ln d), at most 1.3 %
  // here (dP / d ln d = 0.327 below 0.5 mm); allowed 5 %. D30 falls on a
  // sieve, where the curve steepens from 0.327 to 0.577: allowed 3 %.
  const auto g = RadiusDistribution::grading(sand_sieves, sand_passing, 3);
  std::vector<double> r = draw_diameters(g, 400000, 3);
  for (double& x : r) x *= 0.5;
  const GradingSummary s = grading_of<3>(r);
  EXPECT_NEAR(s.d10, 0.2714e-3, 0.05 * 0.2714e-3);
  EXPECT_NEAR(s.d30, 0.5e-3, 0.03 * 0.5e-3);
  EXPECT_NEAR(s.d50, 0.7071e-3, 0.05 * 0.7071e-3);
  EXPECT_NEAR(s.d60, 0.8409e-3, 0.05 * 0.8409e-3);
  EXPECT_NEAR(s.uniformity(), 0.8409 / 0.2714, 0.1 * 0.8409 / 0.2714);
}

TEST(Grading, TheCurvesDiametersAreReadOnItsSemiLogChart) {
  // By hand, as in the test above; a sieve's own fraction gives the sieve;
  // on a flat part the first diameter that reaches it.
  const auto g = RadiusDistribution::grading(sand_sieves, sand_passing, 3);
  EXPECT_NEAR(g.passing_diameter(0.1), 0.2e-3 * std::cbrt(2.5), 1e-15);
  EXPECT_NEAR(g.passing_diameter(0.3), 0.5e-3, 1e-15);
  EXPECT_NEAR(g.passing_diameter(0.5), 0.5e-3 * std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(g.passing_diameter(0.6), 0.5e-3 * std::pow(2.0, 0.75), 1e-15);
  EXPECT_NEAR(g.passing_diameter(1.0), 2.0e-3, 1e-15);
  const auto flat = RadiusDistribution::grading({1e-3, 2e-3, 4e-3}, {0.0, 1.0, 1.0}, 3);
  EXPECT_NEAR(flat.passing_diameter(1.0), 2e-3, 1e-15);
  RadiusDistribution constant;
  EXPECT_THROW((void)constant.passing_diameter(0.5), std::logic_error);
}

TEST(Grading, DiscsFollowACurveByMassWithAFlatTop) {
  // In 2D a disc of unit thickness weighs as d^2. The curve reaches 1 at
  // the third sieve: nothing coarser is drawn, and the largest radius is
  // that sieve's half (the packing's cells are sized by it).
  const std::vector<double> sieves = {0.1e-3, 0.3e-3, 0.9e-3, 1.2e-3};
  const std::vector<double> passing = {0.0, 0.5, 1.0, 1.0};
  const auto g = RadiusDistribution::grading(sieves, passing, 2);
  EXPECT_DOUBLE_EQ(g.largest(), 0.45e-3);
  const auto d = draw_diameters(g, 200000, 4);
  EXPECT_LE(*std::max_element(d.begin(), d.end()), 0.9e-3);
  expect_follows_the_curve(d, sieves, passing, 2, 0.004);
}

TEST(Grading, ACurveByNumberCountsGrains) {
  // By number the fraction finer is binomial: sigma = sqrt(F (1 - F) / n),
  // at most 0.0016 for 100 000 draws.
  const std::vector<double> sieves = {0.25e-3, 0.5e-3, 4.0e-3};
  const std::vector<double> passing = {0.0, 0.1, 1.0};
  const auto g = RadiusDistribution::grading(sieves, passing, 0);
  const auto d = draw_diameters(g, 100000, 5);
  expect_follows_the_curve(d, sieves, passing, 0, 0.002);
}

TEST(Grading, RandomPackingPlacesTheLargestFirstAndKeepsTheCurve) {
  // 3000 spheres of a 0.4-2.4 mm grading in a 20 x 20 x 40 mm box (solid
  // fraction about 0.17): inside, not overlapping, placed largest first,
  // and the grains made still follow the curve by mass. With 3000 grains
  // the standard error is up to about 0.03 (a few hundred coarse grains
  // carry the mass).
  const std::vector<double> sieves = {0.4e-3, 0.8e-3, 1.6e-3, 2.4e-3};
  const std::vector<double> passing = {0.0, 0.2, 0.7, 1.0};
  const auto g = RadiusDistribution::grading(sieves, passing, 3);
  const Vec<3> lo(0, 0, 0), hi(0.02, 0.02, 0.04);
  const auto pk = random_packing<3>(lo, hi, 3000, g, 7, 1000);
  ASSERT_EQ(pk.radius.size(), 3000U);
  expect_placed_largest_first(pk, lo, hi);
  std::vector<double> d;
  for (double r : pk.radius) d.push_back(2.0 * r);
  expect_follows_the_curve(d, sieves, passing, 3, 0.04);
  // The same seed gives the same packing.
  EXPECT_EQ(random_packing<3>(lo, hi, 3000, g, 7, 1000).position[1234], pk.position[1234]);
}

TEST(Grading, RandomPackingToAPorosityHasThatSolidVolume) {
  // Equal discs of 0.5 mm in a 20 x 20 mm box at porosity 0.6: (1 - 0.6) x
  // 4e-4 m^2 / (pi 0.25e-6 m^2) = 203.72 discs' worth, so 204, the nearer
  // whole number (by hand). Solid fraction 0.4, below random sequential
  // addition's 0.55 for discs.
  RadiusDistribution equal;
  equal.value = 0.5e-3;
  const auto discs = random_packing_to_porosity<2>(Vec<2>(0, 0), Vec<2>(0.02, 0.02), 0.6, equal, 3, 1000);
  EXPECT_EQ(discs.radius.size(), 204U);

  // A grading by mass in 3D at porosity 0.75: the grains' volume is within
  // half a grain of a quarter of the box's, and they lie inside it without
  // overlapping, largest first.
  const std::vector<double> sieves = {0.4e-3, 0.8e-3, 1.6e-3, 2.4e-3};
  const std::vector<double> passing = {0.0, 0.2, 0.7, 1.0};
  const auto g = RadiusDistribution::grading(sieves, passing, 3);
  const Vec<3> lo(0, 0, 0), hi(0.015, 0.015, 0.03);
  const auto pk = random_packing_to_porosity<3>(lo, hi, 0.75, g, 11, 1000);
  const double box = 0.015 * 0.015 * 0.03;
  double solid = 0.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < pk.radius.size(); ++i) {
    const double r = pk.radius[i];
    const double v = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    solid += v;
    largest = std::max(largest, v);
  }
  expect_placed_largest_first(pk, lo, hi);
  EXPECT_GT(pk.radius.size(), 1000U);
  EXPECT_LE(std::abs(solid - 0.25 * box), 0.5 * largest);
  // A porosity random sequential addition cannot reach says so.
  EXPECT_THROW(random_packing_to_porosity<3>(lo, hi, 0.5, g, 11, 200), std::runtime_error);
}

TEST(Grading, BadCurvesAreRefused) {
  EXPECT_THROW(RadiusDistribution::grading({1e-3}, {1.0}, 3), std::invalid_argument);
  EXPECT_THROW(RadiusDistribution::grading({1e-3, 1e-3}, {0.0, 1.0}, 3), std::invalid_argument);
  EXPECT_THROW(RadiusDistribution::grading({1e-3, 2e-3}, {0.0, 0.9}, 3), std::invalid_argument);
  EXPECT_THROW(RadiusDistribution::grading({1e-3, 2e-3, 3e-3}, {0.0, 0.6, 0.5}, 3), std::invalid_argument);
  EXPECT_THROW(RadiusDistribution::grading({1e-3, 2e-3}, {0.0, 1.0, 1.0}, 3), std::invalid_argument);
  EXPECT_THROW(RadiusDistribution::grading({1e-3, 2e-3}, {0.0, 1.0}, -1), std::invalid_argument);
}

}  // namespace
}  // namespace darcydem
