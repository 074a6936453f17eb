#pragma once
// Half Verlet list (pairs i < j within r_i + r_j + skin), stored as rows in
// CSR form, with the contact history of each pair. Rebuilt only when some
// particle has moved more than half the skin; histories of pairs that survive
// a rebuild are carried over, also across a reordering of the particles.
//
// Deterministic parallel force sums without atomics: the particles are cut
// into fixed blocks of consecutive indices (the cut depends on N only, never
// on the thread count). A block's rows are evaluated in order by one thread,
// which adds j's share of a pair straight into j when j is in the same block.
// A pair whose j lies in a later block is a "cross" pair: its share for j is
// written to a slot, and each particle adds its slots afterwards in increasing
// slot order (reverse index). Every particle thus sums its forces in one fixed
// order whatever the number of threads. With particles sorted along the
// linked cells, blocks are compact and few pairs cross.
#include <cstdint>
#include <vector>

#include "darcydem/contact/contact_kernel.hpp"
#include "darcydem/core/vec.hpp"
#include "darcydem/neighbour/linked_cells.hpp"

namespace darcydem {

/// old_index's entry for a particle added since the last build (an inlet's
/// grain): it has no history to carry.
inline constexpr std::uint32_t no_old_index = 0xFFFFFFFFU;

/// Whether a list built for the particles of the last build (its offsets'
/// length `old_offsets`, the particle count + 1) can hand its histories to a
/// build for n particles: without old_index, when the count is the same;
/// with it, when every old index is in the old list or no_old_index
/// (particles may have been removed since, Simulation::has_domain, or
/// added, Simulation::add_particle).
inline bool old_list_fits(std::size_t old_offsets, std::size_t n,
                          const std::vector<std::uint32_t>* old_index) {
  if (old_offsets == 0) return false;
  if (old_index == nullptr) return old_offsets == n + 1;
  for (const std::uint32_t o : *old_index) {
    if (o != no_old_index && o + 1 >= old_offsets) return false;
  }
  return true;
}

template <int D>
class VerletList {
 public:
  /// Builds the list for the given particles, keeping old histories.
  /// old_index[i] (if given) is the index particle i had at the last build.
  /// With periodic axes a pair is listed once, at its partners' nearest
  /// images (the positions must be wrapped into the period). With `group`
  /// (one entry per particle), particles of the same group >= 0 (a clump's
  /// members) are never paired.
  void build(const std::vector<Vec<D>>& position, const std::vector<double>& radius, double skin,
             bool keep_rolling, const std::vector<std::uint32_t>* old_index = nullptr,
             const PeriodicCell<D>& cell = {}, const std::vector<std::int32_t>* group = nullptr);

  /// The particles in linked-cell order (cell by cell, x fastest), a
  /// permutation that makes neighbours close in memory.
  [[nodiscard]] std::vector<std::uint32_t> spatial_order(const std::vector<Vec<D>>& position,
                                                         const std::vector<double>& radius, double skin,
                                                         const PeriodicCell<D>& cell = {});

  /// Positions at the last build (for the displacement check).
  [[nodiscard]] const std::vector<Vec<D>>& reference() const { return reference_; }

  [[nodiscard]] std::size_t pair_count() const { return neighbour.size(); }
  /// Whether pair k is held by a contact bond.
  [[nodiscard]] bool is_bonded(std::size_t k) const { return !bonded.empty() && bonded[k] != 0; }
  [[nodiscard]] std::size_t cross_count() const { return cross_force.size(); }
  [[nodiscard]] std::size_t builds() const { return builds_; }
  [[nodiscard]] double cell_size() const { return cell_size_; }
  [[nodiscard]] std::int64_t block_count() const { return block_count_; }
  [[nodiscard]] std::int64_t block_begin(std::int64_t b) const { return b * block_size_; }
  [[nodiscard]] std::int64_t block_end(std::int64_t b, std::int64_t n) const {
    return (b + 1) * block_size_ < n ? (b + 1) * block_size_ : n;
  }
  /// The earliest block with a pair whose j lies in block b (b itself if
  /// none): block b's particles are read and their cross slots written by
  /// the blocks from there up to b.
  [[nodiscard]] std::int64_t earliest_source(std::int64_t b) const { return earliest_source_[b]; }
  /// The list, its histories and its build record, for a checkpoint (the
  /// linked cells are rebuilt at every build and are not kept).
  template <class Archive>
  void checkpoint(Archive& ar) {
    ar(row_offset, neighbour, tangential, rolling, bonded, bond_rotation, bond_strength, cross_begin,
       cross_force, cross_torque, cross_offset, cross_slot, reference_, builds_, cell_size_, block_size_,
       block_count_, earliest_source_);
  }
  /// Bytes held by the list's arrays (capacity), for memory reports.
  [[nodiscard]] std::size_t memory_bytes() const;

  // Rows: pairs of particle i are row_offset[i] .. row_offset[i+1]-1, by increasing j.
  std::vector<std::uint32_t> row_offset;
  std::vector<std::uint32_t> neighbour;  ///< j of each pair
  std::vector<Vec<D>> tangential;        ///< tangential spring history of each pair
  std::vector<AngVec<D>> rolling;        ///< rolling history (empty when unused)
  /// 1 for a pair held by a contact bond (empty until bonds are made,
  /// Simulation::make_bonds). A bonded pair that a build no longer lists
  /// (its grains more than the skin apart) loses its bond.
  std::vector<std::uint8_t> bonded;
  /// The relative rotation each bonded pair's bond has taken since it was
  /// made (empty unless a bond carries a moment, PairParameters::bond_has_moment).
  std::vector<BondRotation<D>> bond_rotation;
  /// Each bonded pair's factor on its strengths (empty unless the strengths
  /// vary, PairParameters::bond_strength_factor).
  std::vector<double> bond_strength;
  // Cross pairs: block b's are slots cross_begin[b] .. cross_begin[b+1]-1, in
  // the order its rows meet them.
  std::vector<std::uint32_t> cross_begin;
  std::vector<Vec<D>> cross_force;      ///< this step's force on j from each cross pair
  std::vector<AngVec<D>> cross_torque;  ///< this step's torque on j from each cross pair
  // Reverse index: the slots where particle j is second are
  // cross_slot[cross_offset[j] .. cross_offset[j+1]-1], increasing.
  std::vector<std::uint32_t> cross_offset;
  std::vector<std::uint32_t> cross_slot;

 private:
  LinkedCells<D> cells_;
  std::vector<Vec<D>> reference_;
  std::size_t builds_ = 0;
  double cell_size_ = 0.0;
  std::int64_t block_size_ = 1;
  std::int64_t block_count_ = 0;
  std::vector<std::int64_t> earliest_source_;
};

}  // namespace darcydem
