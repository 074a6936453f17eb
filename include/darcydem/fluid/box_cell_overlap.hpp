#pragma once
// The volume a box wall takes up in a fluid cell: a box with its own axes
// (possibly rotated) against an axis-aligned cell, exactly (to round-off).
// A box whose axes are the grid's (in any order and sense) is cut interval
// by interval; a rotated one is clipped as a convex polygon (2D) or
// polyhedron (3D) by the cell's sides, and its area or volume summed from
// triangles or tetrahedra about an inner point.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <type_traits>

#include <Eigen/Core>

#include "darcydem/core/vec.hpp"
#include "darcydem/fluid/fluid_grid.hpp"

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

/// The solid behind a plane wall normal to a grid axis (its normal points
/// into the domain, away from the solid), as a box: the half-space behind
/// the plane over the grid widened by the grid's own length on every side,
/// so that within the grid only the plane's face bounds it. `inside` (m,
/// >= 0, below the width of the grid's layer at the side the plane faces)
/// keeps the face that far into the grid where the plane is at or beyond
/// that side, so that the face stays in the grid; as the plane moves in
/// across that layer the offset shrinks in proportion, to none at the
/// layer's far face: the face moves with the plane at 1 - inside / width,
/// so every move of the plane into the grid displaces water, and a plane
/// deeper in has its face exactly on it. None if the half-space misses
/// the widened grid.
template <int D>
[[nodiscard]] std::optional<SolidBox<D>> behind_plane(const FluidGrid<D>& grid, const Vec<D>& point,
                                                      const Vec<D>& normal, double inside = 0.0) {
  const int a = grid_axis_of<D>(normal);
  if (a < 0) throw std::logic_error("behind_plane: the plane's normal is not along a grid axis");
  SolidBox<D> box;
  for (int k = 0; k < D; ++k) {
    const double lo = grid.face_at(k, 0);
    const double hi = grid.face_at(k, grid.cells[k]);
    const double margin = hi - lo;
    double from = lo - margin;
    double to = hi + margin;
    if (k == a) {
      // normal +e_a: solid below the plane; -e_a: above it.
      // How far the plane stands in the grid, over the first layer's width.
      const double first =
          normal[a] > 0.0 ? grid.face_at(a, 1) - lo : hi - grid.face_at(a, grid.cells[a] - 1);
      const double depth = std::max(normal[a] > 0.0 ? point[a] - lo : hi - point[a], 0.0);
      const double offset = inside * std::max(1.0 - depth / first, 0.0);
      if (normal[a] > 0.0) {
        to = std::max(point[a], lo) + offset;
      } else {
        from = std::min(point[a], hi) - offset;
      }
      if (!(to > from)) return std::nullopt;
    }
    box.centre[k] = 0.5 * (from + to);
    box.half[k] = 0.5 * (to - from);
  }
  return box;
}

/// Volume (2D: area x 1 m) of the box inside the cell [lo, hi], m^3.
template <int D>
[[nodiscard]] double box_cell_volume(const SolidBox<D>& box, const std::type_identity_t<Vec<D>>& lo,
                                     const std::type_identity_t<Vec<D>>& hi);

/// f(cell coordinates, volume) for each cell of `grid` that the box's
/// bounding box reaches, with the box's exact volume in it (possibly 0).
/// A box beyond the grid's ends takes up no cell there, also on a periodic
/// axis.
template <int D, class F>
void for_each_box_cell(const FluidGrid<D>& grid, const SolidBox<D>& box, F&& f) {
  const Vec<D> reach = box.bounding_half();
  std::array<int, D> lo{};
  std::array<int, D> hi{};
  for (int k = 0; k < D; ++k) {
    const int first = grid.cell_along(k, box.centre[k] - reach[k]);
    const int last = grid.cell_along(k, box.centre[k] + reach[k]);
    if (last < 0 || first >= grid.cells[k]) return;
    lo[k] = std::max(first, 0);
    hi[k] = std::min(last, grid.cells[k] - 1);
  }
  std::array<int, D> c = lo;
  while (true) {
    Vec<D> corner;
    Vec<D> far;
    for (int k = 0; k < D; ++k) {
      corner[k] = grid.face_at(k, c[k]);
      far[k] = grid.face_at(k, c[k] + 1);
    }
    f(c, box_cell_volume(box, corner, far));
    int k = 0;
    while (k < D && ++c[k] > hi[k]) {
      c[k] = lo[k];
      ++k;
    }
    if (k == D) return;
  }
}

}  // namespace darcydem
