// The exact ball/box overlap against independent references: known
// fractions (half, quarter, eighth of a ball), and in 3D a numerical
// integral over slices of the 2D formula (tanh-sinh quadrature split at
// every point where the slice changes shape), which shares no code with the
// 3D closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "darcydem/fluid/ball_overlap.hpp"

namespace bo = darcydem::ball_overlap;
using std::numbers::pi;

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * pi * r * r * r; }

/// Tanh-sinh quadrature of f over [a, b]; endpoint singularities of the
/// kind sqrt(z - a) converge exponentially.
template <class F>
double tanh_sinh(F&& f, double a, double b) {
  if (b <= a) return 0.0;
  const double h = 1.0 / 64.0;
  const double mid = 0.5 * (a + b);
  const double half = 0.5 * (b - a);
  double sum = 0.0;
  for (int k = -220; k <= 220; ++k) {
    const double t = k * h;
    const double u = 0.5 * pi * std::sinh(t);
    const double x = std::tanh(u);
    const double w = 0.5 * pi * std::cosh(t) / (std::cosh(u) * std::cosh(u));
    if (w < 1e-300) continue;
    sum += w * f(mid + half * x);
  }
  return sum * half * h;
}

/// Reference: integral over z of the 2D disc/rectangle area of each slice.
double sphere_in_box_by_slices(double r, std::array<double, 3> c, std::array<double, 3> lo,
                               std::array<double, 3> hi) {
  const double z0 = std::max(lo[2], c[2] - r);
  const double z1 = std::min(hi[2], c[2] + r);
  if (z1 <= z0) return 0.0;
  auto slice = [&](double z) {
    const double rho = std::sqrt(std::max(0.0, r * r - (z - c[2]) * (z - c[2])));
    return bo::in_box<2>(rho, {c[0], c[1]}, {lo[0], lo[1]}, {hi[0], hi[1]});
  };
  // Break where the slice's disc touches a side or a corner of the rectangle.
  std::vector<double> breaks = {z0, z1};
  for (double dx : {lo[0] - c[0], hi[0] - c[0], 0.0}) {
    for (double dy : {lo[1] - c[1], hi[1] - c[1], 0.0}) {
      const double d2 = dx * dx + dy * dy;
      if (d2 == 0.0 || d2 >= r * r) continue;
      const double dz = std::sqrt(r * r - d2);
      for (double z : {c[2] - dz, c[2] + dz}) {
        if (z > z0 && z < z1) breaks.push_back(z);
      }
    }
  }
  std::sort(breaks.begin(), breaks.end());
  double v = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) v += tanh_sinh(slice, breaks[i], breaks[i + 1]);
  return v;
}

}  // namespace

TEST(BallOverlap, DiscKnownFractions) {
  const double r = 0.7;
  const double a = pi * r * r;
  // Tolerance 1e-14 relative: closed forms, only round-off.
  EXPECT_NEAR(bo::segment_area(r, 0.0), a / 2, 1e-14 * a);
  EXPECT_NEAR(bo::corner_area(r, 0.0, 0.0), a / 4, 1e-14 * a);
  EXPECT_NEAR(bo::in_box<2>(r, {0, 0}, {-1, -1}, {1, 1}), a, 1e-14 * a);
  EXPECT_NEAR(bo::in_box<2>(r, {0, 0}, {0, 0}, {1, 1}), a / 4, 1e-14 * a);
  // A square inscribed in the circle: area 2 r^2.
  const double s = r / std::sqrt(2.0);
  EXPECT_NEAR(bo::in_box<2>(r, {0, 0}, {-s, -s}, {s, s}), 2 * r * r, 1e-13 * a);
}

TEST(BallOverlap, DiscCornerAgainstStripIntegral) {
  // Area of the disc in {x > a, y > b} = integral over x of the chord above b.
  const double r = 1.0;
  for (double a : {0.0, 0.1, 0.35, 0.6}) {
    for (double b : {0.0, 0.2, 0.5, 0.75}) {
      const double xb = std::sqrt(std::max(0.0, r * r - b * b));
      const double ref =
          tanh_sinh([&](double x) { return std::sqrt(r * r - x * x) - b; }, a, std::max(a, xb));
      EXPECT_NEAR(bo::corner_area(r, a, b), ref, 1e-13) << "a=" << a << " b=" << b;
    }
  }
}

TEST(BallOverlap, SphereKnownFractions) {
  const double r = 1.3;
  const double v = sphere_volume(r);
  EXPECT_NEAR(bo::cap_volume(r, 0.0), v / 2, 1e-14 * v);
  EXPECT_NEAR(bo::wedge_volume(r, 0.0, 0.0), v / 4, 1e-14 * v);
  EXPECT_NEAR(bo::octant_volume(r, 0.0, 0.0, 0.0), v / 8, 1e-14 * v);
  EXPECT_NEAR(bo::in_box<3>(r, {0, 0, 0}, {-2, -2, -2}, {2, 2, 2}), v, 1e-14 * v);
  EXPECT_NEAR(bo::in_box<3>(r, {0, 0, 0}, {0, -2, 0}, {2, 0, 2}), v / 8, 1e-14 * v);
  // A cube inscribed in the sphere: side 2r/sqrt(3).
  const double s = r / std::sqrt(3.0);
  EXPECT_NEAR(bo::in_box<3>(r, {0, 0, 0}, {-s, -s, -s}, {s, s, s}), 8 * s * s * s, 1e-13 * v);
}

TEST(BallOverlap, OctantIsSymmetric) {
  const double r = 1.0;
  const double x = bo::octant_volume(r, 0.1, 0.3, 0.5);
  EXPECT_NEAR(bo::octant_volume(r, 0.3, 0.5, 0.1), x, 1e-15);
  EXPECT_NEAR(bo::octant_volume(r, 0.5, 0.1, 0.3), x, 1e-15);
  EXPECT_NEAR(bo::wedge_volume(r, 0.2, 0.6), bo::wedge_volume(r, 0.6, 0.2), 1e-15);
}

TEST(BallOverlap, SphereInRandomBoxesAgainstSliceIntegral) {
  // The issue asks for the sphere/box volume to 1e-9 relative; the closed
  // forms should agree with the independent quadrature far better than that.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const double r = 1.0;
  const double v = sphere_volume(r);
  double worst = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    std::array<double, 3> lo{}, hi{};
    for (int k = 0; k < 3; ++k) {
      double p = u(rng), q = u(rng);
      lo[k] = std::min(p, q);
      hi[k] = std::max(p, q);
    }
    const double exact = bo::in_box<3>(r, {0, 0, 0}, lo, hi);
    const double ref = sphere_in_box_by_slices(r, {0, 0, 0}, lo, hi);
    worst = std::max(worst, std::abs(exact - ref) / v);
  }
  EXPECT_LT(worst, 1e-11);
}
