#pragma once
// The fixed Cartesian grid of the pore fluid over a box, independent of the
// DEM neighbour cells: along each axis either cells of equal size (origin,
// spacing, cells) or graded cells between given face coordinates (`faces`,
// a rectilinear grid). Cell (i, j, k) has index i + nx (j + ny k). In 2D
// the cells are 1 m thick, like the discs.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
struct FluidGrid {
  Vec<D> origin = Vec<D>::Zero();   ///< m, lower corner
  Vec<D> spacing = Vec<D>::Ones();  ///< m, cell size along each axis
  std::array<int, D> cells{};       ///< number of cells along each axis
  /// Along a periodic axis the grid spans the period: its last layer of
  /// cells and its first are neighbours across the face at either end
  /// (face 0 and face `cells`, the same face), which is then not a boundary.
  std::array<bool, D> periodic{};
  /// Graded axes: faces[k] holds the cells[k] + 1 face coordinates along
  /// axis k, increasing (set them with set_faces, which makes origin[k] the
  /// first and cells[k] their count less one; spacing[k] is then NaN, so
  /// code that takes one size for the axis fails loudly). Empty: the axis
  /// is uniform, face i at origin[k] + i spacing[k].
  std::array<std::vector<double>, D> faces{};
  /// Per graded axis, where to start looking for the cell of a coordinate
  /// (cell_along): the axis cut into equal bins, as many as fit the
  /// narrowest cell (up to max_bins), each holding the cell that contains
  /// its start. A coordinate's cell is then its bin's or, when a bin is
  /// no wider than every cell, the next one: one comparison, not a search.
  std::array<std::vector<int>, D> bin_cell{};
  std::array<double, D> bins_per_metre{};
  static constexpr std::size_t max_bins = std::size_t{1} << 16;

  /// Makes axis k graded with faces at `at` (at least two, increasing).
  void set_faces(int k, std::vector<double> at) {
    origin[k] = at.front();
    cells[k] = static_cast<int>(at.size()) - 1;
    spacing[k] = std::numeric_limits<double>::quiet_NaN();
    faces[k] = std::move(at);
    const double span = faces[k].back() - faces[k].front();
    const auto bins = static_cast<std::size_t>(std::clamp(
        std::ceil(span / min_width(k)), static_cast<double>(cells[k]), static_cast<double>(max_bins)));
    bins_per_metre[k] = static_cast<double>(bins) / span;
    bin_cell[k].resize(bins);
    int i = 0;
    for (std::size_t b = 0; b < bins; ++b) {
      const double start = faces[k].front() + static_cast<double>(b) / bins_per_metre[k];
      while (i + 1 < cells[k] && faces[k][static_cast<std::size_t>(i) + 1] <= start) ++i;
      bin_cell[k][b] = i;
    }
  }
  [[nodiscard]] bool graded(int k) const { return !faces[k].empty(); }
  [[nodiscard]] bool any_graded() const {
    for (int k = 0; k < D; ++k) {
      if (graded(k)) return true;
    }
    return false;
  }
  /// Coordinate of face i (0 .. cells) along axis k, m.
  [[nodiscard]] double face_at(int k, int i) const {
    return graded(k) ? faces[k][static_cast<std::size_t>(i)] : origin[k] + i * spacing[k];
  }
  /// Width of cell layer i along axis k, m.
  [[nodiscard]] double width(int k, int i) const {
    return graded(k) ? faces[k][static_cast<std::size_t>(i) + 1] - faces[k][static_cast<std::size_t>(i)]
                     : spacing[k];
  }
  /// Coordinate of the centre of cell layer i along axis k, m.
  [[nodiscard]] double centre_at(int k, int i) const {
    return graded(k)
               ? 0.5 * (faces[k][static_cast<std::size_t>(i)] + faces[k][static_cast<std::size_t>(i) + 1])
               : origin[k] + (i + 0.5) * spacing[k];
  }
  /// The narrowest cell layer along axis k, m.
  [[nodiscard]] double min_width(int k) const {
    double w = std::numeric_limits<double>::infinity();
    for (int i = 0; i < cells[k]; ++i) w = std::min(w, width(k, i));
    return w;
  }
  /// Volume of cell c, m^3 (2D: area x 1 m).
  [[nodiscard]] double cell_volume(const std::array<int, D>& c) const {
    double v = 1.0;
    for (int k = 0; k < D; ++k) v *= width(k, c[k]);
    return v;
  }
  /// Area of the faces normal to `axis` of cell c, m^2 (2D: length x 1 m).
  [[nodiscard]] double face_area(int axis, const std::array<int, D>& c) const {
    double a = 1.0;
    for (int k = 0; k < D; ++k) a *= k == axis ? 1.0 : width(k, c[k]);
    return a;
  }
  /// Length of the grid along axis k, m.
  [[nodiscard]] double length(int k) const { return face_at(k, cells[k]) - face_at(k, 0); }

  [[nodiscard]] std::size_t size() const {
    std::size_t n = 1;
    for (int c : cells) n *= static_cast<std::size_t>(c);
    return n;
  }
  /// Volume of every cell of a grid without graded axes, m^3 (2D: area x 1 m).
  [[nodiscard]] double cell_volume() const { return spacing.prod(); }
  /// Area of every face normal to `axis` of a grid without graded axes, m^2.
  [[nodiscard]] double face_area(int axis) const { return cell_volume() / spacing[axis]; }
  [[nodiscard]] Vec<D> upper() const {
    Vec<D> u;
    for (int k = 0; k < D; ++k) u[k] = face_at(k, cells[k]);
    return u;
  }
  [[nodiscard]] std::size_t index(const std::array<int, D>& c) const {
    std::size_t i = 0;
    for (int k = D - 1; k >= 0; --k)
      i = i * static_cast<std::size_t>(cells[k]) + static_cast<std::size_t>(c[k]);
    return i;
  }
  [[nodiscard]] std::array<int, D> coords(std::size_t i) const {
    std::array<int, D> c{};
    for (int k = 0; k < D; ++k) {
      c[k] = static_cast<int>(i % static_cast<std::size_t>(cells[k]));
      i /= static_cast<std::size_t>(cells[k]);
    }
    return c;
  }
  [[nodiscard]] Vec<D> centre(const std::array<int, D>& c) const {
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = centre_at(k, c[k]);
    return x;
  }
  /// Cell coordinate along `axis` of position x: -1 below the grid, n above
  /// (clamped before the conversion, so a grain far away is still safe; a
  /// NaN position is -1).
  [[nodiscard]] int cell_along(int axis, double x) const {
    if (graded(axis)) {
      const auto& f = faces[axis];
      if (!(x >= f.front())) return -1;  // below, or NaN
      if (x >= f.back()) return cells[axis];
      const auto& bin = bin_cell[axis];
      const auto b =
          std::min(static_cast<std::size_t>((x - f.front()) * bins_per_metre[axis]), bin.size() - 1);
      // From the bin's cell, up past the faces at or below x (one at most
      // unless the bins were capped), and down should rounding have put x
      // in the bin after its own.
      auto i = static_cast<std::size_t>(bin[b]);
      while (f[i + 1] <= x) ++i;
      while (x < f[i]) --i;
      return static_cast<int>(i);
    }
    const double s = std::floor((x - origin[axis]) / spacing[axis]);
    return static_cast<int>(std::clamp(s, -1.0, static_cast<double>(cells[axis])));
  }
  /// Index of the cell holding x, a point on or inside the grid's box (on
  /// one of its sides: the outer cell there).
  [[nodiscard]] std::size_t cell_holding(const Vec<D>& x) const {
    std::array<int, D> c{};
    for (int k = 0; k < D; ++k) c[k] = std::clamp(cell_along(k, x[k]), 0, cells[k] - 1);
    return index(c);
  }
  /// The face (0 .. cells) along `axis` nearest to x.
  [[nodiscard]] int nearest_face(int axis, double x) const {
    if (!graded(axis)) return clamp_cell(std::round((x - origin[axis]) / spacing[axis]), 0, cells[axis]);
    int nearest = 0;
    for (int i = 1; i <= cells[axis]; ++i) {
      if (std::abs(face_at(axis, i) - x) < std::abs(face_at(axis, nearest) - x)) nearest = i;
    }
    return nearest;
  }
  /// x in cell units along `axis`: i + (x - face i) / width i in cell i,
  /// extended beyond the ends with the end cells' widths (NaN stays NaN).
  /// On a uniform axis (x - origin) / spacing.
  [[nodiscard]] double cell_units(int axis, double x) const {
    if (!graded(axis)) return (x - origin[axis]) / spacing[axis];
    const int i = std::clamp(cell_along(axis, x), 0, cells[axis] - 1);
    return i + (x - face_at(axis, i)) / width(axis, i);
  }
  /// Clamps a (possibly huge) floating cell coordinate into [lo, hi] and converts it.
  [[nodiscard]] static int clamp_cell(double s, int lo, int hi) {
    return static_cast<int>(std::clamp(s, static_cast<double>(lo), static_cast<double>(hi)));
  }
  /// A cell coordinate along `axis` one step beyond the grid, -1 or
  /// cells, wrapped onto the other end if the axis is periodic.
  [[nodiscard]] int wrapped(int axis, int c) const {
    if (!periodic[axis]) return c;
    return c < 0 ? c + cells[axis] : (c >= cells[axis] ? c - cells[axis] : c);
  }
  [[nodiscard]] bool any_periodic() const {
    for (bool p : periodic) {
      if (p) return true;
    }
    return false;
  }
  [[nodiscard]] bool inside(const std::array<int, D>& c) const {
    for (int k = 0; k < D; ++k) {
      if (c[k] < 0 || c[k] >= cells[k]) return false;
    }
    return true;
  }
  /// Number of faces normal to `axis` (including the two boundary layers).
  [[nodiscard]] std::size_t face_count(int axis) const {
    return size() / static_cast<std::size_t>(cells[axis]) * static_cast<std::size_t>(cells[axis] + 1);
  }
  /// Index of the face normal to `axis` at the lower side of cell c (c[axis]
  /// may equal cells[axis]: the upper boundary face).
  [[nodiscard]] std::size_t face_index(int axis, const std::array<int, D>& c) const {
    std::size_t i = 0;
    for (int k = D - 1; k >= 0; --k) {
      const auto n = static_cast<std::size_t>(k == axis ? cells[k] + 1 : cells[k]);
      i = i * n + static_cast<std::size_t>(c[k]);
    }
    return i;
  }
  /// Index step between neighbouring cells along `axis`.
  [[nodiscard]] std::size_t stride(int axis) const {
    std::size_t s = 1;
    for (int k = 0; k < axis; ++k) s *= static_cast<std::size_t>(cells[k]);
    return s;
  }
  /// A run of interior faces normal to an axis, side by side in memory: the
  /// cells a in [cell, cell + count), each below the face between a and its
  /// neighbour a + stride(axis), which is at face + (a - cell) in the face
  /// arrays of the axis (face_index).
  struct FaceRun {
    std::size_t cell = 0, count = 0, face = 0;
  };
  /// Number of runs of the interior faces normal to `axis`: one per line
  /// (axis 0) or layer of cells along it.
  [[nodiscard]] std::size_t face_runs(int axis) const {
    return size() / (stride(axis) * static_cast<std::size_t>(cells[axis]));
  }
  /// The r-th run of interior faces normal to `axis`.
  [[nodiscard]] FaceRun face_run(int axis, std::size_t r) const {
    const std::size_t inner = stride(axis);
    const auto m = static_cast<std::size_t>(cells[axis]);
    return {r * inner * m, inner * (m - 1), r * inner * (m + 1) + inner};
  }
};

/// Face coordinates of `cells` cells from `from` to `to` whose widths grow
/// (or shrink) geometrically, the last cell `ratio` times as wide as the
/// first: w_i = w_0 q^i, q = ratio^(1 / (cells - 1)). The ends are exact.
inline std::vector<double> graded_faces(double from, double to, int cells, double ratio) {
  const double q = cells > 1 ? std::pow(ratio, 1.0 / (cells - 1.0)) : 1.0;
  double total = 0.0;
  for (int i = 0; i < cells; ++i) total += std::pow(q, i);
  std::vector<double> faces{from};
  double sum = 0.0;
  for (int i = 0; i < cells; ++i) {
    sum += std::pow(q, i);
    faces.push_back(from + (to - from) * sum / total);
  }
  faces.back() = to;
  return faces;
}

/// The 2D faces of the grid's box: x_min, x_max, y_min, y_max, z_min, z_max.
inline constexpr const char* side_names[6] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};

}  // namespace darcydem
