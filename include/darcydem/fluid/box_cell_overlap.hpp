#pragma once
// The volume a box wall takes up in a fluid cell: a box with its own axes
// (possibly rotated) against an axis-aligned cell, exactly (to round-off).
// A box whose axes are the grid's (in any order and sense) is cut interval
// by interval; a rotated one is clipped as a convex polygon (2D) or
// polyhedron (3D) by the cell's sides, and its area or volume summed from
// triangles or tetrahedra about an inner point.
#include <type_traits>

#include <Eigen/Core>

#include "darcydem/core/vec.hpp"

namespace darcydem {

/// A solid box: centre, half-extents along its own axes, and those axes as
/// the columns of a rotation (Wall::point, Wall::half, Wall::axes).
template <int D>
struct SolidBox {
  Vec<D> centre = Vec<D>::Zero();
  Vec<D> half = Vec<D>::Zero();
  Eigen::Matrix<double, D, D> axes = Eigen::Matrix<double, D, D>::Identity();

  /// Half-extents of the axis-aligned box around it.
  [[nodiscard]] Vec<D> bounding_half() const { return axes.cwiseAbs() * half; }
  /// Area (2D, per metre of thickness) or volume, m^3.
  [[nodiscard]] double volume() const { return (2.0 * half).prod(); }
  /// Its axes are the grid's, each column one of +-e_k.
  [[nodiscard]] bool grid_aligned() const;
};

/// Volume (2D: area x 1 m) of the box inside the cell [lo, hi], m^3.
template <int D>
[[nodiscard]] double box_cell_volume(const SolidBox<D>& box, const std::type_identity_t<Vec<D>>& lo,
                                     const std::type_identity_t<Vec<D>>& hi);

}  // namespace darcydem
