#include "darcydem/fluid/ball_overlap.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "darcydem/core/vec.hpp"

namespace darcydem::ball_overlap {
namespace {

constexpr double pi = std::numbers::pi;

double safe_sqrt(double v) { return std::sqrt(std::max(0.0, v)); }

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
      mirrored[k] = 0.0 - a[k];
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

PairAngles pair_angles(double r, double u, double v) {
  const double w = pair_chord(r, u, v);
  return {w, std::atan2(w, u), std::atan2(w, v), std::atan2(u * v, r * w)};
}

OctantAngles octant_angles(double r, double a, double b) {
  const double zm = pair_chord(r, a, b);
  return {std::atan2(a, b), std::atan2(zm * b, r * a), std::atan2(zm * a, r * b)};
}

double wedge_volume(double r, double a, double b) { return wedge_volume(r, a, b, pair_angles(r, a, b)); }

double octant_volume(double r, double a, double b, double c) {
  return octant_volume(r, a, b, c, pair_angles(r, a, b), pair_angles(r, a, c), pair_angles(r, b, c),
                       octant_angles(r, a, b));
}

template <int D>
double below(double r, const std::array<double, D>& t) {
  std::array<double, 3> a{};
  int count = 0;
  for (int k = 0; k < D; ++k) {
    if (t[k] == unbounded) continue;
    // {x < t} mirrors to {x > -t}; 0 - t rather than -t, so that a face
    // through the centre gives +0: atan2 reads atan2(+0, -0) as pi.
    a[count++] = 0.0 - t[k];
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
