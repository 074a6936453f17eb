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
#include <array>
#include <limits>

namespace darcydem::ball_overlap {

inline constexpr double unbounded = std::numeric_limits<double>::infinity();

/// 2D: area of the disc of radius r above the line x = a.
double segment_area(double r, double a);
/// 2D: area of the disc in {x > a, y > b}, for a, b >= 0.
double corner_area(double r, double a, double b);
/// 3D: volume of the sphere above the plane x = a.
double cap_volume(double r, double a);
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
/// w of the pair (u, v), zero where the planes meet outside the ball.
double pair_chord(double r, double u, double v);
/// Both sets with std::atan2.
PairAngles pair_angles(double r, double u, double v);
OctantAngles octant_angles(double r, double a, double b);
/// The wedge {x > a, y > b} from the angles of the pair (a, b).
double wedge_volume(double r, double a, double b, const PairAngles& ab);
/// The octant {x > a, y > b, z > c} from the angles of its three pairs and
/// its own.
double octant_volume(double r, double a, double b, double c, const PairAngles& ab, const PairAngles& ac,
                     const PairAngles& bc, const OctantAngles& o);
/// Sections on the plane x_j = d_j (a disc of radius^2 rho2 = r^2 - d_j^2)
/// beyond one more plane at distance d_l (pair angles jl, with theta_l the
/// one of d_l) or two (d_l, d_m); zero where the planes miss the disc.
double section_beyond(double rho2, double d_l, const PairAngles& jl, double theta_l);
double section_beyond(double rho2, double d_l, double d_m, const PairAngles& jl, double theta_l,
                      const PairAngles& jm, double theta_m);

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
