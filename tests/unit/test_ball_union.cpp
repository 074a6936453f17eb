// The moments of a union of balls against closed forms: one ball; balls
// apart (the sums); one ball inside another; two equal balls overlapping
// (a solid of revolution, its profile the larger of two circles, so each
// moment is a one-dimensional integral done here independently); and a
// ring of discs or spheres overlapping only pairwise around a hole
// (inclusion-exclusion with the lens, exact without triple overlaps).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "darcydem/particles/ball_union.hpp"

namespace darcydem {
namespace {

constexpr double pi = std::numbers::pi;

/// Simpson's rule, n intervals (even): for the smooth integrands below,
/// with n = 4000 its error (h^4 f'''' / 180) is below 1e-14 of the result.
template <class F>
double simpson(F f, double a, double b, int n = 4000) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int k = 1; k < n; ++k) s += (k % 2 == 1 ? 4.0 : 2.0) * f(a + k * h);
  return s * h / 3.0;
}

TEST(BallUnion, OneBallHasTheBallsMoments) {
  const Vec<3> c(0.3, -1.2, 2.0);
  const double r = 0.7;
  const auto m = ball_union_moments<3>({c}, {r});
  const double v = 4.0 / 3.0 * pi * r * r * r;
  // 3D: the slices' quadrature, to about 1e-12 of the volume.
  EXPECT_NEAR(m.volume / v, 1.0, 1e-12);
  EXPECT_LT((m.centroid() - c).norm(), 1e-12 * r);
  const Eigen::Matrix3d expect = v * (r * r / 5.0 * Eigen::Matrix3d::Identity() + c * c.transpose());
  EXPECT_LT((m.second - expect).norm(), 1e-12 * expect.norm());
  const Vec<2> c2(-0.4, 0.9);
  const auto d = ball_union_moments<2>({c2}, {r});
  const double a = pi * r * r;
  // 2D: Green's theorem with 16-point Gauss-Legendre on quarter arcs, exact
  // for these trigonometric polynomials to round-off.
  EXPECT_NEAR(d.volume / a, 1.0, 1e-14);
  const Eigen::Matrix2d expect2 = a * (r * r / 4.0 * Eigen::Matrix2d::Identity() + c2 * c2.transpose());
  EXPECT_LT((d.second - expect2).norm(), 1e-13 * expect2.norm());
}

TEST(BallUnion, BallsApartAddUpAndABallInsideAnotherAddsNothing) {
  const std::vector<Vec<3>> c{{0.0, 0.0, 0.0}, {2.1, 0.0, 0.3}, {0.0, -1.6, 0.0}};
  const std::vector<double> r{1.0, 0.9, 0.5};
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  Vec<3> first = Vec<3>::Zero();
  double volume = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double v = 4.0 / 3.0 * pi * std::pow(r[i], 3);
    volume += v;
    first += v * c[i];
    second += v * (r[i] * r[i] / 5.0 * Eigen::Matrix3d::Identity() + c[i] * c[i].transpose());
  }
  const auto m = ball_union_moments<3>(c, r);
  EXPECT_NEAR(m.volume / volume, 1.0, 1e-12);
  EXPECT_LT((m.first - first).norm(), 1e-12 * volume);
  EXPECT_LT((m.second - second).norm(), 1e-12 * second.norm());
  // Add a ball inside the first, one touching its inside, and a copy of the
  // second: the union is the same.
  auto more_c = c;
  auto more_r = r;
  more_c.push_back({0.2, 0.1, 0.0});
  more_r.push_back(0.5);
  more_c.push_back({0.0, 0.0, 0.4});
  more_r.push_back(0.6);
  more_c.push_back(c[1]);
  more_r.push_back(r[1]);
  const auto same = ball_union_moments<3>(more_c, more_r);
  EXPECT_NEAR(same.volume / volume, 1.0, 1e-12);
  EXPECT_LT((same.second - second).norm(), 1e-12 * second.norm());
}

/// Two balls of radius r at -d/2 and +d/2 on the first axis: per half (by
/// symmetry the union beyond the mid-plane is the nearer ball there) the
/// coordinate u along the axis from that ball's centre runs over [-d/2, r].
TEST(BallUnion, TwoEqualOverlappingSpheres) {
  const double r = 1.0;
  for (double d : {0.3, 1.0, 1.7}) {
    // Profile area pi (r^2 - u^2) at axial position x = u + d/2 (polynomials:
    // Simpson is exact for them up to cubic pieces, and these are of degree 4,
    // its error then below 1e-14).
    auto area = [&](double u) { return pi * (r * r - u * u); };
    const double volume = 2.0 * simpson(area, -0.5 * d, r);
    const double along =
        2.0 * simpson([&](double u) { return area(u) * (u + 0.5 * d) * (u + 0.5 * d); }, -0.5 * d, r);
    // A disc of radius rho: integral of y^2 over it is pi rho^4 / 4.
    const double across =
        2.0 * simpson([&](double u) { return pi * std::pow(r * r - u * u, 2) / 4.0; }, -0.5 * d, r);
    // The pair turned and moved anywhere: the moments about the origin of
    // the turned diagonal tensor.
    const Eigen::Matrix3d turn =
        Eigen::AngleAxisd(0.7, Vec<3>(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
    const Vec<3> centre(0.4, -0.3, 1.1);
    const Vec<3> axis = turn.col(0);
    const auto m = ball_union_moments<3>({centre - 0.5 * d * axis, centre + 0.5 * d * axis}, {r, r});
    const Eigen::Matrix3d local = Eigen::Vector3d(along, across, across).asDiagonal();
    const Eigen::Matrix3d expect = turn * local * turn.transpose() + volume * centre * centre.transpose();
    EXPECT_NEAR(m.volume / volume, 1.0, 1e-12) << "d = " << d;
    EXPECT_LT((m.centroid() - centre).norm(), 1e-12) << "d = " << d;
    EXPECT_LT((m.second - expect).norm(), 1e-12 * expect.norm()) << "d = " << d;
  }
}

TEST(BallUnion, TwoEqualOverlappingDiscs) {
  const double r = 1.0;
  for (double d : {0.3, 1.0, 1.7}) {
    // u = r sin(t) takes the square roots away: smooth integrands in t.
    const double t0 = std::asin(-0.5 * d / r);
    auto in_t = [&](auto f) {
      return 2.0 * simpson([&](double t) { return f(r * std::sin(t)) * r * std::cos(t); }, t0, 0.5 * pi);
    };
    const double area = in_t([&](double u) { return 2.0 * std::sqrt(std::max(0.0, r * r - u * u)); });
    const double along = in_t([&](double u) {
      return 2.0 * std::sqrt(std::max(0.0, r * r - u * u)) * (u + 0.5 * d) * (u + 0.5 * d);
    });
    const double across =
        in_t([&](double u) { return 2.0 / 3.0 * std::pow(std::max(0.0, r * r - u * u), 1.5); });
    // The lens's closed form, as a check on the check.
    const double lens = 2.0 * r * r * std::acos(0.5 * d / r) - 0.5 * d * std::sqrt(4.0 * r * r - d * d);
    ASSERT_NEAR(area, 2.0 * pi * r * r - lens, 1e-12);
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(1.1).toRotationMatrix();
    const Vec<2> centre(-0.2, 0.5);
    const Vec<2> axis = turn.col(0);
    const auto m = ball_union_moments<2>({centre - 0.5 * d * axis, centre + 0.5 * d * axis}, {r, r});
    const Eigen::Matrix2d expect = turn * Eigen::Vector2d(along, across).asDiagonal() * turn.transpose() +
                                   area * centre * centre.transpose();
    EXPECT_NEAR(m.volume / area, 1.0, 1e-13) << "d = " << d;
    EXPECT_LT((m.centroid() - centre).norm(), 1e-13) << "d = " << d;
    EXPECT_LT((m.second - expect).norm(), 1e-12 * expect.norm()) << "d = " << d;
  }
}

/// Six equal balls on a circle of radius 2 (neighbours 2 apart, radius
/// 1.2): each overlaps its two neighbours only, around a hole in the middle.
TEST(BallUnion, ARingAroundAHoleByInclusionExclusion) {
  const double r = 1.2;
  const double d = 2.0;
  const double lens2 = 2.0 * r * r * std::acos(0.5 * d / r) - 0.5 * d * std::sqrt(4.0 * r * r - d * d);
  // A lens of two spheres: two caps of height h = r - d/2.
  const double h = r - 0.5 * d;
  const double lens3 = 2.0 * pi * h * h * (3.0 * r - h) / 3.0;
  std::vector<Vec<2>> c2;
  std::vector<Vec<3>> c3;
  const Vec<3> shift(0.5, -0.25, 0.125);
  for (int k = 0; k < 6; ++k) {
    const double a = k * pi / 3.0;
    c2.emplace_back(2.0 * std::cos(a), 2.0 * std::sin(a));
    c3.push_back(Vec<3>(2.0 * std::cos(a), 0.0, 2.0 * std::sin(a)) + shift);
  }
  const auto m2 = ball_union_moments<2>(c2, std::vector<double>(6, r));
  EXPECT_NEAR(m2.volume, 6.0 * pi * r * r - 6.0 * lens2, 1e-13 * m2.volume);
  EXPECT_LT(m2.first.norm(), 1e-13 * m2.volume);
  const auto m3 = ball_union_moments<3>(c3, std::vector<double>(6, r));
  EXPECT_NEAR(m3.volume, 6.0 * 4.0 / 3.0 * pi * r * r * r - 6.0 * lens3, 1e-12 * m3.volume);
  EXPECT_LT((m3.centroid() - shift).norm(), 1e-12);
}

/// The volume of the lens two balls of radii a and b, d apart, share.
double lens_volume(double a, double b, double d) {
  return pi * (a + b - d) * (a + b - d) * (d * d + 2.0 * d * (a + b) - 3.0 * (a - b) * (a - b)) / (12.0 * d);
}

// Slices of a union of balls turned any way cross each other at depths the
// quadrature must find: an uneven pair (radii 1 and 0.8) and a bent trimer
// (0.8, 1, 0.8; its end balls apart, so that inclusion-exclusion with the
// two lenses is exact) turned 20 random ways, against those closed forms:
// 1e-12 (measured 6e-14; an 8-point rule on the depth's intervals, its
// halves agreeing by chance, once left 2e-10 and 7e-9).
TEST(BallUnion, AnUnevenPairAndATrimerTurnedAnyWayByInclusionExclusion) {
  const std::vector<Vec<3>> pair{{0.0, 0.0, 0.0}, {1.2, 0.8, 0.0}};
  const std::vector<double> pair_r{1.0, 0.8};
  const std::vector<Vec<3>> trimer{{-1.4, 0.0, 0.0}, {0.0, 0.0, 0.0}, {1.2, 0.8, 0.0}};
  const std::vector<double> trimer_r{0.8, 1.0, 0.8};
  auto ball = [](double r) { return 4.0 / 3.0 * pi * r * r * r; };
  const double pair_volume = ball(1.0) + ball(0.8) - lens_volume(1.0, 0.8, pair[1].norm());
  const double trimer_volume =
      2.0 * ball(0.8) + ball(1.0) - lens_volume(0.8, 1.0, 1.4) - lens_volume(1.0, 0.8, trimer[2].norm());
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < 20; ++k) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    auto turned = [&](std::vector<Vec<3>> c) {
      for (auto& x : c) x = q * x;
      return c;
    };
    worst = std::max(worst, std::abs(ball_union_moments<3>(turned(pair), pair_r).volume / pair_volume - 1.0));
    worst = std::max(worst,
                     std::abs(ball_union_moments<3>(turned(trimer), trimer_r).volume / trimer_volume - 1.0));
  }
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace darcydem
