// Bond strengths that scatter from bond to bond (PFC's strength scatter):
// each bond's strengths are the scene's times a factor f of Weibull's
// distribution with modulus m and mean 1, F(f) = 1 - exp(-(f / s)^m),
// s = 1 / Gamma(1 + 1/m), drawn from a hash of the two grains' ids.
// Checked against that closed form: the factors themselves, and the loads
// at which a row of bonded dimers, pulled apart slowly, break one by one.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "dem_setup.hpp"

namespace darcydem {
namespace {

/// Weibull's distribution function of mean 1 and modulus m.
double weibull_cdf(double f, double m) {
  const double scale = 1.0 / std::tgamma(1.0 + 1.0 / m);
  return 1.0 - std::exp(-std::pow(f / scale, m));
}

/// Kolmogorov-Smirnov's statistic of a sample against Weibull's CDF.
double ks_statistic(std::vector<double> sample, double m) {
  std::sort(sample.begin(), sample.end());
  const auto n = static_cast<double>(sample.size());
  double d = 0.0;
  for (std::size_t k = 0; k < sample.size(); ++k) {
    const double c = weibull_cdf(sample[k], m);
    d = std::max({d, c - static_cast<double>(k) / n, static_cast<double>(k + 1) / n - c});
  }
  return d;
}

double mean_of(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

PairParameters scattered(double modulus, std::uint64_t seed) {
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  spec.restitution = 0.3;
  spec.bond_tensile_strength = 1.0;
  spec.bond_shear_strength = 1.0;
  spec.bond_strength_weibull_modulus = modulus;
  spec.bond_strength_seed = seed;
  const Material grain{"grain", 2500.0, 0.0, 0.0};
  return make_pair_parameters(grain, grain, spec);
}

// 10^5 pairs of ids: their factors follow Weibull's law. Bounds: the mean
// of N draws is within 4 standard errors (CV / sqrt(N), the CV from the
// closed form) of 1 (a wrong scale, e.g. without the Gamma normalization,
// is 9 % off for m = 5); KS below 1.95 / sqrt(N), its 0.1 % critical value.
TEST(BondStrengthScatter, FactorsFollowWeibullsLawWithMeanOne) {
  for (const double m : {2.0, 5.0, 12.0}) {
    const auto pp = scattered(m, 7);
    std::vector<double> f;
    for (std::uint32_t a = 0; a < 1000; ++a) {
      for (std::uint32_t b = 1000; b < 1100; ++b) f.push_back(pp.bond_strength_factor(a, b));
    }
    const double n = static_cast<double>(f.size());
    const double g1 = std::tgamma(1.0 + 1.0 / m);
    const double cv = std::sqrt(std::tgamma(1.0 + 2.0 / m) / (g1 * g1) - 1.0);
    EXPECT_NEAR(mean_of(f), 1.0, 4.0 * cv / std::sqrt(n)) << "m = " << m;
    EXPECT_LT(ks_statistic(f, m), 1.95 / std::sqrt(n)) << "m = " << m;
  }
}

// A bond's factor is the pair's, whichever grain comes first; another seed
// draws other factors; without a modulus every factor is 1.
TEST(BondStrengthScatter, FactorIsThePairsAndTheSeedsAlone) {
  const auto pp = scattered(5.0, 7);
  const auto other = scattered(5.0, 8);
  int same = 0;
  for (std::uint32_t a = 0; a < 200; ++a) {
    const std::uint32_t b = 3 * a + 1;
    EXPECT_EQ(pp.bond_strength_factor(a, b), pp.bond_strength_factor(b, a));
    if (pp.bond_strength_factor(a, b) == other.bond_strength_factor(a, b)) ++same;
  }
  EXPECT_EQ(same, 0);
  EXPECT_EQ(scattered(0.0, 7).bond_strength_factor(3, 4), 1.0);
}

// Dimers: a fixed disc and a free one below it, bonded, pulled apart by a
// load on the free disc that grows slowly from 0 to 3 T (T the mean tensile
// strength). A bond holds its disc while the load is below f T, so the
// loads at which the dimers let go, over T, are a sample of the factors:
// all of them break (P(f > 3) = exp(-(3 s)^5) ~ 1e-69 for m = 5), and the
// sample follows Weibull's law (KS below its 0.1 % critical value; the
// mean within 4 standard errors of 1). The ramp lasts 3000 / omega: the
// bond's spring lags the load by at most F' / (k omega) = 1e-3 T, and a
// step adds 1e-4 T, a shift of the sample far below the bounds.
TEST(BondStrengthScatter, DimersPulledApartBreakAtWeibullScatteredLoads) {
  constexpr double r = 1e-3;
  constexpr double density = 2500.0;
  constexpr double modulus = 5.0;
  constexpr int dimers = 300;
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  spec.restitution = 0.3;
  spec.bond_tensile_strength = 1.0;  // N/m
  spec.bond_shear_strength = 1.0;
  spec.bond_strength_weibull_modulus = modulus;
  spec.bond_strength_seed = 3;
  auto sim = testing::single_material<2>(density, spec);
  for (int k = 0; k < dimers; ++k) {
    sim.particles.add(Vec<2>(4.0 * r * k, 0.0), r, density, 0, true, Vec<2>::Zero());
    sim.particles.add(Vec<2>(4.0 * r * k, -2.0 * r * (1.0 - 0.5e-9)), r, density, 0, false, Vec<2>::Zero());
  }
  const double mass = density * std::numbers::pi * r * r;
  const double omega = std::sqrt(spec.normal_stiffness / mass);
  sim.time_step = 0.1 / omega;
  sim.prepare();
  ASSERT_EQ(sim.make_bonds(), static_cast<std::size_t>(dimers));
  const double t_ramp = 3000.0 / omega;
  const double load_rate = 3.0 * spec.bond_tensile_strength / t_ramp;  // N/m/s
  auto& p = sim.particles;
  p.external_force.assign(p.size(), Vec<2>::Zero());
  std::vector<double> break_load;  // over T
  std::size_t bonds = sim.bond_count();
  while (sim.time < t_ramp && bonds > 0) {
    const double load = load_rate * (sim.time + sim.time_step);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.fixed[i] != 0) continue;
      // A disc let go is parked, its load removed, far from the others.
      const bool free = p.position[i].y() < -2.2 * r;
      p.external_force[i] = free ? Vec<2>::Zero() : Vec<2>(0.0, -load);
      if (free) p.velocity[i].setZero();
    }
    sim.step();
    const std::size_t now = sim.bond_count();
    for (std::size_t k = now; k < bonds; ++k) break_load.push_back(load / spec.bond_tensile_strength);
    bonds = now;
  }
  ASSERT_EQ(break_load.size(), static_cast<std::size_t>(dimers)) << "bonds left: " << bonds;
  // Each bond let go at its own factor: the loads sorted against the
  // pairs' factors sorted (grains 2k and 2k + 1 in creation order), within
  // the lag and the step above (2e-3 T).
  std::vector<double> factors;
  for (int k = 0; k < dimers; ++k) {
    factors.push_back(sim.contact_table(0, 0).bond_strength_factor(2 * k, 2 * k + 1));
  }
  std::sort(factors.begin(), factors.end());
  std::vector<double> sorted_loads = break_load;
  std::sort(sorted_loads.begin(), sorted_loads.end());
  double worst = 0.0;
  for (int k = 0; k < dimers; ++k) worst = std::max(worst, std::abs(sorted_loads[k] - factors[k]));
  EXPECT_LT(worst, 2e-3);
  const double n = dimers;
  const double g1 = std::tgamma(1.0 + 1.0 / modulus);
  const double cv = std::sqrt(std::tgamma(1.0 + 2.0 / modulus) / (g1 * g1) - 1.0);
  EXPECT_NEAR(mean_of(break_load), 1.0, 4.0 * cv / std::sqrt(n));
  EXPECT_LT(ks_statistic(break_load, modulus), 1.95 / std::sqrt(n));
  // And they scatter: the weakest in 300 below the mean by far, the
  // strongest above it (the 1/300 and 299/300 quantiles: 0.36 and 1.56).
  const auto [lo, hi] = std::minmax_element(break_load.begin(), break_load.end());
  EXPECT_LT(*lo, 0.6);
  EXPECT_GT(*hi, 1.3);
}

}  // namespace
}  // namespace darcydem
