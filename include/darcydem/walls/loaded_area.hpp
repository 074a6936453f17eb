#pragma once
// The area a plane wall loads the sample over, as a triaxial or biaxial
// test takes it (YADE's TriaxialStressController, PFC's servo walls): the
// sample's cross-section across the plane's normal, bounded by the other
// walls as they stand now. The plane's normal must be along an axis; the
// cross-section is then
// - 3D: the disc of a cylinder wall touched from inside whose axis is along
//   the normal (a triaxial cell's platen), pi R^2; otherwise
// - along each other axis, the distance between the plane wall facing up
//   it (normal +e_k: the sample's lower side) and the one facing down it
//   (normal -e_k), or the period along a periodic axis; their product
//   (2D: times the unit thickness, 1 m).
// A cylinder wall (a triaxial cell's confining wall) loads its lateral
// surface: 2 pi R times its height, the distance between the plane walls
// facing up and down its axis, or the period along it (2D: times 1 m).
// A stress-controlled servo loads such a wall with its target stress times
// this area, and the `wall_stress` probe divides the wall's load by it.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {

/// The area, m^2 (2D: per metre), or why the walls do not define one.
struct LoadedArea {
  double area = 0.0;
  std::string why_not;  ///< empty when `area` holds
};

/// The sample's extent along grid axis k, m: between the plane wall facing
/// +e_k and the one facing -e_k, or the period; `area` holds the length.
template <int D>
LoadedArea span_along(const std::vector<Wall<D>>& walls, int k, const PeriodicCell<D>& periodic) {
  static constexpr const char* axis_name[] = {"x", "y", "z"};
  if (periodic.periodic[k]) return {periodic.length[k], {}};
  int below = 0, above = 0;
  double lo = 0.0, hi = 0.0;
  for (const auto& o : walls) {
    if (!o.is_plane() || grid_axis_of<D>(o.normal) != k) continue;
    if (o.normal[k] > 0.0) {
      ++below;
      lo = o.point[k];
    } else {
      ++above;
      hi = o.point[k];
    }
  }
  const std::string along = axis_name[k];
  if (below != 1 || above != 1) {
    return {0.0, "the sample's extent along " + along + " needs one plane wall facing +" + along +
                     " and one facing -" + along + " (or a periodic " + along + "); there are " +
                     std::to_string(below) + " and " + std::to_string(above)};
  }
  if (!(hi > lo)) {
    return {0.0, "the plane walls bounding the sample along " + along + " have crossed (" +
                     std::to_string(lo) + " m facing +" + along + ", " + std::to_string(hi) + " m facing -" +
                     along + ")"};
  }
  return {hi - lo, {}};
}

/// The area walls[i] loads, from the walls as they are now: a plane's
/// cross-section, a cylinder's lateral surface.
template <int D>
LoadedArea loaded_area(const std::vector<Wall<D>>& walls, std::size_t i, const PeriodicCell<D>& periodic) {
  const Wall<D>& w = walls[i];
  if (w.is_cylinder()) {
    const double perimeter = 2.0 * std::numbers::pi * w.radius;
    if constexpr (D == 2) {
      return {perimeter * 1.0, {}};  // the unit thickness, m
    } else {
      const int a = grid_axis_of<D>(w.axis);
      if (a < 0) return {0.0, "its axis is not along x, y or z, so the walls do not bound its height"};
      LoadedArea h = span_along(walls, a, periodic);
      if (!h.why_not.empty()) return {0.0, "its height is not bounded: " + h.why_not};
      return {perimeter * h.area, {}};
    }
  }
  if (!w.is_plane())
    return {0.0,
            "a box wall has no loaded area (a plane's is its cross-section of the sample, a "
            "cylinder's its lateral surface)"};
  const int a = grid_axis_of<D>(w.normal);
  if (a < 0) return {0.0, "its normal is not along an axis, so the walls do not bound its cross-section"};
  if constexpr (D == 3) {
    int cylinders = 0;
    double area = 0.0;
    for (const auto& c : walls) {
      if (c.is_cylinder() && c.from_inside && std::abs(std::abs(c.axis.dot(w.normal)) - 1.0) <= 1e-9) {
        ++cylinders;
        area = std::numbers::pi * c.radius * c.radius;
      }
    }
    if (cylinders == 1) return {area, {}};
    if (cylinders > 1)
      return {0.0, "several cylinder walls run along its normal: its cross-section is ambiguous"};
  }
  double area = 1.0;  // 2D: the unit thickness, m
  for (int k = 0; k < D; ++k) {
    if (k == a) continue;
    const LoadedArea side = span_along(walls, k, periodic);
    if (!side.why_not.empty()) return {0.0, "its cross-section is not bounded: " + side.why_not};
    area *= side.area;
  }
  return {area, {}};
}

/// The particles' load on walls[i] over its loaded area, Pa (the probe
/// wall_stress): a plane's force against its normal, a cylinder's
/// radial_load; NaN where the walls bound no area.
template <int D>
double wall_stress(const std::vector<Wall<D>>& walls, std::size_t i, const PeriodicCell<D>& periodic) {
  const LoadedArea a = loaded_area(walls, i, periodic);
  if (!a.why_not.empty()) return std::numeric_limits<double>::quiet_NaN();
  const Wall<D>& w = walls[i];
  return (w.is_cylinder() ? w.radial_load : -w.force.dot(w.normal)) / a.area;
}

}  // namespace darcydem
