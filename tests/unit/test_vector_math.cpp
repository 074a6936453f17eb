// atan2_batch, atan_batch and power_law_batch against std::atan2, std::atan
// and std::pow: the vector library's documented accuracy
// is a few ulp; 4 ulp (relative 4 x 2^-52 ~ 8.9e-16 of the result, or of
// pi/2 for results near zero) is the bound asserted here. Every quadrant,
// signed zeros, and batch lengths that leave a tail of 1..3 values.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "darcydem/core/vector_math.hpp"

TEST(VectorMath, Atan2BatchMatchesTheScalarFunction) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  std::vector<double> y, x;
  for (int i = 0; i < 4000; ++i) {
    y.push_back(u(rng));
    x.push_back(u(rng));
  }
  // The first quadrant's edges as the overlaps use them, and tiny/huge ratios.
  for (double a : {0.0, 1e-300, 1e-12, 0.5, 1.0, 1e12}) {
    for (double b : {0.0, 1e-300, 1e-12, 0.5, 1.0, 1e12}) {
      y.push_back(a);
      x.push_back(b);
    }
  }
  const double eps = std::numeric_limits<double>::epsilon();
  for (std::size_t n : {y.size(), y.size() - 1, y.size() - 2, y.size() - 3, std::size_t{3}, std::size_t{0}}) {
    std::vector<double> out(n, std::nan(""));
    darcydem::atan2_batch(y.data(), x.data(), out.data(), n);
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ref = std::atan2(y[i], x[i]);
      worst = std::max(worst, std::abs(out[i] - ref) / std::max(std::abs(ref), 1.5707963267948966 * eps));
    }
    EXPECT_LE(worst, 4.0 * eps) << "n = " << n;
  }
}

TEST(VectorMath, Atan2BatchKeepsSignedZerosLikeTheScalarFunction) {
  // atan2(+0, -0) = pi and atan2(-0, +0) = -0: the overlaps rely on their
  // distances being +0 (ball_overlap.hpp); the batch must agree with std.
  const std::vector<double> y = {0.0, 0.0, -0.0, -0.0, 1.0};
  const std::vector<double> x = {0.0, -0.0, 0.0, -0.0, 0.0};
  std::vector<double> out(y.size());
  darcydem::atan2_batch(y.data(), x.data(), out.data(), y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    EXPECT_EQ(out[i], std::atan2(y[i], x[i])) << i;
    EXPECT_EQ(std::signbit(out[i]), std::signbit(std::atan2(y[i], x[i]))) << i;
  }
}

TEST(VectorMath, AtanBatchMatchesTheScalarFunction) {
  // The drag's blending function takes atan(262.5 (0.8 - n)) per cell, n in
  // [0, 1]: arguments from -52.5 to 210; also 0, +-1e-300, +-1e300 and
  // batch lengths that leave a tail. 4 ulp as for atan2.
  std::vector<double> x = {0.0, -0.0, 1e-300, -1e-300, 1e300, -1e300};
  for (int i = 0; i <= 4000; ++i) x.push_back(262.5 * (0.8 - 0.00025 * i));
  const double eps = std::numeric_limits<double>::epsilon();
  for (std::size_t n : {x.size(), x.size() - 1, x.size() - 2, x.size() - 3, std::size_t{3}, std::size_t{0}}) {
    std::vector<double> out(n, std::nan(""));
    darcydem::atan_batch(x.data(), out.data(), n);
    double worst = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double ref = std::atan(x[i]);
      if (ref == 0.0) {
        EXPECT_EQ(out[i], ref) << i;
        continue;
      }
      worst = std::max(worst, std::abs(out[i] - ref) / std::abs(ref));
    }
    EXPECT_LE(worst, 4.0 * eps) << "n = " << n;
  }
}

TEST(VectorMath, PowerLawBatchIsWithinItsErrorBound) {
  // exp(e ln x): the log's and the product's rounding (a few ulp of e ln x)
  // becomes a relative error of |e ln x| times that in the result, plus the
  // exp's own few ulp. With the vector library's 4 ulp per function, the
  // bound asserted is (4 + 5 |e ln x|) ulp; over the drag's range of Re
  // (1e-6 to 1e3) that is at most about 50 ulp (1.1e-14) for e = 0.687.
  // Also x = 0, where x^e is 0 for e > 0, as pow gives.
  std::vector<double> x = {0.0};
  for (int i = 1; i <= 3001; ++i) x.push_back(1e-6 * std::pow(10.0, 0.003 * i));
  const double eps = std::numeric_limits<double>::epsilon();
  for (double e : {0.687, -2.65}) {
    std::vector<double> out(x.size());
    darcydem::power_law_batch(x.data(), e, out.data(), x.size());
    double worst_over_bound = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double ref = std::pow(x[i], e);
      if (x[i] == 0.0) {
        EXPECT_EQ(out[i], ref) << "exponent " << e;
        continue;
      }
      const double bound = (4.0 + 5.0 * std::abs(e * std::log(x[i]))) * eps;
      worst_over_bound = std::max(worst_over_bound, std::abs(out[i] - ref) / ref / bound);
    }
    EXPECT_LE(worst_over_bound, 1.0) << "exponent " << e;
  }
}
