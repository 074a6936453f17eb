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
