#include "darcydem/fluid/ball_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "darcydem/core/vec.hpp"

namespace darcydem::ball_overlap {
namespace {

constexpr double pi = std::numbers::pi;

double safe_sqrt(double v) { return std::sqrt(std::max(0.0, v)); }

/// Antiderivative of sqrt(s^2 - x^2) for |x| <= s.
double root_integral(double s, double x) {
  if (s <= 0.0) return 0.0;
  const double q = safe_sqrt(s * s - x * x);
  return 0.5 * (x * q + s * s * std::atan2(x, q));
}

/// Antiderivative in z of (r^2 - z^2) acos(beta / sqrt(r^2 - z^2)), valid for
/// |z| <= s = sqrt(r^2 - beta^2), beta >= 0. Integration by parts turns the
/// acos into algebraic terms, an asin and an atan.
double slice_integral(double r, double beta, double z) {
  const double s2 = r * r - beta * beta;
  const double q = safe_sqrt(s2 - z * z);
  // acos(beta / rho) and asin(z / s) as atan2 of exact legs: no loss of
  // accuracy where the slice just touches the plane (q -> 0).
  const double acos_term = beta == 0.0 ? 0.5 * pi : std::atan2(q, beta);
  const double asin_term = std::atan2(z, q);
  return (r * r * z - z * z * z / 3.0) * acos_term +
         beta / 3.0 * ((0.5 * s2 - 2.0 * r * r) * asin_term - 0.5 * z * q) +
         2.0 * r * r * r / 3.0 * std::atan2(z * beta, r * q);
}

/// Measure of the ball in {x_k > a_k} over the `count` constraints in `a`.
double upper(int dim, double r, std::array<double, 3> a, int count) {
  // Vacuous constraints go; any constraint beyond the ball empties it.
  int m = 0;
  for (int k = 0; k < count; ++k) {
    if (a[k] >= r) return 0.0;
    if (a[k] > -r) a[m++] = a[k];
  }
  count = m;
  for (int k = 0; k < count; ++k) {
    if (a[k] < 0.0) {
      // {x > a} = everything minus {x < a}, and {x < a} mirrors to {x > -a}.
      std::array<double, 3> without{};
      int w = 0;
      for (int j = 0; j < count; ++j) {
        if (j != k) without[w++] = a[j];
      }
      std::array<double, 3> mirrored = a;
      mirrored[k] = -a[k];
      return upper(dim, r, without, w) - upper(dim, r, mirrored, count);
    }
  }
  if (dim == 2) {
    switch (count) {
      case 0:
        return particle_volume<2>(r);
      case 1:
        return segment_area(r, a[0]);
      default:
        return corner_area(r, a[0], a[1]);
    }
  }
  switch (count) {
    case 0:
      return particle_volume<3>(r);
    case 1:
      return cap_volume(r, a[0]);
    case 2:
      return wedge_volume(r, a[0], a[1]);
    default:
      return octant_volume(r, a[0], a[1], a[2]);
  }
}

}  // namespace

double segment_area(double r, double a) {
  if (a >= r) return 0.0;
  if (a <= -r) return pi * r * r;
  const double h = safe_sqrt(r * r - a * a);
  return r * r * std::atan2(h, a) - a * h;
}

double corner_area(double r, double a, double b) {
  if (a * a + b * b >= r * r) return 0.0;
  const double hb = safe_sqrt(r * r - b * b);
  const double ha = safe_sqrt(r * r - a * a);
  return 0.5 * r * r * (std::atan2(hb, b) - std::atan2(a, ha)) - 0.5 * (b * hb + a * ha) + a * b;
}

double cap_volume(double r, double a) {
  if (a >= r) return 0.0;
  if (a <= -r) return particle_volume<3>(r);
  return pi * (r - a) * (r - a) * (2.0 * r + a) / 3.0;
}

double wedge_volume(double r, double a, double b) {
  if (a * a + b * b >= r * r) return 0.0;
  // Slices x = const from a to s_b: the disc of radius sqrt(r^2 - x^2) above
  // y = b, a circular segment.
  const double sb = std::sqrt(r * r - b * b);
  // At the upper end z = s_b the slice closes (q = 0): the antiderivatives
  // reduce to their limits, which saves four atan2 calls.
  const double upper = b > 0.0 ? b / 3.0 * (0.5 * sb * sb - 2.0 * r * r) * (0.5 * pi) + r * r * r / 3.0 * pi
                               : slice_integral(r, b, sb);
  return upper - slice_integral(r, b, a) - b * (0.25 * pi * sb * sb - root_integral(sb, a));
}

double octant_volume(double r, double a, double b, double c) {
  const double zm2 = r * r - a * a - b * b;
  if (zm2 <= c * c || zm2 <= 0.0) return 0.0;
  // Slices z = const from c to z_m: the corner of a disc of radius
  // rho = sqrt(r^2 - z^2) in {x > a, y > b}, whose area is
  //   rho^2/2 (acos(b/rho) - asin(a/rho)) - (b sqrt(rho^2-b^2) + a sqrt(rho^2-a^2))/2 + a b,
  // with asin(a/rho) = pi/2 - acos(a/rho).
  const double zm = std::sqrt(zm2);
  const double sa = std::sqrt(r * r - a * a);
  const double sb = std::sqrt(r * r - b * b);
  auto cubic = [&](double z) { return r * r * z - z * z * z / 3.0; };
  return 0.5 * (slice_integral(r, b, zm) - slice_integral(r, b, c)) +
         0.5 * (slice_integral(r, a, zm) - slice_integral(r, a, c)) - 0.25 * pi * (cubic(zm) - cubic(c)) -
         0.5 * b * (root_integral(sb, zm) - root_integral(sb, c)) -
         0.5 * a * (root_integral(sa, zm) - root_integral(sa, c)) + a * b * (zm - c);
}

template <int D>
double below(double r, const std::array<double, D>& t) {
  std::array<double, 3> a{};
  int count = 0;
  for (int k = 0; k < D; ++k) {
    if (t[k] == unbounded) continue;
    a[count++] = -t[k];  // {x < t} mirrors to {x > -t}
  }
  return upper(D, r, a, count);
}

template <int D>
double in_box(double r, const std::array<double, D>& centre, const std::array<double, D>& lo,
              const std::array<double, D>& hi) {
  double sum = 0.0;
  for (int corner = 0; corner < (1 << D); ++corner) {
    std::array<double, D> t{};
    int lows = 0;
    for (int k = 0; k < D; ++k) {
      const bool low = ((corner >> k) & 1) != 0;
      t[k] = (low ? lo[k] : hi[k]) - centre[k];
      lows += low ? 1 : 0;
    }
    sum += ((lows & 1) != 0 ? -1.0 : 1.0) * below<D>(r, t);
  }
  return sum;
}

template double below<2>(double, const std::array<double, 2>&);
template double below<3>(double, const std::array<double, 3>&);
template double in_box<2>(double, const std::array<double, 2>&, const std::array<double, 2>&,
                          const std::array<double, 2>&);
template double in_box<3>(double, const std::array<double, 3>&, const std::array<double, 3>&,
                          const std::array<double, 3>&);

}  // namespace darcydem::ball_overlap
