#include "darcydem/fluid/box_cell_overlap.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

namespace darcydem {
namespace {

/// A side of the cell: the points x with sign * x[axis] <= sign * at are kept.
struct CellSide {
  int axis = 0;
  double sign = 1.0;
  double at = 0.0;
  template <int D>
  [[nodiscard]] double beyond(const Vec<D>& x) const {
    return sign * (x[axis] - at);
  }
};

/// The point where the segment p-q (on either side) meets the side's plane;
/// its coordinate along the axis is set to the plane's exactly.
template <int D>
Vec<D> crossing(const Vec<D>& p, const Vec<D>& q, double dp, double dq, const CellSide& side) {
  Vec<D> x = p + (dp / (dp - dq)) * (q - p);
  x[side.axis] = side.at;
  return x;
}

/// Sutherland-Hodgman: the part of the closed polygon behind the side, in
/// order. Points on the plane (and where edges cross it) also go to `on`.
template <int D>
std::vector<Vec<D>> clip_polygon(const std::vector<Vec<D>>& polygon, const CellSide& side,
                                 std::vector<Vec<D>>* on) {
  std::vector<Vec<D>> out;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec<D>& p = polygon[i];
    const Vec<D>& q = polygon[(i + 1) % n];
    const double dp = side.beyond(p);
    const double dq = side.beyond(q);
    if (dp <= 0.0) {
      out.push_back(p);
      if (dp == 0.0 && on != nullptr) on->push_back(p);
    }
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      out.push_back(crossing(p, q, dp, dq, side));
      if (on != nullptr) on->push_back(out.back());
    }
  }
  return out;
}

/// The cell's sides, two per axis.
template <int D>
std::array<CellSide, 2 * D> sides_of(const Vec<D>& lo, const Vec<D>& hi) {
  std::array<CellSide, 2 * D> s{};
  for (int k = 0; k < D; ++k) {
    s[2 * k] = {k, -1.0, lo[k]};
    s[2 * k + 1] = {k, 1.0, hi[k]};
  }
  return s;
}

double rotated_area(const SolidBox<2>& box, const Vec<2>& lo, const Vec<2>& hi) {
  const Vec<2> a = box.axes.col(0) * box.half[0];
  const Vec<2> b = box.axes.col(1) * box.half[1];
  std::vector<Vec<2>> polygon = {box.centre - a - b, box.centre + a - b, box.centre + a + b,
                                 box.centre - a + b};
  for (const CellSide& side : sides_of<2>(lo, hi)) {
    polygon = clip_polygon<2>(polygon, side, nullptr);
    if (polygon.size() < 3) return 0.0;
  }
  // Shoelace.
  double twice = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec<2>& p = polygon[i];
    const Vec<2>& q = polygon[(i + 1) % polygon.size()];
    twice += p[0] * q[1] - p[1] * q[0];
  }
  return 0.5 * std::abs(twice);
}

/// The points of a convex polygon in a plane normal to `axis`, in order
/// round their mean.
std::vector<Vec<3>> ordered_in_plane(std::vector<Vec<3>> points, int axis) {
  Vec<3> mean = Vec<3>::Zero();
  for (const Vec<3>& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  const int u = (axis + 1) % 3;
  const int v = (axis + 2) % 3;
  std::sort(points.begin(), points.end(), [&](const Vec<3>& a, const Vec<3>& b) {
    return std::atan2(a[v] - mean[v], a[u] - mean[u]) < std::atan2(b[v] - mean[v], b[u] - mean[u]);
  });
  return points;
}

double rotated_volume(const SolidBox<3>& box, const Vec<3>& lo, const Vec<3>& hi) {
  // The box's corners, bit k of the index: + along its axis k.
  std::array<Vec<3>, 8> corner;
  for (int c = 0; c < 8; ++c) {
    corner[c] = box.centre;
    for (int k = 0; k < 3; ++k) corner[c] += (((c >> k) & 1) ? 1.0 : -1.0) * box.half[k] * box.axes.col(k);
  }
  // Its six faces, each a loop of corners.
  std::vector<std::vector<Vec<3>>> faces;
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3;
    const int v = (k + 2) % 3;
    for (int s = 0; s < 2; ++s) {
      const int base = s << k;
      faces.push_back({corner[base], corner[base | (1 << u)], corner[base | (1 << u) | (1 << v)],
                       corner[base | (1 << v)]});
    }
  }
  for (const CellSide& side : sides_of<3>(lo, hi)) {
    std::vector<std::vector<Vec<3>>> kept;
    std::vector<Vec<3>> cap;
    for (const auto& face : faces) {
      std::vector<Vec<3>> part = clip_polygon<3>(face, side, &cap);
      if (part.size() >= 3) kept.push_back(std::move(part));
    }
    if (cap.size() >= 3) kept.push_back(ordered_in_plane(std::move(cap), side.axis));
    faces = std::move(kept);
    if (faces.size() < 4) return 0.0;
  }
  // Tetrahedra from an inner point to the faces' triangles (a convex
  // polyhedron: each is positive, whatever way its face goes round).
  Vec<3> inner = Vec<3>::Zero();
  double count = 0.0;
  for (const auto& face : faces) {
    for (const Vec<3>& p : face) inner += p;
    count += static_cast<double>(face.size());
  }
  inner /= count;
  double six = 0.0;
  for (const auto& face : faces) {
    const Vec<3> a = face[0] - inner;
    for (std::size_t i = 1; i + 1 < face.size(); ++i)
      six += std::abs(a.dot((face[i] - inner).cross(face[i + 1] - inner)));
  }
  return six / 6.0;
}

}  // namespace

template <int D>
bool SolidBox<D>::grid_aligned() const {
  for (int j = 0; j < D; ++j) {
    int nonzero = 0;
    for (int k = 0; k < D; ++k) nonzero += std::abs(axes(k, j)) > 1e-12 ? 1 : 0;
    if (nonzero != 1) return false;
  }
  return true;
}

template <int D>
double box_cell_volume(const SolidBox<D>& box, const std::type_identity_t<Vec<D>>& lo,
                       const std::type_identity_t<Vec<D>>& hi) {
  const Vec<D> reach = box.bounding_half();
  double aligned = 1.0;  // the bounding box's overlap with the cell
  for (int k = 0; k < D; ++k) {
    const double overlap =
        std::min(hi[k], box.centre[k] + reach[k]) - std::max(lo[k], box.centre[k] - reach[k]);
    if (overlap <= 0.0) return 0.0;
    aligned *= overlap;
  }
  if (box.grid_aligned()) return aligned;
  // All the box's corners inside the cell: the whole box.
  bool within = true;
  for (int k = 0; k < D; ++k)
    within = within && box.centre[k] - reach[k] >= lo[k] && box.centre[k] + reach[k] <= hi[k];
  if (within) return box.volume();
  if constexpr (D == 2) {
    return rotated_area(box, lo, hi);
  } else {
    return rotated_volume(box, lo, hi);
  }
}

template struct SolidBox<2>;
template struct SolidBox<3>;
template double box_cell_volume<2>(const SolidBox<2>&, const Vec<2>&, const Vec<2>&);
template double box_cell_volume<3>(const SolidBox<3>&, const Vec<3>&, const Vec<3>&);

}  // namespace darcydem
