#include "darcydem/neighbour/verlet_list.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "darcydem/core/parallel.hpp"

namespace darcydem {

namespace {
/// Blocks of about 6000 particles, an even number of them (two threads get
/// equal shares), each a multiple of 4 particles (the kicks take four at a
/// time); one block for small systems. Depends on n only.
std::int64_t block_size_for(std::int64_t n) {
  if (n <= parallel_threshold) return n > 0 ? n : 1;
  constexpr std::int64_t pair_of_blocks = 12288;
  const std::int64_t blocks = 2 * ((n + pair_of_blocks - 1) / pair_of_blocks);
  return ((n + blocks - 1) / blocks + 3) / 4 * 4;
}
}  // namespace

template <int D>
std::vector<std::uint32_t> VerletList<D>::spatial_order(const std::vector<Vec<D>>& position,
                                                        const std::vector<double>& radius, double skin,
                                                        const PeriodicCell<D>& cell) {
  double r_max = 0.0;
  for (double r : radius) r_max = std::max(r_max, r);
  cells_.build(position, 2.0 * r_max + skin, cell);
  return cells_.sorted();
}

template <int D>
void VerletList<D>::build(const std::vector<Vec<D>>& position, const std::vector<double>& radius, double skin,
                          bool keep_rolling, const std::vector<std::uint32_t>* old_index,
                          const PeriodicCell<D>& cell, const std::vector<std::int32_t>* group) {
  const auto n = static_cast<std::int64_t>(position.size());
  double r_max = 0.0;
  for (double r : radius) r_max = std::max(r_max, r);
  cell_size_ = 2.0 * r_max + skin;
  cells_.build(position, cell_size_, cell);
  block_size_ = block_size_for(n);
  block_count_ = (n + block_size_ - 1) / block_size_;

  auto for_each_partner = [&](std::int64_t i, auto&& emit) {
    const Vec<D>& xi = position[i];
    const double ri = radius[i] + skin;
    const std::int32_t gi = group != nullptr ? (*group)[i] : -1;
    cells_.for_each_near(cells_.cell_of(xi), [&](std::uint32_t j) {
      if (j <= i) return;
      if (gi >= 0 && (*group)[j] == gi) return;
      const double range = ri + radius[j];
      if (cell.shortest(position[j] - xi).squaredNorm() < range * range) emit(j);
    });
  };

  // Pass 1: row lengths; pass 2: fill. Both are independent per row.
  std::vector<std::uint32_t> offset(static_cast<std::size_t>(n) + 1, 0);
  for_each_index_dynamic(n, [&](std::int64_t i) {
    std::uint32_t count = 0;
    for_each_partner(i, [&](std::uint32_t) { ++count; });
    offset[i + 1] = count;
  });
  for (std::int64_t i = 0; i < n; ++i) offset[i + 1] += offset[i];
  const std::size_t pairs = offset[n];
  std::vector<std::uint32_t> next(pairs);
  for_each_index_dynamic(n, [&](std::int64_t i) {
    std::uint32_t k = offset[i];
    for_each_partner(i, [&](std::uint32_t j) { next[k++] = j; });
    std::sort(next.begin() + offset[i], next.begin() + offset[i + 1]);  // canonical rows
  });

  // Carry the histories of surviving pairs over. The old pair of new pair
  // (i, j) is (old i, old j) in its old order; a history is relative motion of
  // the first particle against the second, so it changes sign if they swapped.
  std::vector<Vec<D>> next_tangential(pairs, Vec<D>::Zero());
  std::vector<AngVec<D>> next_rolling(keep_rolling ? pairs : 0, AngVec<D>::Zero());
  const bool old_bonds = !bonded.empty() && bonded.size() == neighbour.size();
  std::vector<std::uint8_t> next_bonded(old_bonds ? pairs : 0, 0);
  const bool old_rotation = old_bonds && bond_rotation.size() == neighbour.size();
  std::vector<BondRotation<D>> next_rotation(old_rotation ? pairs : 0);
  const bool old_strength = old_bonds && bond_strength.size() == neighbour.size();
  std::vector<double> next_strength(old_strength ? pairs : 0, 1.0);
  if (old_list_fits(row_offset.size(), static_cast<std::size_t>(n), old_index)) {
    const bool old_rolling = keep_rolling && rolling.size() == neighbour.size();
    for_each_index_dynamic(n, [&](std::int64_t i) {
      const std::uint32_t oi = old_index != nullptr ? (*old_index)[i] : static_cast<std::uint32_t>(i);
      if (oi == no_old_index) return;
      for (std::uint32_t k = offset[i]; k < offset[i + 1]; ++k) {
        const std::uint32_t oj = old_index != nullptr ? (*old_index)[next[k]] : next[k];
        if (oj == no_old_index) continue;
        const std::uint32_t lo = std::min(oi, oj);
        const std::uint32_t hi = std::max(oi, oj);
        const auto row_begin = neighbour.begin() + row_offset[lo];
        const auto row_end = neighbour.begin() + row_offset[lo + 1];
        const auto it = std::lower_bound(row_begin, row_end, hi);
        if (it == row_end || *it != hi) continue;
        const auto a = static_cast<std::size_t>(it - neighbour.begin());
        const double sign = oi < oj ? 1.0 : -1.0;
        next_tangential[k] = sign * tangential[a];
        if (old_rolling) next_rolling[k] = sign * rolling[a];
        if (old_bonds) next_bonded[k] = bonded[a];
        if (old_strength) next_strength[k] = bond_strength[a];
        if (old_rotation) {
          // The bending turns with the pair's order; the twist about the
          // normal does not (both the rotation and the normal change sign).
          next_rotation[k].bending = sign * bond_rotation[a].bending;
          next_rotation[k].twist = bond_rotation[a].twist;
        }
      }
    });
  }
  row_offset = std::move(offset);
  neighbour = std::move(next);
  tangential = std::move(next_tangential);
  rolling = std::move(next_rolling);
  bonded = std::move(next_bonded);
  bond_rotation = std::move(next_rotation);
  bond_strength = std::move(next_strength);

  // Cross pairs, block by block in row order, and their reverse index.
  cross_begin.assign(static_cast<std::size_t>(block_count_) + 1, 0);
  for (std::int64_t b = 0; b < block_count_; ++b) {
    const auto end = static_cast<std::uint32_t>(block_end(b, n));
    std::uint32_t count = 0;
    for (std::int64_t i = block_begin(b); i < end; ++i) {
      for (std::uint32_t k = row_offset[i]; k < row_offset[i + 1]; ++k) count += neighbour[k] >= end ? 1 : 0;
    }
    cross_begin[b + 1] = cross_begin[b] + count;
  }
  const std::size_t crosses = cross_begin[block_count_];
  cross_force.assign(crosses, Vec<D>::Zero());
  cross_torque.assign(crosses, AngVec<D>::Zero());
  cross_offset.assign(static_cast<std::size_t>(n) + 1, 0);
  std::vector<std::uint32_t> partner(crosses);
  for (std::int64_t b = 0; b < block_count_; ++b) {
    const auto end = static_cast<std::uint32_t>(block_end(b, n));
    std::uint32_t slot = cross_begin[b];
    for (std::int64_t i = block_begin(b); i < end; ++i) {
      for (std::uint32_t k = row_offset[i]; k < row_offset[i + 1]; ++k) {
        if (neighbour[k] >= end) partner[slot++] = neighbour[k];
      }
    }
  }
  // The earliest block with a cross pair into each block.
  earliest_source_.resize(static_cast<std::size_t>(block_count_));
  for (std::int64_t b = 0; b < block_count_; ++b) earliest_source_[b] = b;
  for (std::int64_t b = 0; b < block_count_; ++b) {
    for (std::uint32_t s = cross_begin[b]; s < cross_begin[b + 1]; ++s) {
      auto& first = earliest_source_[partner[s] / block_size_];
      first = std::min(first, b);
    }
  }
  for (std::uint32_t j : partner) ++cross_offset[j + 1];
  for (std::int64_t i = 0; i < n; ++i) cross_offset[i + 1] += cross_offset[i];
  cross_slot.resize(crosses);
  std::vector<std::uint32_t> fill(cross_offset.begin(), cross_offset.end() - 1);
  for (std::size_t s = 0; s < crosses; ++s) cross_slot[fill[partner[s]]++] = static_cast<std::uint32_t>(s);

  reference_ = position;
  ++builds_;
}

template <int D>
std::size_t VerletList<D>::memory_bytes() const {
  auto bytes = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return bytes(row_offset) + bytes(neighbour) + bytes(tangential) + bytes(rolling) + bytes(bonded) +
         bytes(bond_rotation) + bytes(bond_strength) + bytes(cross_begin) + bytes(cross_force) +
         bytes(cross_torque) + bytes(cross_offset) + bytes(cross_slot) + bytes(reference_) +
         bytes(earliest_source_) + cells_.memory_bytes();
}

template class VerletList<2>;
template class VerletList<3>;

}  // namespace darcydem
