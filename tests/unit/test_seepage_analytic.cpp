// The closed-form seepage solution against REFERENCE.md's table (computed
// independently for H = 0.05 m, m_v = 1.012e-5 1/Pa, k = 1.0009e-3 m/s,
// q = 1e-3 m/s, n = 0.2121) and against its own limits.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "darcydem/analysis/seepage_analytic.hpp"

using darcydem::SeepageColumnParameters;

namespace {
SeepageColumnParameters reference(double bulk_modulus) {
  SeepageColumnParameters p;
  p.height = 0.05;
  p.inflow = 1e-3;
  p.conductivity = 1.0009e-3;
  p.compressibility = 1.012e-5;
  p.fluid_storage = 0.2121 / bulk_modulus;
  p.unit_weight = 1000.0 * 9.80665;
  return p;
}
}  // namespace

TEST(SeepageAnalytic, ReproducesReferenceTable) {
  // REFERENCE.md gives S in mm to 4 decimals: tolerance half a unit of the
  // last digit.
  const double tol = 0.5e-4;
  struct Row {
    double kf;
    double s[6];
  };
  const double times[6] = {0.01, 0.05, 0.1, 0.2, 0.5, 1.0};
  const Row rows[] = {{1e7, {0.0100, 0.0462, 0.0766, 0.1064, 0.1231, 0.1239}},
                      {1e5, {0.0083, 0.0393, 0.0678, 0.0993, 0.1219, 0.1239}},
                      {1e4, {0.0032, 0.0161, 0.0315, 0.0567, 0.0983, 0.1188}}};
  for (const auto& row : rows) {
    const auto p = reference(row.kf);
    for (int i = 0; i < 6; ++i) {
      EXPECT_NEAR(darcydem::seepage_uplift(p, times[i]) * 1e3, row.s[i], tol)
          << "K_f=" << row.kf << " t=" << times[i];
    }
  }
}

TEST(SeepageAnalytic, LimitsAndSteadyState) {
  const auto p = reference(1e7);
  // Steady numbers of REFERENCE.md: 490 Pa at the bottom, uplift 0.124 mm.
  EXPECT_NEAR(p.steady_bottom_pressure(), 490.0, 0.5);
  EXPECT_NEAR(p.final_uplift() * 1e3, 0.124, 0.0005);
  EXPECT_DOUBLE_EQ(darcydem::seepage_uplift(p, 0.0), 0.0);
  EXPECT_NEAR(darcydem::seepage_uplift(p, 50.0), p.final_uplift(), 1e-12 * p.final_uplift());
  for (double z : {0.0, 0.01, 0.025, 0.05}) {
    EXPECT_NEAR(darcydem::seepage_pressure(p, z, 50.0), p.steady_bottom_pressure() * z / p.height, 1e-9);
  }
  // Early times: all the inflow goes into expansion, S = q t (incompressible fluid).
  auto q = p;
  q.fluid_storage = 0.0;
  EXPECT_NEAR(darcydem::seepage_uplift(q, 1e-4), q.inflow * 1e-4, 0.01 * q.inflow * 1e-4);
  // The drained top stays at zero, and the uplift is m_v times the integral
  // of the pressure (trapezoid rule on 2000 intervals, error < 1e-6).
  const double t = 0.05;
  EXPECT_NEAR(darcydem::seepage_pressure(p, 0.0, t), 0.0, 1e-9);
  double integral = 0.0;
  const int n = 2000;
  for (int i = 0; i <= n; ++i) {
    const double w = (i == 0 || i == n) ? 0.5 : 1.0;
    integral += w * darcydem::seepage_pressure(p, p.height * i / n, t) * p.height / n;
  }
  EXPECT_NEAR(p.compressibility * integral, darcydem::seepage_uplift(p, t), 1e-6 * p.final_uplift());
}

TEST(SeepageAnalytic, ConsolidationDegree) {
  // Terzaghi's one-way drainage: U(Tv = 0.197) = 0.5 and U(Tv = 0.848) = 0.9
  // (the textbook values, to the 3 digits they are quoted with), and the
  // early U = 2 sqrt(Tv / pi) (1 % at Tv = 1e-3).
  auto p = reference(1e7);
  p.fluid_storage = 0.0;
  const double cv = p.consolidation_coefficient();
  auto at_tv = [&](double tv) { return darcydem::consolidation_degree(p, tv * p.height * p.height / cv); };
  EXPECT_NEAR(at_tv(0.197), 0.5, 0.001);
  EXPECT_NEAR(at_tv(0.848), 0.9, 0.001);
  EXPECT_NEAR(at_tv(1e-3), 2.0 * std::sqrt(1e-3 / 3.14159265358979),
              0.01 * 2.0 * std::sqrt(1e-3 / 3.14159265358979));
  // A compressible fluid takes the share B = m_v / (m_v + n/K_f) at once.
  auto q = reference(1e5);
  const double b = q.compressibility / (q.compressibility + q.fluid_storage);
  EXPECT_NEAR(darcydem::consolidation_degree(q, 1e-12), 1.0 - b, 1e-3);
}

TEST(SeepageAnalytic, ConsolidationPressure) {
  // The isochrones of the same consolidation: their mean over the column
  // is the share of the load the water still carries, so
  //   (1/H) integral of u dz = stress (1 - U)
  // with U from consolidation_degree, a different series (the midpoint
  // rule on 2000 points: 1e-6 of the stress). At the sealed end the
  // pressure starts at B stress and falls; at the drained end it is 0.
  auto p = reference(1e5);
  const double stress = 500.0;
  const double b = p.compressibility / (p.compressibility + p.fluid_storage);
  const double cv = p.consolidation_coefficient();
  for (double tv : {0.01, 0.1, 0.197, 0.5, 1.0}) {
    const double t = tv * p.height * p.height / cv;
    constexpr int n = 2000;
    double mean = 0.0;
    for (int i = 0; i < n; ++i)
      mean += darcydem::consolidation_pressure(p, stress, (i + 0.5) * p.height / n, t) / n;
    EXPECT_NEAR(mean, stress * (1.0 - darcydem::consolidation_degree(p, t)), 1e-5 * stress) << tv;
    EXPECT_EQ(darcydem::consolidation_pressure(p, stress, 0.0, t), 0.0);
  }
  const double early = 1e-6 * p.height * p.height / cv;
  EXPECT_NEAR(darcydem::consolidation_pressure(p, stress, p.height, early), b * stress, 1e-6 * stress);
  // At the sealed end by Tv = 0.848 (U = 0.9 for B = 1): u / (B stress) =
  // (4/pi) exp(-pi^2 Tv / 4) to the next term's 1e-8.
  const double late = 0.848 * p.height * p.height / cv;
  EXPECT_NEAR(
      darcydem::consolidation_pressure(p, stress, p.height, late),
      b * stress * 4.0 / std::numbers::pi * std::exp(-std::numbers::pi * std::numbers::pi * 0.848 / 4.0),
      1e-6 * stress);
}
