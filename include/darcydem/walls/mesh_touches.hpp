#pragma once
// A particle's touches on the walls, one per contact list candidate, with
// whether each counts as a contact. Every wall but a mesh touches a
// particle once. A mesh can touch it on several facets, and near an edge or
// corner the facets that share it all reach the same surface: a grain
// resting on a flat mesh near an edge, or on a convex ridge, would be pushed
// twice. So a mesh's touches are taken nearest first, and a touch counts
// unless its nearest point lies on or behind the tangent plane of a nearer
// touch that counts (it is then part of the surface that touch already
// stands for). A grain in a concave corner touches each face of it; one on a
// flat or convex part of the surface touches it once, whichever facets it
// spans. When a touch that does not count had the contact's history (its
// tangential and rolling springs) and the one that shadows it has none, the
// history moves to it: a grain rolling across the facets of a flat mesh
// keeps its springs as on a plane.
#include <algorithm>
#include <array>
#include <cstdint>
#include <type_traits>
#include <vector>

#include "darcydem/walls/wall.hpp"

namespace darcydem {

/// Calls visit(k, touch, counts) for each wall candidate k of particle i
/// (centre x, radius r), in the list's order. `counts` is false for a
/// mesh's touch that a nearer one shadows; touches with gap >= r count (they
/// are not contacts anyway). With a non-const list, histories move as
/// described above.
template <int D, class List, class Visit>
void for_each_wall_touch(const std::vector<Wall<D>>& walls, List& list, std::size_t i, const Vec<D>& x,
                         double r, Visit&& visit) {
  using Touch = typename Wall<D>::Touch;
  const std::uint32_t end = list.offset[i + 1];
  for (std::uint32_t k = list.offset[i]; k < end;) {
    const Wall<D>& w = walls[list.wall[k]];
    if (!w.is_mesh()) {
      visit(k, w.touch(x), true);
      ++k;
      continue;
    }
    // The run of this mesh's candidates.
    std::uint32_t stop = k + 1;
    while (stop < end && list.wall[stop] == list.wall[k]) ++stop;
    constexpr std::uint32_t stack_size = 32;
    std::array<Touch, stack_size> touch_stack;
    std::array<std::uint32_t, stack_size> order_stack{};
    std::array<bool, stack_size> counts_stack{};
    std::vector<Touch> touch_heap;
    std::vector<std::uint32_t> order_heap;
    std::vector<char> counts_heap;
    const std::uint32_t m = stop - k;
    const bool heap = m > stack_size;
    if (heap) {
      touch_heap.resize(m);
      order_heap.resize(m);
      counts_heap.assign(m, 1);
    }
    Touch* touch = heap ? touch_heap.data() : touch_stack.data();
    std::uint32_t* order = heap ? order_heap.data() : order_stack.data();
    auto counts = [&](std::uint32_t j) -> bool { return heap ? counts_heap[j] != 0 : counts_stack[j]; };
    auto set_counts = [&](std::uint32_t j, bool c) {
      if (heap) {
        counts_heap[j] = c ? 1 : 0;
      } else {
        counts_stack[j] = c;
      }
    };
    std::uint32_t touching = 0;
    const Vec<D> local = w.to_local(x);
    for (std::uint32_t j = 0; j < m; ++j) {
      touch[j] = w.facet_touch_local(local, list.facet[k + j]);
      set_counts(j, true);
      if (touch[j].gap < r) order[touching++] = j;
    }
    // Nearest first (ties by facet, for a result that does not depend on
    // the order the list holds them in).
    std::sort(order, order + touching, [&](std::uint32_t a, std::uint32_t b) {
      return touch[a].gap < touch[b].gap ||
             (touch[a].gap == touch[b].gap && list.facet[k + a] < list.facet[k + b]);
    });
    // Round-off in the nearest points' coordinates, well below any overlap.
    const double tolerance = 1e-9 * r;
    for (std::uint32_t a = 0; a < touching; ++a) {
      const std::uint32_t j = order[a];
      const Vec<D> cj = x - touch[j].gap * touch[j].normal;
      for (std::uint32_t b = 0; b < a; ++b) {
        const std::uint32_t i_kept = order[b];
        if (!counts(i_kept)) continue;
        const Vec<D> ci = x - touch[i_kept].gap * touch[i_kept].normal;
        if ((cj - ci).dot(touch[i_kept].normal) > tolerance) continue;
        set_counts(j, false);
        if constexpr (!std::is_const_v<List>) {
          const std::uint32_t from = k + j;
          const std::uint32_t to = k + i_kept;
          if (list.tangential[to] == Vec<D>::Zero() && list.tangential[from] != Vec<D>::Zero()) {
            list.tangential[to] = list.tangential[from];
            list.tangential[from].setZero();
            if (!list.rolling.empty()) {
              list.rolling[to] = list.rolling[from];
              list.rolling[from].setZero();
            }
          }
        }
        break;
      }
    }
    for (std::uint32_t j = 0; j < m; ++j) visit(k + j, touch[j], counts(j));
    k = stop;
  }
}

}  // namespace darcydem
