#pragma once
// Linked-cell binning: particles sorted into cubic cells of a given size by a
// counting sort, so that each cell's particles are contiguous and in
// increasing index order (deterministic neighbour order). Cells are numbered
// with the axis of fewest cells fastest and the axis of most cells slowest,
// so that a run of consecutive cells (and of particles sorted along them) is
// a compact slab across the domain's longest side, whatever its shape.
#include <array>
#include <cstdint>
#include <vector>

#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
class LinkedCells {
 public:
  /// Bins the points; cell_size must be >= the largest interaction range.
  void build(const std::vector<Vec<D>>& points, double cell_size);

  [[nodiscard]] std::array<int, D> cell_of(const Vec<D>& x) const;
  [[nodiscard]] std::int64_t flat(const std::array<int, D>& c) const;
  [[nodiscard]] const std::array<int, D>& dims() const { return dims_; }
  /// Particles of cell c: sorted_[start_[c]] .. sorted_[start_[c+1]-1].
  [[nodiscard]] const std::vector<std::uint32_t>& start() const { return start_; }
  [[nodiscard]] const std::vector<std::uint32_t>& sorted() const { return sorted_; }
  [[nodiscard]] const std::vector<std::uint32_t>& cell_index() const { return cell_index_; }
  [[nodiscard]] std::size_t memory_bytes() const {
    return (start_.capacity() + sorted_.capacity() + cell_index_.capacity()) * sizeof(std::uint32_t);
  }

  /// Calls f(j) for every particle j in the 3^D cells around cell c.
  template <class F>
  void for_each_near(const std::array<int, D>& c, F&& f) const {
    std::array<int, D> lo;
    std::array<int, D> hi;
    for (int k = 0; k < D; ++k) {
      lo[k] = c[k] > 0 ? c[k] - 1 : 0;
      hi[k] = c[k] + 1 < dims_[k] ? c[k] + 1 : dims_[k] - 1;
    }
    if constexpr (D == 2) {
      for (int y = lo[1]; y <= hi[1]; ++y) {
        for (int x = lo[0]; x <= hi[0]; ++x) {
          visit(flat({x, y}), f);
        }
      }
    } else {
      for (int z = lo[2]; z <= hi[2]; ++z) {
        for (int y = lo[1]; y <= hi[1]; ++y) {
          for (int x = lo[0]; x <= hi[0]; ++x) {
            visit(flat({x, y, z}), f);
          }
        }
      }
    }
  }

 private:
  template <class F>
  void visit(std::int64_t cell, F& f) const {
    for (std::uint32_t k = start_[cell]; k < start_[cell + 1]; ++k) f(sorted_[k]);
  }

  Vec<D> origin_ = Vec<D>::Zero();
  double inv_size_ = 1.0;
  std::array<int, D> dims_{};
  std::array<std::int64_t, D> stride_{};  ///< flat index = sum c[k] stride_[k]
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> sorted_;
  std::vector<std::uint32_t> cell_index_;  ///< per particle
};

}  // namespace darcydem
