#pragma once
// Exact measure of a ball (a disc of unit thickness in 2D, a sphere in 3D)
// cut by axis-aligned planes. Everything is built on one function,
// below<D>(r, t): the measure of the ball of radius r centred at the origin
// that lies in {x_k < t_k for every k}. The part of a ball inside a box
// follows by inclusion-exclusion over the box's corners, so the parts in a
// row of cells telescope: they add up to the ball's measure to round-off,
// and each part changes continuously as the ball crosses a face.
//
// Closed forms (no quadrature): in 2D the circular segment and the corner
// of a disc; in 3D the spherical cap, the "wedge" {x > a, y > b} and the
// "octant" {x > a, y > b, z > c}, obtained by integrating the 2D corner
// area over slices (see docs/ARCHITECTURE.md).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace darcydem::ball_overlap {

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

/// 2D: area of the disc of radius r above the line x = a.
double segment_area(double r, double a);
/// 2D: area of the disc in {x > a, y > b}, for a, b >= 0.
double corner_area(double r, double a, double b);
/// 3D: volume of the sphere in {x > a, y > b}, for a, b >= 0.
double wedge_volume(double r, double a, double b);
/// 3D: volume of the sphere in {x > a, y > b, z > c}, for a, b, c >= 0.
double octant_volume(double r, double a, double b, double c);

/// The arctangents of the 3D closed forms, so that a caller can compute
/// them in batches (core/vector_math.hpp) and share them: the wedge of two
/// planes, the octant of three and the sections of the ball on its planes
/// all use the same few angles.
///
/// Distances are >= +0 (not -0: atan2(+0, -0) is pi, not 0).
/// For two planes at distances u, v (w = sqrt(r^2 - u^2 - v^2), the
/// half-chord where both planes meet the ball):
struct PairAngles {
  double w = 0.0;
  double theta_u = 0.0;  ///< atan2(w, u)
  double theta_v = 0.0;  ///< atan2(w, v)
  double tau = 0.0;      ///< atan2(u v, r w)
};
/// The octant's own, for planes at a and b (zm = sqrt(r^2 - a^2 - b^2)):
struct OctantAngles {
  double ab = 0.0;  ///< atan2(a, b)
  double zb = 0.0;  ///< atan2(zm b, r a)
  double za = 0.0;  ///< atan2(zm a, r b)
};
/// Both sets with std::atan2.
PairAngles pair_angles(double r, double u, double v);
OctantAngles octant_angles(double r, double a, double b);

// Inline: called per grain in the fluid's hot loop (pore_fluid_overlap.hpp).

/// 3D: volume of the sphere above the plane x = a.
inline double cap_volume(double r, double a) {
  if (a >= r) return 0.0;
  if (a <= -r) return 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return std::numbers::pi * (r - a) * (r - a) * (2.0 * r + a) / 3.0;
}

/// w of the pair (u, v), zero where the planes meet outside the ball.
inline double pair_chord(double r, double u, double v) {
  return std::sqrt(std::max(0.0, r * r - u * u - v * v));
}

namespace detail {
// The 3D closed forms integrate the 2D corner area over slices z = const
// (docs/ARCHITECTURE.md). With rho^2 = r^2 - z^2 and the plane at beta,
//   J(beta, z) = (r^2 z - z^3/3) acos(beta/rho)
//              + beta/3 ((s^2/2 - 2 r^2) asin(z/s) - z q/2) + 2 r^3/3 atan(z beta / (r q))
// is an antiderivative of (r^2 - z^2) acos(beta/rho) (s^2 = r^2 - beta^2,
// q = sqrt(s^2 - z^2)), and R(s, z) = (z q + s^2 asin(z/s))/2 one of
// sqrt(s^2 - z^2). Each acos, asin and atan is one of the pair or octant
// angles: at z = a below the plane beta = b, q is the pair's w; at the
// octant's top z = zm, q is the other plane's distance.

/// J(beta, z) from its three angles.
inline double slice_integral(double r, double beta, double z, double q, double acos_term, double asin_term,
                             double atan_term) {
  const double s2 = r * r - beta * beta;
  return (r * r * z - z * z * z / 3.0) * acos_term +
         beta / 3.0 * ((0.5 * s2 - 2.0 * r * r) * asin_term - 0.5 * z * q) +
         2.0 * r * r * r / 3.0 * atan_term;
}

/// R(s, z) from asin(z/s).
inline double root_integral(double s2, double z, double q, double asin_term) {
  return 0.5 * (z * q + s2 * asin_term);
}
}  // namespace detail

/// The wedge {x > a, y > b} from the angles of the pair (a, b), for
/// a^2 + b^2 < r^2 (no check: elsewhere the value is finite but
/// meaningless).
inline double wedge_volume_inside(double r, double a, double b, const PairAngles& ab) {
  constexpr double pi = std::numbers::pi;
  // Slices x = const from a to s_b = sqrt(r^2 - b^2): the disc of radius
  // sqrt(r^2 - x^2) above y = b, a circular segment. At the upper end the
  // slice closes and J reduces to its limit.
  const double sb2 = r * r - b * b;
  const double upper = b / 3.0 * (0.5 * sb2 - 2.0 * r * r) * (0.5 * pi) + r * r * r / 3.0 * pi;
  const double asin_a = 0.5 * pi - ab.theta_u;  // asin(a / s_b) = atan2(a, w)
  return upper - detail::slice_integral(r, b, a, ab.w, ab.theta_v, asin_a, ab.tau) -
         b * (0.25 * pi * sb2 - detail::root_integral(sb2, a, ab.w, asin_a));
}
/// The wedge {x > a, y > b} from the angles of the pair (a, b).
inline double wedge_volume(double r, double a, double b, const PairAngles& ab) {
  return a * a + b * b >= r * r ? 0.0 : wedge_volume_inside(r, a, b, ab);
}

/// The octant {x > a, y > b, z > c} from the angles of its three pairs and
/// its own, for a^2 + b^2 + c^2 < r^2 (no check, as wedge_volume_inside).
inline double octant_volume_inside(double r, double a, double b, double c, const PairAngles& ab,
                                   const PairAngles& ac, const PairAngles& bc, const OctantAngles& o) {
  constexpr double pi = std::numbers::pi;
  // Slices z = const from c to z_m: the corner of a disc of radius
  // rho = sqrt(r^2 - z^2) in {x > a, y > b}, whose area is
  //   rho^2/2 (acos(b/rho) - asin(a/rho)) - (b sqrt(rho^2-b^2) + a sqrt(rho^2-a^2))/2 + a b,
  // with asin(a/rho) = pi/2 - acos(a/rho).
  const double zm = ab.w;
  const double sa2 = r * r - a * a;
  const double sb2 = r * r - b * b;
  // At z_m, acos(b/rho) = atan2(a, b) and acos(a/rho) = pi/2 - atan2(a, b)
  // (both pi/2 when a = b = 0, the limit of acos(0)).
  const bool both_zero = (a == 0.0) & (b == 0.0);
  const double acos_b_top = both_zero ? 0.5 * pi : o.ab;
  const double acos_a_top = both_zero ? 0.5 * pi : 0.5 * pi - o.ab;
  const double asin_c_b = 0.5 * pi - bc.theta_v;  // atan2(c, w_bc)
  const double asin_c_a = 0.5 * pi - ac.theta_v;  // atan2(c, w_ac)
  auto cubic = [&](double z) { return r * r * z - z * z * z / 3.0; };
  const double j_b = detail::slice_integral(r, b, zm, a, acos_b_top, ab.theta_u, o.zb) -
                     detail::slice_integral(r, b, c, bc.w, bc.theta_u, asin_c_b, bc.tau);
  const double j_a = detail::slice_integral(r, a, zm, b, acos_a_top, ab.theta_v, o.za) -
                     detail::slice_integral(r, a, c, ac.w, ac.theta_u, asin_c_a, ac.tau);
  const double r_b =
      detail::root_integral(sb2, zm, a, ab.theta_u) - detail::root_integral(sb2, c, bc.w, asin_c_b);
  const double r_a =
      detail::root_integral(sa2, zm, b, ab.theta_v) - detail::root_integral(sa2, c, ac.w, asin_c_a);
  return 0.5 * j_b + 0.5 * j_a - 0.25 * pi * (cubic(zm) - cubic(c)) - 0.5 * b * r_b - 0.5 * a * r_a +
         a * b * (zm - c);
}
/// The octant {x > a, y > b, z > c} from the angles of its three pairs and
/// its own.
inline double octant_volume(double r, double a, double b, double c, const PairAngles& ab,
                            const PairAngles& ac, const PairAngles& bc, const OctantAngles& o) {
  const double zm2 = r * r - a * a - b * b;
  return zm2 <= c * c || zm2 <= 0.0 ? 0.0 : octant_volume_inside(r, a, b, c, ab, ac, bc, o);
}

/// Sections on the plane x_j = d_j (a disc of radius^2 rho2 = r^2 - d_j^2)
/// beyond one more plane at distance d_l (pair angles jl, with theta_l the
/// one of d_l) or two (d_l, d_m); zero where the planes miss the disc.
inline double section_beyond(double rho2, double d_l, const PairAngles& jl, double theta_l) {
  // Circular segment: rho^2 atan2(h, d_l) - d_l h, with h = w of the pair.
  const double v = rho2 * theta_l - d_l * jl.w;
  return d_l * d_l >= rho2 ? 0.0 : v;
}
inline double section_beyond(double rho2, double d_l, double d_m, const PairAngles& jl, double theta_l,
                             const PairAngles& jm, double theta_m) {
  // Corner of the disc (corner_area): h_l and h_m are the pairs' w, and
  // atan2(d_l, h_l) = pi/2 - theta_l.
  const double v = 0.5 * rho2 * (theta_m - (0.5 * std::numbers::pi - theta_l)) -
                   0.5 * (d_m * jm.w + d_l * jl.w) + d_l * d_m;
  return d_l * d_l + d_m * d_m >= rho2 ? 0.0 : v;
}

/// Measure (m^2 x 1 m in 2D, m^3 in 3D) of the ball of radius r at the
/// origin in {x_k < t_k}; t_k = unbounded drops that constraint.
template <int D>
double below(double r, const std::array<double, D>& t);

/// Measure of the ball of radius r centred at `centre` inside the box
/// [lo, hi].
template <int D>
double in_box(double r, const std::array<double, D>& centre, const std::array<double, D>& lo,
              const std::array<double, D>& hi);

}  // namespace darcydem::ball_overlap
