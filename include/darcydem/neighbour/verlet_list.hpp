#pragma once
// Half Verlet list (pairs i < j within r_i + r_j + skin), stored as rows in
// CSR form, with the contact history of each pair. Rebuilt only when some
// particle has moved more than half the skin; histories of pairs that survive
// a rebuild are carried over. A reverse index lists, for each particle j, the
// pairs where it is the second member, in increasing pair order, so that each
// particle sums its contact forces in a fixed order (no atomics, results
// independent of the thread count).
#include <cstdint>
#include <vector>

#include "darcydem/core/vec.hpp"
#include "darcydem/neighbour/linked_cells.hpp"

namespace darcydem {

template <int D>
class VerletList {
 public:
  /// Builds the list for the given particles, keeping old histories.
  void build(const std::vector<Vec<D>>& position, const std::vector<double>& radius, double skin,
             bool keep_rolling);

  /// Largest displacement of any particle since the last build (m).
  [[nodiscard]] double max_displacement(const std::vector<Vec<D>>& position) const;

  [[nodiscard]] std::size_t pair_count() const { return neighbour.size(); }
  [[nodiscard]] std::size_t builds() const { return builds_; }
  [[nodiscard]] double cell_size() const { return cell_size_; }

  // Rows: pairs of particle i are row_offset[i] .. row_offset[i+1]-1.
  std::vector<std::uint32_t> row_offset;
  std::vector<std::uint32_t> neighbour;  ///< j of each pair
  std::vector<Vec<D>> tangential;        ///< tangential spring history of each pair
  std::vector<AngVec<D>> rolling;        ///< rolling history (empty when unused)
  std::vector<Vec<D>> force_on_j;        ///< this step's force on j from each pair
  std::vector<AngVec<D>> torque_on_j;    ///< this step's torque on j from each pair
  // Reverse index: pairs where particle j is second are
  // reverse_pair[reverse_offset[j] .. reverse_offset[j+1]-1].
  std::vector<std::uint32_t> reverse_offset;
  std::vector<std::uint32_t> reverse_pair;

 private:
  LinkedCells<D> cells_;
  std::vector<Vec<D>> reference_;
  std::size_t builds_ = 0;
  double cell_size_ = 0.0;
};

}  // namespace darcydem
