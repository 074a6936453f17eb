#pragma once
// Linked-cell binning: particles sorted into cubic cells of a given size by a
// counting sort, so that each cell's particles are contiguous and in
// increasing index order (deterministic neighbour order). Cells are numbered
// with the axis of fewest cells fastest and the axis of most cells slowest,
// so that a run of consecutive cells (and of particles sorted along them) is
// a compact slab across the domain's longest side, whatever its shape. Along
// a periodic axis the cells tile the period exactly and the neighbours of
// the last cell include the first.
#include <array>
#include <cstdint>
#include <vector>

#include "darcydem/core/periodic_cell.hpp"
#include "darcydem/core/vec.hpp"

namespace darcydem {

template <int D>
class LinkedCells {
 public:
  /// Bins the points; cell_size must be >= the largest interaction range.
  /// Along periodic axes the points must lie in the period (wrapped).
  void build(const std::vector<Vec<D>>& points, double cell_size, const PeriodicCell<D>& cell = {});

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

  /// Calls f(j) for every particle j in the 3^D cells around cell c (each
  /// cell once: a periodic axis of one or two cells has fewer neighbours).
  template <class F>
  void for_each_near(const std::array<int, D>& c, F&& f) const {
    std::array<std::array<int, 3>, D> near{};
    std::array<int, D> count{};
    for (int k = 0; k < D; ++k) {
      if (!periodic_[k]) {
        count[k] = 0;
        for (int v = c[k] > 0 ? c[k] - 1 : 0; v <= c[k] + 1 && v < dims_[k]; ++v) near[k][count[k]++] = v;
      } else if (dims_[k] >= 3) {
        near[k] = {(c[k] + dims_[k] - 1) % dims_[k], c[k], (c[k] + 1) % dims_[k]};
        count[k] = 3;
      } else {
        count[k] = dims_[k];
        near[k] = {0, 1, 0};
      }
    }
    if constexpr (D == 2) {
      for (int y = 0; y < count[1]; ++y) {
        for (int x = 0; x < count[0]; ++x) visit(flat({near[0][x], near[1][y]}), f);
      }
    } else {
      for (int z = 0; z < count[2]; ++z) {
        for (int y = 0; y < count[1]; ++y) {
          for (int x = 0; x < count[0]; ++x) visit(flat({near[0][x], near[1][y], near[2][z]}), f);
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
  Vec<D> inv_size_ = Vec<D>::Ones();  ///< cells per metre along each axis
  std::array<int, D> dims_{};
  std::array<bool, D> periodic_{};
  std::array<std::int64_t, D> stride_{};  ///< flat index = sum c[k] stride_[k]
  std::vector<std::uint32_t> start_;
  std::vector<std::uint32_t> sorted_;
  std::vector<std::uint32_t> cell_index_;  ///< per particle
};

}  // namespace darcydem
