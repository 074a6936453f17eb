#include "darcydem/neighbour/linked_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

namespace darcydem {

template <int D>
void LinkedCells<D>::build(const std::vector<Vec<D>>& points, double cell_size, const PeriodicCell<D>& cell) {
  const std::size_t n = points.size();
  Vec<D> lo = Vec<D>::Constant(0.0);
  Vec<D> hi = Vec<D>::Constant(0.0);
  if (n > 0) {
    lo = points[0];
    hi = points[0];
    for (const auto& p : points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  if (!lo.allFinite() || !hi.allFinite()) {
    const auto bad =
        std::find_if(points.begin(), points.end(), [](const Vec<D>& p) { return !p.allFinite(); });
    throw std::runtime_error(
        fmt::format("the position of particle {} is not finite: the simulation blew up (forces too large for "
                    "the time step: check the contact stiffnesses, gravity and the pore fluid's values)",
                    bad - points.begin()));
  }
  periodic_ = cell.periodic;
  for (int k = 0; k < D; ++k) {
    if (periodic_[k]) lo[k] = cell.lower[k];
  }
  // Cells along an axis: a periodic one is tiled exactly (cells at least
  // `size` long), any other covers the points' spread.
  auto cells_along = [&](int k, double size) {
    if (periodic_[k]) return std::max(1.0, std::floor(cell.length[k] / size));
    return std::floor((hi[k] - lo[k]) / size) + 1.0;
  };
  // Limit the number of cells to a few per particle, whatever the spread.
  const double limit = std::max<double>(64.0, 4.0 * static_cast<double>(n));
  double size = cell_size;
  for (;;) {
    double count = 1.0;
    for (int k = 0; k < D; ++k) count *= cells_along(k, size);
    if (count <= limit) break;
    size *= 1.5;
  }
  origin_ = lo;
  std::int64_t total = 1;
  for (int k = 0; k < D; ++k) {
    dims_[k] = static_cast<int>(cells_along(k, size));
    inv_size_[k] = periodic_[k] ? dims_[k] / cell.length[k] : 1.0 / size;
    total *= dims_[k];
  }
  std::array<int, D> axes;
  for (int k = 0; k < D; ++k) axes[k] = k;
  std::stable_sort(axes.begin(), axes.end(), [&](int a, int b) { return dims_[a] < dims_[b]; });
  std::int64_t stride = 1;
  for (int a : axes) {
    stride_[a] = stride;
    stride *= dims_[a];
  }
  start_.assign(static_cast<std::size_t>(total) + 1, 0);
  cell_index_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<std::uint32_t>(flat(cell_of(points[i])));
    cell_index_[i] = c;
    ++start_[c + 1];
  }
  for (std::size_t c = 0; c + 1 < start_.size(); ++c) start_[c + 1] += start_[c];
  sorted_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) sorted_[fill[cell_index_[i]]++] = static_cast<std::uint32_t>(i);
}

template <int D>
std::array<int, D> LinkedCells<D>::cell_of(const Vec<D>& x) const {
  std::array<int, D> c;
  for (int k = 0; k < D; ++k) {
    const int v = static_cast<int>(std::floor((x[k] - origin_[k]) * inv_size_[k]));
    c[k] = periodic_[k] ? ((v % dims_[k]) + dims_[k]) % dims_[k] : std::clamp(v, 0, dims_[k] - 1);
  }
  return c;
}

template <int D>
std::int64_t LinkedCells<D>::flat(const std::array<int, D>& c) const {
  std::int64_t f = 0;
  for (int k = 0; k < D; ++k) f += c[k] * stride_[k];
  return f;
}

template class LinkedCells<2>;
template class LinkedCells<3>;

}  // namespace darcydem
