// The Verlet list's bookkeeping: histories carried over a reordering of the
// particles (with the sign flip a history takes when the pair's members swap
// roles), and the cross-block slots that make force sums deterministic.
#include <gtest/gtest.h>

#include <vector>

#include "darcydem/neighbour/verlet_list.hpp"

namespace darcydem {
namespace {

// Three spheres in a row, 0-1 and 1-2 touching. The tangential history of a
// pair is the slip of its first member against its second; after the
// particles are renumbered (0, 1, 2) -> (2, 0, 1) the old pair (0, 1) is the
// new pair (1, 2), same order: same history; the old pair (1, 2) is the new
// pair (0, 2) with first and second swapped: the history changes sign.
TEST(VerletList, HistoriesFollowAReorderingWithTheirSign) {
  const std::vector<double> radius(3, 0.5e-3);
  std::vector<Vec<3>> x = {Vec<3>(0, 0, 0), Vec<3>(1e-3, 0, 0), Vec<3>(2e-3, 0, 0)};
  VerletList<3> list;
  list.build(x, radius, 1e-4, false);
  ASSERT_EQ(list.pair_count(), 2U);  // (0,1) and (1,2); 0 and 2 are 2 mm apart
  const Vec<3> h01(0, 1e-6, 0);
  const Vec<3> h12(0, 0, 2e-6);
  list.tangential[list.row_offset[0]] = h01;
  list.tangential[list.row_offset[1]] = h12;

  // New particle k is old particle order[k].
  const std::vector<std::uint32_t> order = {1, 2, 0};
  std::vector<Vec<3>> y = {x[1], x[2], x[0]};
  list.build(y, radius, 1e-4, false, &order);
  ASSERT_EQ(list.pair_count(), 2U);
  // New pairs: (0,1) = old (1,2); (0,2) = old (1,0), swapped.
  ASSERT_EQ(list.row_offset[1] - list.row_offset[0], 2U);
  EXPECT_EQ(list.neighbour[0], 1U);
  EXPECT_EQ(list.neighbour[1], 2U);
  EXPECT_EQ(list.tangential[0], h12);
  EXPECT_EQ(list.tangential[1], Vec<3>(-h01));
}

// Above the parallel threshold the particles are cut into several blocks;
// every pair whose second member lies in a later block has exactly one slot,
// and the reverse index lists each slot once, under its second member.
TEST(VerletList, CrossSlotsCoverExactlyThePairsAcrossBlocks) {
  std::vector<Vec<3>> x;
  for (int k = 0; k < 30; ++k) {
    for (int j = 0; j < 30; ++j) {
      for (int i = 0; i < 10; ++i) x.emplace_back(1e-3 * i, 1e-3 * j, 1e-3 * k);
    }
  }
  const std::vector<double> radius(x.size(), 0.5e-3);
  VerletList<3> list;
  list.build(x, radius, 1e-4, false);
  const auto n = static_cast<std::int64_t>(x.size());
  ASSERT_GT(list.block_count(), 1);
  std::size_t expected = 0;
  for (std::int64_t b = 0; b < list.block_count(); ++b) {
    const auto end = static_cast<std::uint32_t>(list.block_end(b, n));
    for (std::int64_t i = list.block_begin(b); i < end; ++i) {
      for (std::uint32_t k = list.row_offset[i]; k < list.row_offset[i + 1]; ++k) {
        expected += list.neighbour[k] >= end ? 1 : 0;
      }
    }
  }
  ASSERT_GT(expected, 0U);
  EXPECT_EQ(list.cross_count(), expected);
  std::vector<int> seen(list.cross_count(), 0);
  for (std::int64_t j = 0; j < n; ++j) {
    for (std::uint32_t q = list.cross_offset[j]; q < list.cross_offset[j + 1]; ++q)
      ++seen[list.cross_slot[q]];
  }
  for (int s : seen) EXPECT_EQ(s, 1);
}

}  // namespace
}  // namespace darcydem
