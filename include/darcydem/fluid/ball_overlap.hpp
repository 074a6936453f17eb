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

#include "darcydem/core/lanes.hpp"

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
/// The inline closed forms below take T = double or T = Lanes (four balls
/// at once, core/lanes.hpp): the same formulas, with every case chosen by
/// `condition ? a : b` rather than a branch.
///
/// Distances are >= +0 (not -0: atan2(+0, -0) is pi, not 0).
/// For two planes at distances u, v (w = sqrt(r^2 - u^2 - v^2), the
/// half-chord where both planes meet the ball):
template <class T>
struct PairAnglesOf {
  T w{};
  T theta_u{};  ///< atan2(w, u)
  T theta_v{};  ///< atan2(w, v)
  T tau{};      ///< atan2(u v, r w)
};
using PairAngles = PairAnglesOf<double>;
/// The octant's own, for planes at a and b (zm = sqrt(r^2 - a^2 - b^2)):
template <class T>
struct OctantAnglesOf {
  T ab{};  ///< atan2(a, b)
  T zb{};  ///< atan2(zm b, r a)
  T za{};  ///< atan2(zm a, r b)
};
using OctantAngles = OctantAnglesOf<double>;
/// Both sets with std::atan2.
PairAngles pair_angles(double r, double u, double v);
OctantAngles octant_angles(double r, double a, double b);

// Inline: called per grain in the fluid's hot loop (pore_fluid_overlap.hpp).

/// 3D: volume of the sphere above the plane x = a.
template <class T>
inline T cap_volume(T r, T a) {
  constexpr double pi = std::numbers::pi;
  const T inside = pi * (r - a) * (r - a) * (2.0 * r + a) / 3.0;
  return a >= r ? 0.0 : (a <= -r ? 4.0 / 3.0 * pi * r * r * r : inside);
}

/// w of the pair (u, v), zero where the planes meet outside the ball.
template <class T>
inline T pair_chord(T r, T u, T v) {
  return lane_sqrt(lane_max(0.0, r * r - u * u - v * v));
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
template <class T>
inline T slice_integral(T r, T beta, T z, T q, T acos_term, T asin_term, T atan_term) {
  const T s2 = r * r - beta * beta;
  return (r * r * z - z * z * z / 3.0) * acos_term +
         beta / 3.0 * ((0.5 * s2 - 2.0 * r * r) * asin_term - 0.5 * z * q) +
         2.0 * r * r * r / 3.0 * atan_term;
}

/// R(s, z) from asin(z/s).
template <class T>
inline T root_integral(T s2, T z, T q, T asin_term) {
  return 0.5 * (z * q + s2 * asin_term);
}
}  // namespace detail

/// The wedge {x > a, y > b} from the angles of the pair (a, b), for
/// a^2 + b^2 < r^2 (no check: elsewhere the value is finite but
/// meaningless).
template <class T>
inline T wedge_volume_inside(T r, T a, T b, const PairAnglesOf<T>& ab) {
  constexpr double pi = std::numbers::pi;
  // Slices x = const from a to s_b = sqrt(r^2 - b^2): the disc of radius
  // sqrt(r^2 - x^2) above y = b, a circular segment. At the upper end the
  // slice closes and J reduces to its limit.
  const T sb2 = r * r - b * b;
  const T upper = b / 3.0 * (0.5 * sb2 - 2.0 * r * r) * (0.5 * pi) + r * r * r / 3.0 * pi;
  const T asin_a = 0.5 * pi - ab.theta_u;  // asin(a / s_b) = atan2(a, w)
  return upper - detail::slice_integral(r, b, a, ab.w, ab.theta_v, asin_a, ab.tau) -
         b * (0.25 * pi * sb2 - detail::root_integral(sb2, a, ab.w, asin_a));
}
/// The wedge {x > a, y > b} from the angles of the pair (a, b).
template <class T>
inline T wedge_volume(T r, T a, T b, const PairAnglesOf<T>& ab) {
  const T inside = wedge_volume_inside(r, a, b, ab);
  return a * a + b * b >= r * r ? 0.0 : inside;
}

/// The octant {x > a, y > b, z > c} from the angles of its three pairs and
/// its own, for a^2 + b^2 + c^2 < r^2 (no check, as wedge_volume_inside).
template <class T>
inline T octant_volume_inside(T r, T a, T b, T c, const PairAnglesOf<T>& ab, const PairAnglesOf<T>& ac,
                              const PairAnglesOf<T>& bc, const OctantAnglesOf<T>& o) {
  constexpr double pi = std::numbers::pi;
  // Slices z = const from c to z_m: the corner of a disc of radius
  // rho = sqrt(r^2 - z^2) in {x > a, y > b}, whose area is
  //   rho^2/2 (acos(b/rho) - asin(a/rho)) - (b sqrt(rho^2-b^2) + a sqrt(rho^2-a^2))/2 + a b,
  // with asin(a/rho) = pi/2 - acos(a/rho).
  const T zm = ab.w;
  const T sa2 = r * r - a * a;
  const T sb2 = r * r - b * b;
  // At z_m, acos(b/rho) = atan2(a, b) and acos(a/rho) = pi/2 - atan2(a, b)
  // (both pi/2 when a = b = 0, the limit of acos(0)).
  const auto both_zero = (a == 0.0) & (b == 0.0);
  const T acos_b_top = both_zero ? 0.5 * pi : o.ab;
  const T acos_a_top = both_zero ? 0.5 * pi : 0.5 * pi - o.ab;
  const T asin_c_b = 0.5 * pi - bc.theta_v;  // atan2(c, w_bc)
  const T asin_c_a = 0.5 * pi - ac.theta_v;  // atan2(c, w_ac)
  auto cubic = [&](T z) { return r * r * z - z * z * z / 3.0; };
  const T j_b = detail::slice_integral(r, b, zm, a, acos_b_top, ab.theta_u, o.zb) -
                detail::slice_integral(r, b, c, bc.w, bc.theta_u, asin_c_b, bc.tau);
  const T j_a = detail::slice_integral(r, a, zm, b, acos_a_top, ab.theta_v, o.za) -
                detail::slice_integral(r, a, c, ac.w, ac.theta_u, asin_c_a, ac.tau);
  const T r_b = detail::root_integral(sb2, zm, a, ab.theta_u) - detail::root_integral(sb2, c, bc.w, asin_c_b);
  const T r_a = detail::root_integral(sa2, zm, b, ab.theta_v) - detail::root_integral(sa2, c, ac.w, asin_c_a);
  return 0.5 * j_b + 0.5 * j_a - 0.25 * pi * (cubic(zm) - cubic(c)) - 0.5 * b * r_b - 0.5 * a * r_a +
         a * b * (zm - c);
}
/// The octant {x > a, y > b, z > c} from the angles of its three pairs and
/// its own.
template <class T>
inline T octant_volume(T r, T a, T b, T c, const PairAnglesOf<T>& ab, const PairAnglesOf<T>& ac,
                       const PairAnglesOf<T>& bc, const OctantAnglesOf<T>& o) {
  const T zm2 = r * r - a * a - b * b;
  const T inside = octant_volume_inside(r, a, b, c, ab, ac, bc, o);
  return (zm2 <= c * c) | (zm2 <= 0.0) ? 0.0 : inside;
}

/// Sections on the plane x_j = d_j (a disc of radius^2 rho2 = r^2 - d_j^2)
/// beyond one more plane at distance d_l (pair angles jl, with theta_l the
/// one of d_l) or two (d_l, d_m); zero where the planes miss the disc.
template <class T>
inline T section_beyond(T rho2, T d_l, const PairAnglesOf<T>& jl, T theta_l) {
  // Circular segment: rho^2 atan2(h, d_l) - d_l h, with h = w of the pair.
  const T v = rho2 * theta_l - d_l * jl.w;
  return d_l * d_l >= rho2 ? 0.0 : v;
}
template <class T>
inline T section_beyond(T rho2, T d_l, T d_m, const PairAnglesOf<T>& jl, T theta_l, const PairAnglesOf<T>& jm,
                        T theta_m) {
  // Corner of the disc (corner_area): h_l and h_m are the pairs' w, and
  // atan2(d_l, h_l) = pi/2 - theta_l.
  const T v = 0.5 * rho2 * (theta_m - (0.5 * std::numbers::pi - theta_l)) - 0.5 * (d_m * jm.w + d_l * jl.w) +
              d_l * d_m;
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
