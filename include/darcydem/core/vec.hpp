#pragma once
// Small vector types shared by the whole engine. Dimension D is 2 (discs of
// unit out-of-plane thickness) or 3 (spheres). In 2D, rotations are about the
// out-of-plane axis, so angular quantities are 1-component vectors.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace darcydem {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;

/// Number of rotational degrees of freedom: 1 for discs, 3 for spheres.
template <int D>
inline constexpr int rotation_dim = (D == 2) ? 1 : 3;

template <int D>
using AngVec = Eigen::Matrix<double, rotation_dim<D>, 1>;

/// a x b: the moment of force b about arm a.
inline AngVec<2> cross(const Vec<2>& a, const Vec<2>& b) { return AngVec<2>(a.x() * b.y() - a.y() * b.x()); }
inline Vec<3> cross(const Vec<3>& a, const Vec<3>& b) {
  return Vec<3>(a.y() * b.z() - a.z() * b.y(), a.z() * b.x() - a.x() * b.z(), a.x() * b.y() - a.y() * b.x());
}

/// w x r: the velocity of a point at arm r of a body spinning at w.
inline Vec<2> cross(const AngVec<2>& w, const Vec<2>& r) { return Vec<2>(-w[0] * r.y(), w[0] * r.x()); }

/// Volume of a particle of radius r: a disc of 1 m thickness in 2D (m^3).
template <int D>
constexpr double particle_volume(double radius) {
  if constexpr (D == 2) {
    return std::numbers::pi * radius * radius;
  } else {
    return 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  }
}

/// Moment of inertia factor: I = factor * m r^2 (1/2 disc, 2/5 sphere).
template <int D>
inline constexpr double inertia_factor = (D == 2) ? 0.5 : 0.4;

/// The axis a plane wall's normal lies along, or -1 if it lies along none
/// (its other components not all zero).
template <int D>
[[nodiscard]] int grid_axis_of(const Vec<D>& normal) {
  int axis = -1;
  for (int k = 0; k < D; ++k) {
    if (normal[k] == 0.0) continue;
    if (axis >= 0) return -1;
    axis = k;
  }
  return axis;
}

}  // namespace darcydem
