// The excess pore pressure's thrust on walls: on a box wall that displaces
// the fluid, and on the barrier of an impermeable plate (pore_fluid.hpp).
#include <algorithm>
#include <array>
#include <stdexcept>

#include "darcydem/fluid/box_cell_overlap.hpp"
#include "darcydem/fluid/pore_fluid.hpp"

namespace darcydem {
namespace {

/// The section of `box` on the face normal to `axis` at x_f whose extent
/// along the other axes is that of the cell `c`, m^2 (2D: m): the box's
/// exact volume in the slab [x_f - eps, x_f + eps] over that extent, over
/// 2 eps. The section is linear in x within the slab unless a corner or
/// edge of the box lies in it, so this is its value at x_f, or the mean of
/// the two sides' where a face of the box lies on the plane. With eps a
/// millionth of the cell, the slab's volume loses about 1e-10 of itself to
/// round-off against the box's size.
template <int D>
double box_section(const SolidBox<D>& box, const FluidGrid<D>& grid, int axis, double x_f,
                   const std::array<int, D>& c) {
  const double eps = 1e-6 * grid.width(axis, std::clamp(c[axis], 0, grid.cells[axis] - 1));
  Vec<D> lo;
  Vec<D> hi;
  for (int k = 0; k < D; ++k) {
    lo[k] = k == axis ? x_f - eps : grid.face_at(k, c[k]);
    hi[k] = k == axis ? x_f + eps : grid.face_at(k, c[k] + 1);
  }
  const Vec<D> reach = box.bounding_half();
  for (int k = 0; k < D; ++k) {
    if (hi[k] < box.centre[k] - reach[k] || lo[k] > box.centre[k] + reach[k]) return 0.0;
  }
  return box_cell_volume(box, lo, hi) / (2.0 * eps);
}

}  // namespace

template <int D>
Vec<D> PoreFluid<D>::wall_thrust(const Wall<D>& wall) const {
  if (!initialized_) throw std::logic_error("PoreFluid::wall_thrust before initialize");
  if (wall.is_box) return box_thrust(SolidBox<D>{wall.point, wall.half, wall.axes});
  // A plane: the half-space behind it, its face kept a hundred-thousandth
  // of a cell inside the grid (ten times box_section's slab), so that a
  // plane on or beyond the side it faces takes that side's pressure; the
  // thrust is along its normal (the box's sides beyond the grid are dry).
  const int axis = grid_axis_of<D>(wall.normal);
  if (axis < 0) throw std::logic_error("PoreFluid::wall_thrust of a plane not normal to a grid axis");
  const int layer = wall.normal[axis] > 0.0 ? 0 : grid.cells[axis] - 1;
  const double inside = 1e-5 * grid.width(axis, layer);
  const auto box = behind_plane(grid, wall.point, wall.normal, inside);
  if (!box) return Vec<D>::Zero();
  return box_thrust(*box).dot(wall.normal) * wall.normal;
}

template <int D>
Vec<D> PoreFluid<D>::box_thrust(const SolidBox<D>& box) const {
  Vec<D> thrust = Vec<D>::Zero();
  // -(integral of grad u over the box's part in the grid), cell by cell.
  for_each_box_cell(grid, box, [&](const std::array<int, D>& c, double v) {
    if (v == 0.0) return;
    for (int k = 0; k < D; ++k) {
      auto up = c;
      ++up[k];
      const double g = 0.5 * (face_gq_[k][grid.face_index(k, c)][0] + face_gq_[k][grid.face_index(k, up)][0]);
      thrust[k] -= v * g;
    }
  });
  // Where it crosses a side: its section there times the side's pressure,
  // from the cell's and the face's gradient (on a drained face the imposed
  // value), along the side's outward normal.
  for (const BoundaryFace& bf : boundary_faces_) {
    const int axis = bf.side / 2;
    const bool upper = (bf.side & 1) != 0;
    const auto cc = grid.coords(bf.cell);
    const double x_f = grid.face_at(axis, upper ? cc[axis] + 1 : cc[axis]);
    const double section = box_section<D>(box, grid, axis, x_f, cc);
    if (section == 0.0) continue;
    const double g = face_gq_[axis][bf.index][0];
    const double u = upper ? pressure_[bf.cell] + g * bf.half : pressure_[bf.cell] - g * bf.half;
    thrust[axis] += (upper ? 1.0 : -1.0) * section * u;
  }
  // Where it crosses a barrier: its section times the jump across it.
  for (const BlockedFace& f : blocked_) {
    const auto cc = grid.coords(f.cell_below);
    const double x_f = grid.face_at(f.axis, cc[f.axis] + 1);
    const double section = box_section<D>(box, grid, f.axis, x_f, cc);
    if (section == 0.0) continue;
    thrust[f.axis] += section * (pressure_[f.cell_below] - pressure_[f.cell_below + grid.stride(f.axis)]);
  }
  return thrust;
}

template <int D>
Vec<D> PoreFluid<D>::barrier_thrust(std::size_t barrier) const {
  if (!initialized_) throw std::logic_error("PoreFluid::barrier_thrust before initialize");
  if (barrier >= barriers.size()) throw std::out_of_range("PoreFluid::barrier_thrust: no such barrier");
  Vec<D> thrust = Vec<D>::Zero();
  for (const BlockedFace& f : blocked_) {
    if (f.barrier != barrier) continue;
    const double area = grid.face_area(f.axis, grid.coords(f.cell_below));
    thrust[f.axis] += area * (pressure_[f.cell_below] - pressure_[f.cell_below + grid.stride(f.axis)]);
  }
  return thrust;
}

template Vec<2> PoreFluid<2>::wall_thrust(const Wall<2>&) const;
template Vec<3> PoreFluid<3>::wall_thrust(const Wall<3>&) const;
template Vec<2> PoreFluid<2>::barrier_thrust(std::size_t) const;
template Vec<3> PoreFluid<3>::barrier_thrust(std::size_t) const;

}  // namespace darcydem
