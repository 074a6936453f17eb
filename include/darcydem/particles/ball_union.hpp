#pragma once
// The volume, first and second moments of a union of balls (2D: discs),
// which may overlap: what a clump of overlapping members weighs and how it
// turns. Each point of the union counts once.
//   2D: exactly, by Green's theorem along the arcs of the circles that
//       bound the union (each arc's integrand a trigonometric polynomial of
//       degree 4, integrated by Gauss-Legendre to round-off);
//   3D: the same for each slice z = const (a union of discs), integrated
//       over z by adaptive Gauss-Legendre (16 points; bisected until the
//       halves agree with the whole) between the balls' poles, to
//       about 1e-12 of the union's volume (the slices' moments have kinks
//       where two slice circles start to cross, which the adaptive
//       bisection resolves).
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct BallUnionMoments {
  double volume = 0.0;                                                       ///< m^3 (2D: m^2)
  Vec<D> first = Vec<D>::Zero();                                             ///< integral of x, m^4 (2D: m^3)
  Eigen::Matrix<double, D, D> second = Eigen::Matrix<double, D, D>::Zero();  ///< of x x^T
  [[nodiscard]] Vec<D> centroid() const { return first / volume; }
};

/// The moments of the union of the balls (centres, radii > 0) about the
/// origin.
template <int D>
BallUnionMoments<D> ball_union_moments(const std::vector<Vec<D>>& centres, const std::vector<double>& radii);

}  // namespace darcydem
