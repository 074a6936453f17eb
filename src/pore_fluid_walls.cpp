// The excess pore pressure's thrust on walls: on a box wall that displaces
// the fluid, and on the barrier of an impermeable plate (pore_fluid.hpp).
#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

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

/// f(c, area, fraction) for each cell c with c[k] in [from, to] whose
/// extent across k meets the axis-aligned box [lo, hi]: `area` is the
/// box's section over that extent, m^(D-1) (2D: m; possibly 0 where they
/// only touch), and `fraction` its part of the extent (exactly 1 where the
/// box spans it).
template <int D, class F>
void for_each_section(const FluidGrid<D>& grid, const Vec<D>& lo, const Vec<D>& hi, int k, int from, int to,
                      F&& f) {
  std::array<int, D> first{};
  std::array<int, D> last{};
  for (int j = 0; j < D; ++j) {
    first[j] = j == k ? from : std::max(grid.cell_along(j, lo[j]), 0);
    last[j] = j == k ? to : std::min(grid.cell_along(j, hi[j]), grid.cells[j] - 1);
    if (last[j] < first[j]) return;
  }
  std::array<int, D> c = first;
  while (true) {
    double area = 1.0;
    double fraction = 1.0;
    for (int j = 0; j < D; ++j) {
      if (j == k) continue;
      const double a = grid.face_at(j, c[j]);
      const double b = grid.face_at(j, c[j] + 1);
      const double overlap = std::max(0.0, std::min(b, hi[j]) - std::max(a, lo[j]));
      area *= overlap;
      fraction *= overlap / (b - a);
    }
    f(c, area, fraction);
    int j = 0;
    while (j < D && ++c[j] > last[j]) {
      c[j] = first[j];
      ++j;
    }
    if (j == D) return;
  }
}

}  // namespace

template <int D>
std::optional<SolidBox<D>> PoreFluid<D>::displaced_box(const Wall<D>& wall) const {
  if (wall.is_box()) return SolidBox<D>{wall.point, wall.half, wall.axes};
  // A plane: the half-space behind it, its face a hundred-thousandth of a
  // cell inside the grid (ten times box_section's slab) where the plane is
  // on or beyond the side it faces, so that it stands on that side: it
  // takes the side's pressure and, impermeable, closes it. The sliver
  // shrinks to nothing as the plane crosses the first layer (behind_plane),
  // so every move it makes into the grid displaces water: 1 - 1e-5 of its
  // volume there, all of it deeper in.
  const int axis = grid_axis_of<D>(wall.normal);
  if (axis < 0)
    throw std::logic_error("PoreFluid: a plane that displaces the fluid must be normal to a grid axis");
  const int layer = wall.normal[axis] > 0.0 ? 0 : grid.cells[axis] - 1;
  return behind_plane(grid, wall.point, wall.normal, 1e-5 * grid.width(axis, layer));
}

template <int D>
std::pair<Vec<D>, Vec<D>> PoreFluid<D>::planes_wet_region(const std::vector<Wall<D>>& walls,
                                                          std::size_t skip) const {
  Vec<D> lo = Vec<D>::Constant(-std::numeric_limits<double>::infinity());
  Vec<D> hi = Vec<D>::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t w : solid_walls) {
    if (w == skip || walls.at(w).is_box()) continue;
    const auto solid = displaced_box(walls[w]);
    if (!solid) continue;
    const int axis = grid_axis_of<D>(walls[w].normal);
    if (walls[w].normal[axis] > 0.0) {
      lo[axis] = std::max(lo[axis], solid->centre[axis] + solid->half[axis]);
    } else {
      hi[axis] = std::min(hi[axis], solid->centre[axis] - solid->half[axis]);
    }
  }
  return {lo, hi};
}

template <int D>
Vec<D> PoreFluid<D>::wall_thrust(const std::vector<Wall<D>>& walls, std::size_t w) const {
  if (!initialized_) throw std::logic_error("PoreFluid::wall_thrust before initialize");
  const Wall<D>& wall = walls.at(w);
  auto box = displaced_box(wall);
  if (!box) return Vec<D>::Zero();
  if (!wall.is_box()) {
    // Across its normal, only where the other planes leave water: a platen
    // between platens is wet over the section they bound.
    const auto [wet_lo, wet_hi] = planes_wet_region(walls, w);
    const int axis = grid_axis_of<D>(wall.normal);
    for (int k = 0; k < D; ++k) {
      if (k == axis) continue;
      const double from = std::max(box->centre[k] - box->half[k], wet_lo[k]);
      const double to = std::min(box->centre[k] + box->half[k], wet_hi[k]);
      if (!(to > from)) return Vec<D>::Zero();
      box->centre[k] = 0.5 * (from + to);
      box->half[k] = 0.5 * (to - from);
    }
  }
  const Vec<D> thrust = is_impermeable(w) ? sealed_box_thrust(*box) : box_thrust(*box);
  // On a plane, along its normal (the box's sides beyond the grid are dry).
  return wall.is_box() ? thrust : Vec<D>(thrust.dot(wall.normal) * wall.normal);
}

template <int D>
void PoreFluid<D>::compute_open_faces(const std::vector<Wall<D>>& walls) {
  // First the part of each face the walls cover now, in face_open_.
  for (int k = 0; k < D; ++k) {
    if (impermeable_walls.empty()) {
      face_open_[k].clear();
      face_covered_[k].clear();
    } else {
      face_open_[k].assign(grid.face_count(k), 0.0);
    }
  }
  for (std::size_t w : impermeable_walls) {
    const auto box = displaced_box(walls.at(w));
    if (!box) continue;
    if (box->axes != Eigen::Matrix<double, D, D>::Identity())
      throw std::logic_error("PoreFluid: an impermeable wall must lie along the grid's axes");
    const Vec<D> lo = box->centre - box->half;
    const Vec<D> hi = box->centre + box->half;
    for (int k = 0; k < D; ++k) {
      // The faces normal to k on or between the box's two faces, over the
      // cells whose sides the box reaches: covered by the box's section.
      int from = 0;
      while (from <= grid.cells[k] && grid.face_at(k, from) < lo[k]) ++from;
      int to = from - 1;
      while (to + 1 <= grid.cells[k] && grid.face_at(k, to + 1) <= hi[k]) ++to;
      for_each_section<D>(grid, lo, hi, k, from, to,
                          [&](const std::array<int, D>& c, double, double fraction) {
                            double& now = face_open_[k][grid.face_index(k, c)];
                            now = std::min(1.0, now + fraction);
                          });
    }
  }
  // A face is closed where a wall covered it at the last fluid step and
  // still does: a wall passing a face in this step moved the water between
  // them through it (or drew it in), which would otherwise be trapped.
  for (int k = 0; k < D; ++k) {
    if (face_open_[k].empty()) continue;
    if (face_covered_[k].size() != face_open_[k].size()) face_covered_[k] = face_open_[k];
    for (std::size_t f = 0; f < face_open_[k].size(); ++f) {
      const double now = face_open_[k][f];
      face_open_[k][f] = 1.0 - std::min(now, face_covered_[k][f]);
      face_covered_[k][f] = now;
    }
  }
}

template <int D>
Vec<D> PoreFluid<D>::sealed_box_thrust(const SolidBox<D>& box) const {
  const Vec<D> lo = box.centre - box.half;
  const Vec<D> hi = box.centre + box.half;
  Vec<D> thrust = Vec<D>::Zero();
  for (int k = 0; k < D; ++k) {
    for (const bool upper : {false, true}) {
      // The box's face normal to k on this side, wet on its outside.
      const double x = upper ? hi[k] : lo[k];
      const double g_lo = grid.face_at(k, 0);
      const double g_hi = grid.face_at(k, grid.cells[k]);
      if (upper ? !(x >= g_lo && x < g_hi) : !(x > g_lo && x <= g_hi)) continue;  // no water beyond
      // The layer of cells on the wet side.
      int layer = std::clamp(grid.cell_along(k, x), 0, grid.cells[k] - 1);
      if (!upper && layer > 0 && x <= grid.face_at(k, layer)) --layer;
      if (upper && layer + 1 < grid.cells[k] && x >= grid.face_at(k, layer + 1)) ++layer;
      // The wet cell's pressure: no water crosses the face, so the pressure
      // is flat towards it (du/dn = 0), and the cell's is the face's to
      // second order in the cell's width.
      for_each_section<D>(grid, lo, hi, k, layer, layer,
                          [&](const std::array<int, D>& c, double area, double) {
                            thrust[k] += (upper ? -1.0 : 1.0) * area * pressure_[grid.index(c)];
                          });
    }
  }
  return thrust;
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

template std::pair<Vec<2>, Vec<2>> PoreFluid<2>::planes_wet_region(const std::vector<Wall<2>>&,
                                                                   std::size_t) const;
template std::pair<Vec<3>, Vec<3>> PoreFluid<3>::planes_wet_region(const std::vector<Wall<3>>&,
                                                                   std::size_t) const;
template Vec<2> PoreFluid<2>::wall_thrust(const std::vector<Wall<2>>&, std::size_t) const;
template Vec<3> PoreFluid<3>::wall_thrust(const std::vector<Wall<3>>&, std::size_t) const;
template void PoreFluid<2>::compute_open_faces(const std::vector<Wall<2>>&);
template void PoreFluid<3>::compute_open_faces(const std::vector<Wall<3>>&);
template Vec<2> PoreFluid<2>::barrier_thrust(std::size_t) const;
template Vec<3> PoreFluid<3>::barrier_thrust(std::size_t) const;

}  // namespace darcydem
