#include "darcydem/neighbour/verlet_list.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

namespace darcydem {

template <int D>
void VerletList<D>::build(const std::vector<Vec<D>>& position, const std::vector<double>& radius, double skin,
                          bool keep_rolling) {
  const auto n = static_cast<std::int64_t>(position.size());
  double r_max = 0.0;
  for (double r : radius) r_max = std::max(r_max, r);
  cell_size_ = 2.0 * r_max + skin;
  cells_.build(position, cell_size_);

  auto for_each_partner = [&](std::int64_t i, auto&& emit) {
    const Vec<D>& xi = position[i];
    const double ri = radius[i] + skin;
    cells_.for_each_near(cells_.cell_of(xi), [&](std::uint32_t j) {
      if (j <= i) return;
      const double range = ri + radius[j];
      if ((position[j] - xi).squaredNorm() < range * range) emit(j);
    });
  };

  // Pass 1: row lengths; pass 2: fill. Both are independent per row.
  std::vector<std::uint32_t> offset(static_cast<std::size_t>(n) + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) if (n > 2000)
  for (std::int64_t i = 0; i < n; ++i) {
    std::uint32_t count = 0;
    for_each_partner(i, [&](std::uint32_t) { ++count; });
    offset[i + 1] = count;
  }
  for (std::int64_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
  const std::size_t pairs = offset[n];
  std::vector<std::uint32_t> next(pairs);
#pragma omp parallel for schedule(dynamic, 256) if (n > 2000)
  for (std::int64_t i = 0; i < n; ++i) {
    std::uint32_t k = offset[i];
    // Cells are visited in a fixed order and each cell lists particles in
    // increasing index, but sort anyway so rows are canonical.
    for_each_partner(i, [&](std::uint32_t j) { next[k++] = j; });
    std::sort(next.begin() + offset[i], next.begin() + offset[i + 1]);
  }

  // Carry the histories of surviving pairs over (rows are sorted by j).
  std::vector<Vec<D>> next_tangential(pairs, Vec<D>::Zero());
  std::vector<AngVec<D>> next_rolling(keep_rolling ? pairs : 0, AngVec<D>::Zero());
  const bool have_old = row_offset.size() == offset.size();
  if (have_old) {
    const bool old_rolling = keep_rolling && rolling.size() == neighbour.size();
#pragma omp parallel for schedule(dynamic, 256) if (n > 2000)
    for (std::int64_t i = 0; i < n; ++i) {
      std::uint32_t a = row_offset[i];
      const std::uint32_t a_end = row_offset[i + 1];
      for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) {
        while (a < a_end && neighbour[a] < next[k]) ++a;
        if (a < a_end && neighbour[a] == next[k]) {
          next_tangential[k] = tangential[a];
          if (old_rolling) next_rolling[k] = rolling[a];
        }
      }
    }
  }
  row_offset = std::move(offset);
  neighbour = std::move(next);
  tangential = std::move(next_tangential);
  rolling = std::move(next_rolling);
  force_on_j.assign(pairs, Vec<D>::Zero());
  torque_on_j.assign(pairs, AngVec<D>::Zero());

  // Reverse index by counting sort over j, pairs in increasing order.
  reverse_offset.assign(static_cast<std::size_t>(n) + 1, 0);
  for (std::uint32_t j : neighbour) ++reverse_offset[j + 1];
  for (std::int64_t i = 0; i < n; ++i) reverse_offset[i + 1] += reverse_offset[i];
  reverse_pair.resize(pairs);
  std::vector<std::uint32_t> fill(reverse_offset.begin(), reverse_offset.end() - 1);
  for (std::size_t p = 0; p < pairs; ++p) reverse_pair[fill[neighbour[p]]++] = static_cast<std::uint32_t>(p);

  reference_ = position;
  ++builds_;
}

namespace {
/// NaN would be ignored by max(): report it as an infinite displacement, so
/// the list is rebuilt and the rebuild reports the blown-up state.
inline double finite_or_inf(double v) { return std::isnan(v) ? std::numeric_limits<double>::infinity() : v; }
}  // namespace

template <int D>
double VerletList<D>::max_displacement(const std::vector<Vec<D>>& position) const {
  if (reference_.size() != position.size()) return 1e300;
  double m2 = 0.0;
  const auto n = static_cast<std::int64_t>(position.size());
  if (n > 2000) {
#pragma omp parallel for reduction(max : m2)
    for (std::int64_t i = 0; i < n; ++i)
      m2 = std::max(m2, finite_or_inf((position[i] - reference_[i]).squaredNorm()));
  } else {
    for (std::int64_t i = 0; i < n; ++i)
      m2 = std::max(m2, finite_or_inf((position[i] - reference_[i]).squaredNorm()));
  }
  return std::sqrt(m2);
}

template class VerletList<2>;
template class VerletList<3>;

}  // namespace darcydem
