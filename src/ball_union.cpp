// Moments of a union of balls (ball_union.hpp).
#include "darcydem/particles/ball_union.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <utility>

namespace darcydem {

namespace {

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
struct GaussLegendre {
  std::vector<double> node;
  std::vector<double> weight;
  explicit GaussLegendre(int n) : node(static_cast<std::size_t>(n)), weight(static_cast<std::size_t>(n)) {
    for (int i = 0; i < n; ++i) {
      double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
      double dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0;
        double p1 = x;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (x * p1 - p0) / (x * x - 1.0);
        const double dx = p1 / dp;
        x -= dx;
        if (std::abs(dx) < 1e-16) break;
      }
      node[static_cast<std::size_t>(i)] = x;
      weight[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
    }
  }
};

struct Disc {
  double x = 0.0;
  double y = 0.0;
  double r = 0.0;
};

/// A plane union's area and moments: area, x, y, x^2, y^2, xy.
using PlaneMoments = std::array<double, 6>;

/// The arcs of circle i that bound the union (angles in [0, 2 pi]).
std::vector<std::pair<double, double>> exposed_arcs(const std::vector<Disc>& discs, std::size_t i) {
  constexpr double turn = 2.0 * std::numbers::pi;
  const Disc& a = discs[i];
  std::vector<std::pair<double, double>> covered;
  for (std::size_t j = 0; j < discs.size(); ++j) {
    if (j == i) continue;
    const Disc& b = discs[j];
    const double d = std::hypot(b.x - a.x, b.y - a.y);
    if (d >= a.r + b.r) continue;
    if (d + a.r <= b.r) {
      // Inside b: no arc, unless the two are the same circle and i comes first.
      if (!(d == 0.0 && a.r == b.r && i < j)) return {};
      continue;
    }
    if (d + b.r <= a.r) continue;
    // The half angle of the arc inside b, from the chord's distance to a's
    // centre x = (d^2 + a^2 - b^2) / 2d and its half length h, each factor
    // of h^2 = (a - x)(a + x) free of cancellation (an acos near +-1 would
    // lose half the digits of a short arc's ends).
    const double a_minus_x = (b.r - d + a.r) * (b.r + d - a.r) / (2.0 * d);
    const double a_plus_x = (a.r + d - b.r) * (a.r + d + b.r) / (2.0 * d);
    const double half =
        std::atan2(std::sqrt(std::max(0.0, a_minus_x * a_plus_x)), 0.5 * (a_plus_x - a_minus_x));
    double lo = std::atan2(b.y - a.y, b.x - a.x) - half;
    lo -= turn * std::floor(lo / turn);
    const double hi = lo + 2.0 * half;
    if (hi > turn) {
      covered.emplace_back(lo, turn);
      covered.emplace_back(0.0, hi - turn);
    } else {
      covered.emplace_back(lo, hi);
    }
  }
  std::sort(covered.begin(), covered.end());
  std::vector<std::pair<double, double>> arcs;
  double from = 0.0;
  for (const auto& [lo, hi] : covered) {
    if (lo > from) arcs.emplace_back(from, lo);
    from = std::max(from, hi);
  }
  if (from < turn) arcs.emplace_back(from, turn);
  return arcs;
}

/// Green's theorem along the union's boundary, counter-clockwise on each
/// circle (the arcs round a hole then run clockwise about it, as they must).
PlaneMoments plane_moments(const std::vector<Disc>& discs, const GaussLegendre& rule) {
  PlaneMoments m{};
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const Disc& c = discs[i];
    for (const auto& [a, b] : exposed_arcs(discs, i)) {
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a) / (0.5 * std::numbers::pi))));
      const double h = (b - a) / pieces;
      for (int p = 0; p < pieces; ++p) {
        const double mid = a + (p + 0.5) * h;
        for (std::size_t q = 0; q < rule.node.size(); ++q) {
          const double t = mid + 0.5 * h * rule.node[q];
          const double w = 0.5 * h * rule.weight[q] * c.r;
          const double cs = std::cos(t);
          const double sn = std::sin(t);
          const double x = c.x + c.r * cs;
          const double y = c.y + c.r * sn;
          // dA: (x dy - y dx) / 2; x dA: x^2/2 dy; y dA: -y^2/2 dx;
          // x^2 dA: x^3/3 dy; y^2 dA: -y^3/3 dx; xy dA: x^2 y/2 dy.
          m[0] += w * 0.5 * (x * cs + y * sn);
          m[1] += w * 0.5 * x * x * cs;
          m[2] += w * 0.5 * y * y * sn;
          m[3] += w * x * x * x * cs / 3.0;
          m[4] += w * y * y * y * sn / 3.0;
          m[5] += w * 0.5 * x * x * y * cs;
        }
      }
    }
  }
  return m;
}

/// A slice's moments weighted for the volume integral: V, x, y, z, xx, yy,
/// zz, xy, xz, yz.
using SliceMoments = std::array<double, 10>;

SliceMoments slice_at(const std::vector<Vec<3>>& centres, const std::vector<double>& radii, double z,
                      const GaussLegendre& rule) {
  std::vector<Disc> discs;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    const double dz = z - centres[i].z();
    const double r2 = radii[i] * radii[i] - dz * dz;
    if (r2 > 0.0) discs.push_back({centres[i].x(), centres[i].y(), std::sqrt(r2)});
  }
  const PlaneMoments p = plane_moments(discs, rule);
  return {p[0], p[1], p[2], z * p[0], p[3], p[4], z * z * p[0], p[5], z * p[1], z * p[2]};
}

struct SliceIntegral {
  const std::vector<Vec<3>>& centres;
  const std::vector<double>& radii;
  const GaussLegendre& plane_rule;
  const GaussLegendre& depth_rule;
  double tolerance;  ///< per unit length of z

  SliceMoments rule(double a, double b) const {
    SliceMoments sum{};
    for (std::size_t q = 0; q < depth_rule.node.size(); ++q) {
      const double z = 0.5 * (a + b) + 0.5 * (b - a) * depth_rule.node[q];
      const SliceMoments s = slice_at(centres, radii, z, plane_rule);
      for (std::size_t k = 0; k < s.size(); ++k) sum[k] += 0.5 * (b - a) * depth_rule.weight[q] * s[k];
    }
    return sum;
  }

  /// Bisects until the rule on the halves agrees with the whole to the
  /// tolerance (depth 40: intervals down to 1e-12 of the span).
  SliceMoments adaptive(double a, double b, const SliceMoments& whole, int depth) const {
    const double m = 0.5 * (a + b);
    const SliceMoments left = rule(a, m);
    const SliceMoments right = rule(m, b);
    double change = 0.0;
    SliceMoments sum{};
    for (std::size_t k = 0; k < sum.size(); ++k) {
      sum[k] = left[k] + right[k];
      change = std::max(change, std::abs(sum[k] - whole[k]));
    }
    if (change <= tolerance * (b - a) || depth >= 40) return sum;
    const SliceMoments l = adaptive(a, m, left, depth + 1);
    const SliceMoments r = adaptive(m, b, right, depth + 1);
    for (std::size_t k = 0; k < sum.size(); ++k) sum[k] = l[k] + r[k];
    return sum;
  }
};

/// The moments of balls given about their bounding box's centre s, scaled
/// by its largest side L (so that every moment is of order one).
template <int D>
BallUnionMoments<D> scaled_moments(const std::vector<Vec<D>>& centres, const std::vector<double>& radii) {
  const GaussLegendre plane_rule(16);
  BallUnionMoments<D> out;
  if constexpr (D == 2) {
    std::vector<Disc> discs;
    for (std::size_t i = 0; i < centres.size(); ++i)
      discs.push_back({centres[i].x(), centres[i].y(), radii[i]});
    const PlaneMoments p = plane_moments(discs, plane_rule);
    out.volume = p[0];
    out.first = Vec<2>(p[1], p[2]);
    out.second << p[3], p[5], p[5], p[4];
  } else {
    const GaussLegendre depth_rule(16);
    const SliceIntegral integral{centres, radii, plane_rule, depth_rule, 1e-14};
    std::vector<double> breaks;
    for (std::size_t i = 0; i < centres.size(); ++i) {
      breaks.push_back(centres[i].z() - radii[i]);
      breaks.push_back(centres[i].z() + radii[i]);
    }
    std::sort(breaks.begin(), breaks.end());
    SliceMoments total{};
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
      if (!(breaks[b + 1] > breaks[b])) continue;
      const SliceMoments s =
          integral.adaptive(breaks[b], breaks[b + 1], integral.rule(breaks[b], breaks[b + 1]), 0);
      for (std::size_t k = 0; k < s.size(); ++k) total[k] += s[k];
    }
    out.volume = total[0];
    out.first = Vec<3>(total[1], total[2], total[3]);
    out.second << total[4], total[7], total[8], total[7], total[5], total[9], total[8], total[9], total[6];
  }
  return out;
}

}  // namespace

template <int D>
BallUnionMoments<D> ball_union_moments(const std::vector<Vec<D>>& centres, const std::vector<double>& radii) {
  if (centres.empty() || centres.size() != radii.size())
    throw std::invalid_argument("ball_union_moments: one radius per centre, at least one ball");
  Vec<D> lo = centres[0];
  Vec<D> hi = centres[0];
  for (std::size_t i = 0; i < centres.size(); ++i) {
    if (!(radii[i] > 0.0)) throw std::invalid_argument("ball_union_moments: radii must be > 0");
    lo = lo.cwiseMin(centres[i] - Vec<D>::Constant(radii[i]));
    hi = hi.cwiseMax(centres[i] + Vec<D>::Constant(radii[i]));
  }
  const Vec<D> s = 0.5 * (lo + hi);
  const double size = (hi - lo).maxCoeff();
  std::vector<Vec<D>> scaled(centres.size());
  std::vector<double> scaled_radii(radii.size());
  for (std::size_t i = 0; i < centres.size(); ++i) {
    scaled[i] = (centres[i] - s) / size;
    scaled_radii[i] = radii[i] / size;
  }
  const BallUnionMoments<D> m = scaled_moments<D>(scaled, scaled_radii);
  // Back to metres and about the origin: x = s + L x'.
  BallUnionMoments<D> out;
  const double l_d = std::pow(size, D);
  out.volume = m.volume * l_d;
  const Vec<D> first = m.first * l_d * size;  // about s
  out.first = first + out.volume * s;
  out.second = m.second * l_d * size * size + first * s.transpose() + s * first.transpose() +
               out.volume * s * s.transpose();
  return out;
}

template BallUnionMoments<2> ball_union_moments<2>(const std::vector<Vec<2>>&, const std::vector<double>&);
template BallUnionMoments<3> ball_union_moments<3>(const std::vector<Vec<3>>&, const std::vector<double>&);

}  // namespace darcydem
