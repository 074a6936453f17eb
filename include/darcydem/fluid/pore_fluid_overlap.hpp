#pragma once
// PoreFluid::for_each_overlap: how each grain's volume is shared among the
// cells it overlaps. Cells are at least one grain diameter wide (checked when
// the scene is read), so a grain crosses at most one face per axis. With d_k
// the distance from the centre to the crossed face along axis k, the part of
// the grain beyond the faces of a set T of axes is the cap, wedge or octant
// M(T) (ball_overlap.hpp), and the part in the cell reached by crossing
// exactly the faces of S follows by inclusion-exclusion (a Moebius
// transform over the subsets):
//   vol(S) = sum over T with S in T of (-1)^{|T| - |S|} M(T).
// The parts add up to the grain's volume (minus what lies outside the grid).
// Optionally it also reports the grain's cross-section on every face it
// crosses (the solid area through which it moves across that face).
//
// Grains are taken in chunks. Each grain is first cut against the grid
// (which faces it crosses; loops over the chunk, vectorised), then the
// grains of a chunk are filed by the set of axes they cross, and each set
// is processed by code compiled for it: no branch depends on a grain's
// position. A set's grains go four at a time on vector lanes
// (core/lanes.hpp) through the closed forms; in 3D the arctangents of the
// wedges, octants and sections are shared (ball_overlap::PairAngles) and
// computed together for the four (core/vector_math.hpp). Each grain's
// shares are then emitted one grain at a time.
#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "darcydem/core/lanes.hpp"
#include "darcydem/core/vector_math.hpp"
#include "darcydem/fluid/ball_overlap.hpp"
#include "darcydem/fluid/pore_fluid.hpp"

namespace darcydem {
namespace overlap_detail {

/// Where a grain lies on the fluid grid: its home cell and, per axis, the
/// neighbour across the nearer face and the distance to that face.
template <int D>
struct GrainCut {
  std::array<int, D> home{};
  std::array<int, D> other{};
  std::array<double, D> dist{};
};

/// The cuts of a chunk of grains, axis by axis (filled by loops over the
/// chunk that the compiler vectorises), and each grain's set of crossed
/// axes (bit k: axis k).
template <int D>
struct ChunkCuts {
  static constexpr std::size_t capacity = 256;
  std::array<std::array<int, capacity>, D> home;
  std::array<std::array<int, capacity>, D> other;
  std::array<std::array<double, capacity>, D> dist;
  std::array<int, capacity> mask;
  [[nodiscard]] GrainCut<D> of(std::size_t g) const {
    GrainCut<D> cut;
    for (int k = 0; k < D; ++k) {
      cut.home[k] = home[k][g];
      cut.other[k] = other[k][g];
      cut.dist[k] = dist[k][g];
    }
    return cut;
  }
};

/// Linear indices on the grid: of cells (FluidGrid::index) and of the faces
/// normal to each axis (FluidGrid::face_index), as strides per axis.
template <int D>
struct GridStrides {
  std::array<std::int64_t, D> cell{};
  std::array<std::array<std::int64_t, D>, D> face{};  ///< [normal axis][axis]
  explicit GridStrides(const FluidGrid<D>& grid) {
    std::int64_t c = 1;
    for (int k = 0; k < D; ++k) {
      cell[k] = c;
      c *= grid.cells[k];
    }
    for (int a = 0; a < D; ++a) {
      std::int64_t f = 1;
      for (int k = 0; k < D; ++k) {
        face[a][k] = f;
        f *= k == a ? grid.cells[k] + 1 : grid.cells[k];
      }
    }
  }
};

/// In place, m[S] <- sum over T containing S of (-1)^{|T|-|S|} m[T]: from
/// the measures beyond at least the planes of S to beyond exactly them.
template <int K, class T, std::size_t N>
inline void beyond_exactly(std::array<T, N>& m) {
  for (int j = 0; j < K; ++j) {
    for (int s = 0; s < (1 << K); ++s) {
      if ((s & (1 << j)) == 0) m[s] -= m[s | (1 << j)];
    }
  }
}

/// The j-th axis in Mask.
template <int Mask>
constexpr int axis_of(int j) {
  for (int k = 0; k < 3; ++k) {
    if ((Mask >> k) & 1) {
      if (j == 0) return k;
      --j;
    }
  }
  return -1;
}

/// Index of the pair (j, l), j < l, of crossing axes: (0,1) 0, (0,2) 1, (1,2) 2.
constexpr int pair_slot(int j, int l) { return j + l - 1; }

/// Where the cells (or faces) of a grain's subsets lie: the linear index
/// of the home one, the index step across each crossed plane, and whether
/// the home one and the one across each plane are inside the grid.
struct Reach {
  std::int64_t home = 0;
  std::array<std::int64_t, 3> shift{};
  bool home_in = true;
  std::array<bool, 3> home_l{};   ///< home inside along crossed axis j
  std::array<bool, 3> other_l{};  ///< the neighbour inside along crossed axis j
};

/// Emits value[s] for each subset s of the K crossed planes at
/// reach.home moved across the planes of s, where inside the grid.
template <int K, class E>
inline void emit_subsets(const Reach& reach, const std::array<double, 1 << K>& value, E&& emit) {
  for (int s = 0; s < (1 << K); ++s) {
    std::int64_t at = reach.home;
    bool inside = reach.home_in;
    for (int t = 0; t < K; ++t) {
      const bool moved = ((s >> t) & 1) != 0;
      at += moved ? reach.shift[t] : 0;
      inside = inside && (moved ? reach.other_l[t] : reach.home_l[t]);
    }
    if (value[s] > 0.0 && inside) emit(static_cast<std::size_t>(at), value[s]);
  }
}

/// The cells of a grain crossing the planes of `axes` (K of them).
template <int D, int K>
inline Reach cell_reach(const FluidGrid<D>& grid, const GridStrides<D>& strides, const GrainCut<D>& cut,
                        const std::array<int, 3>& axes) {
  Reach reach;
  for (int k = 0; k < D; ++k) {
    reach.home += static_cast<std::int64_t>(cut.home[k]) * strides.cell[k];
    bool crossed = false;
    for (int j = 0; j < K; ++j) crossed = crossed || axes[j] == k;
    if (!crossed) reach.home_in = reach.home_in && cut.home[k] >= 0 && cut.home[k] < grid.cells[k];
  }
  for (int j = 0; j < K; ++j) {
    const int k = axes[j];
    const int other = grid.wrapped(k, cut.other[k]);  // across a periodic end: the other end's layer
    reach.shift[j] = static_cast<std::int64_t>(other - cut.home[k]) * strides.cell[k];
    reach.home_l[j] = cut.home[k] >= 0 && cut.home[k] < grid.cells[k];
    reach.other_l[j] = other >= 0 && other < grid.cells[k];
  }
  return reach;
}

/// The faces normal to crossed axis J that the grain's section lies on:
/// the face between home and its neighbour along axes[J], moved across the
/// other crossed planes (inside the grid there if 0..cells-1; the face
/// itself is inside if 0..cells along its own axis). On a periodic axis the
/// face at an end is face 0 or face `cells`, whichever side the centre is
/// on: the two are one face, and each grain's section lands on one of them.
template <int D, int K, int J>
inline Reach face_reach(const FluidGrid<D>& grid, const GridStrides<D>& strides, const GrainCut<D>& cut,
                        const std::array<int, 3>& axes) {
  const int k = axes[J];
  const auto& fs = strides.face[k];
  const int along = std::max(cut.home[k], cut.other[k]);
  Reach reach;
  reach.home = static_cast<std::int64_t>(along) * fs[k];
  reach.home_in = along >= 0 && along <= grid.cells[k];
  for (int a = 0; a < D; ++a) {
    if (a == k) continue;
    reach.home += static_cast<std::int64_t>(cut.home[a]) * fs[a];
    bool crossed = false;
    for (int j = 0; j < K; ++j) crossed = crossed || axes[j] == a;
    if (!crossed) reach.home_in = reach.home_in && cut.home[a] >= 0 && cut.home[a] < grid.cells[a];
  }
  int t = 0;
  for (int j = 0; j < K; ++j) {
    if (j == J) continue;
    const int a = axes[j];
    const int other = grid.wrapped(a, cut.other[a]);
    reach.shift[t] = static_cast<std::int64_t>(other - cut.home[a]) * fs[a];
    reach.home_l[t] = cut.home[a] >= 0 && cut.home[a] < grid.cells[a];
    reach.other_l[t] = other >= 0 && other < grid.cells[a];
    ++t;
  }
  return reach;
}

/// The section of four grains on the plane of their J-th crossing axis: a
/// (D-1)-ball of radius rho = sqrt(r^2 - d_J^2), shared among the faces
/// beyond the other crossed planes in the same way as the volume among the
/// cells (subset bit t: the t-th other crossed axis).
template <int D, int K, int J>
inline std::array<Lanes, 1 << (K - 1)> section_measures(
    Lanes r, const std::array<Lanes, 3>& d, const std::array<ball_overlap::PairAnglesOf<Lanes>, 3>& pa) {
  namespace bo = ball_overlap;
  constexpr int others = K - 1;
  // The other crossing axes, in order.
  constexpr int L0 = J == 0 ? 1 : 0;
  constexpr int L1 = J == 2 ? 1 : 2;
  // The pair (J, l) and, in it, the angle of d_l.
  auto pair_of = [&](int l) -> const bo::PairAnglesOf<Lanes>& {
    return pa[pair_slot(std::min(J, l), std::max(J, l))];
  };
  auto theta = [&](int l) { return l > J ? pair_of(l).theta_v : pair_of(l).theta_u; };
  const Lanes rho2 = lane_max(0.0, r * r - d[J] * d[J]);
  std::array<Lanes, 1 << others> ms{};
  if constexpr (D == 2) {
    const Lanes rho = lane_sqrt(rho2);
    ms[0] = 2.0 * rho;
    if constexpr (others == 1) ms[1] = lane_max(0.0, rho - d[L0]);
  } else {
    ms[0] = std::numbers::pi * rho2;
    if constexpr (others >= 1) ms[1] = bo::section_beyond(rho2, d[L0], pair_of(L0), theta(L0));
    if constexpr (others == 2) {
      ms[2] = bo::section_beyond(rho2, d[L1], pair_of(L1), theta(L1));
      ms[3] = bo::section_beyond(rho2, d[L0], d[L1], pair_of(L0), theta(L0), pair_of(L1), theta(L1));
    }
  }
  beyond_exactly<others>(ms);
  return ms;
}

/// Lane l of each of the vectors.
template <std::size_t N>
inline std::array<double, N> lane_of(const std::array<Lanes, N>& v, int l) {
  std::array<double, N> out{};
  for (std::size_t s = 0; s < N; ++s) out[s] = v[s][l];
  return out;
}

/// The cuts along a graded axis k (FluidGrid::faces, not periodic) of the
/// grains [start, start + n): as the uniform axes' loop in for_each_overlap,
/// with the home cell from FluidGrid::cell_along; beyond the grid's
/// ends the home cell (-1 or cells) is as wide as the end cell.
template <int D>
void cut_graded_axis(const FluidGrid<D>& grid, int k, const ParticleData<D>& p, std::size_t start,
                     std::size_t n, ChunkCuts<D>& cuts) {
  const int last = grid.cells[k];
  for (std::size_t g = 0; g < n; ++g) {
    const double x = p.position[start + g][k];
    const int cell = grid.cell_along(k, x);  // -1 .. cells, -1 for NaN
    const double lo = cell >= 0 ? grid.face_at(k, cell) : grid.face_at(k, 0) - grid.width(k, 0);
    const double hi =
        cell < last ? grid.face_at(k, cell + 1) : grid.face_at(k, last) + grid.width(k, last - 1);
    const double r = p.radius[start + g];
    const double below = x - lo;
    const double above = hi - x;
    const int down = below < r ? 1 : 0;
    const int up = (1 - down) & (above < r ? 1 : 0);
    cuts.home[k][g] = cell;
    cuts.other[k][g] = cell + up - down;
    cuts.dist[k][g] = lane_max(0.0, down != 0 ? below : above);
    cuts.mask[g] = (k == 0 ? 0 : cuts.mask[g]) | ((down | up) << k);
  }
}

/// The grains `members` (indices into the chunk starting at `start`), which
/// all cross exactly the faces of the axes in Mask, four at a time: the
/// measures for four grains on vector lanes (the last group padded with
/// copies of its first grain, whose results are not used), then each
/// grain's cells and faces one by one.
template <int D, int Mask, class F, class G>
void cut_bucket(const FluidGrid<D>& grid, const GridStrides<D>& strides, const ParticleData<D>& p,
                const ChunkCuts<D>& cuts, const std::uint16_t* members, std::size_t count, std::size_t start,
                F& f, G& section, bool sections) {
  namespace bo = ball_overlap;
  constexpr int K = __builtin_popcount(Mask);
  constexpr int subsets = 1 << K;
  constexpr std::array<int, 3> axes = {axis_of<Mask>(0), axis_of<Mask>(1), axis_of<Mask>(2)};
  // Arctangents (3D), 3 per pair of crossing axes and 3 more for the octant.
  constexpr int pairs_count = K * (K - 1) / 2;
  constexpr int angles = D == 3 ? 3 * pairs_count + (K == 3 ? 3 : 0) : 0;
  for (std::size_t g0 = 0; g0 < count; g0 += lane_count) {
    const int used = static_cast<int>(std::min<std::size_t>(lane_count, count - g0));
    std::array<std::size_t, lane_count> g{};
    for (int l = 0; l < lane_count; ++l) g[l] = members[g0 + (l < used ? l : 0)];
    auto gather = [&](auto value) { return Lanes{value(g[0]), value(g[1]), value(g[2]), value(g[3])}; };
    const Lanes r = gather([&](std::size_t k) { return p.radius[start + k]; });
    std::array<Lanes, 3> d{};
    for (int j = 0; j < K; ++j) d[j] = gather([&](std::size_t k) { return cuts.dist[axes[j]][k]; });
    std::array<bo::PairAnglesOf<Lanes>, 3> pa{};
    bo::OctantAnglesOf<Lanes> oa{};
    if constexpr (angles > 0) {
      alignas(32) std::array<double, lane_count * angles> ys;
      alignas(32) std::array<double, lane_count * angles> xs;
      alignas(32) std::array<double, lane_count * angles> at;
      auto put = [&](int slot, Lanes y, Lanes x) {
        store_lanes(ys.data() + lane_count * slot, y);
        store_lanes(xs.data() + lane_count * slot, x);
      };
      for (int j = 0; j < K; ++j) {
        for (int l = j + 1; l < K; ++l) {
          const int s = pair_slot(j, l);
          const Lanes w = bo::pair_chord(r, d[j], d[l]);
          pa[s].w = w;
          put(3 * s, w, d[j]);
          put(3 * s + 1, w, d[l]);
          put(3 * s + 2, d[j] * d[l], r * w);
        }
      }
      if constexpr (K == 3) {
        const Lanes zm = pa[0].w;  // the chord of the pair (0, 1)
        put(9, d[0], d[1]);
        put(10, zm * d[1], r * d[0]);
        put(11, zm * d[0], r * d[1]);
      }
      atan2_batch(ys.data(), xs.data(), at.data(), lane_count * angles);
      auto angle = [&](int slot) { return load_lanes(at.data() + lane_count * slot); };
      for (int s = 0; s < pairs_count; ++s) {
        pa[s].theta_u = angle(3 * s);
        pa[s].theta_v = angle(3 * s + 1);
        pa[s].tau = angle(3 * s + 2);
      }
      if constexpr (K == 3) oa = {angle(9), angle(10), angle(11)};
    }
    // M(T) for every subset T of the crossing axes (bit j: axes[j]).
    std::array<Lanes, subsets> m{};
    for (int l = 0; l < lane_count; ++l) m[0][l] = particle_volume<D>(r[l]);
    if constexpr (D == 2) {
      for (int l = 0; l < lane_count; ++l) {
        for (int j = 0; j < K; ++j) m[1 << j][l] = bo::segment_area(r[l], d[j][l]);
        if constexpr (K == 2) m[3][l] = bo::corner_area(r[l], d[0][l], d[1][l]);
      }
    } else {
      for (int j = 0; j < K; ++j) m[1 << j] = bo::cap_volume(r, d[j]);
      for (int j = 0; j < K; ++j) {
        for (int l = j + 1; l < K; ++l)
          m[(1 << j) | (1 << l)] = bo::wedge_volume(r, d[j], d[l], pa[pair_slot(j, l)]);
      }
      if constexpr (K == 3) m[7] = bo::octant_volume(r, d[0], d[1], d[2], pa[0], pa[1], pa[2], oa);
    }
    beyond_exactly<K>(m);
    // The sections on the faces crossed.
    std::array<std::array<Lanes, (1 << K) / 2>, 3> ms{};
    if constexpr (K > 0) {
      if (sections) {
        ms[0] = section_measures<D, K, 0>(r, d, pa);
        if constexpr (K >= 2) ms[1] = section_measures<D, K, 1>(r, d, pa);
        if constexpr (K == 3) ms[2] = section_measures<D, K, 2>(r, d, pa);
      }
    }
    // Each grain's cells and faces.
    for (int l = 0; l < used; ++l) {
      const GrainCut<D> cut = cuts.of(members[g0 + l]);
      const std::size_t i = start + members[g0 + l];
      emit_subsets<K>(cell_reach<D, K>(grid, strides, cut, axes), lane_of(m, l),
                      [&](std::size_t cell, double v) { f(cell, i, v); });
      if constexpr (K > 0) {
        if (sections) {
          auto on = [&]<int J>() {
            constexpr int k = axes[J];
            emit_subsets<K - 1>(face_reach<D, K, J>(grid, strides, cut, axes), lane_of(ms[J], l),
                                [&](std::size_t face, double a) { section(k, face, i, a); });
          };
          on.template operator()<0>();
          if constexpr (K >= 2) on.template operator()<1>();
          if constexpr (K == 3) on.template operator()<2>();
        }
      }
    }
  }
}

}  // namespace overlap_detail

template <int D>
template <class F, class G>
void PoreFluid<D>::for_each_overlap(const ParticleData<D>& p, std::size_t begin, std::size_t end, F&& f,
                                    G&& section, bool sections) const {
  using overlap_detail::cut_bucket;
  using Cuts = overlap_detail::ChunkCuts<D>;
  constexpr std::size_t chunk = Cuts::capacity;
  constexpr int masks = 1 << D;
  auto cuts = std::make_unique<Cuts>();
  std::array<std::vector<std::uint16_t>, masks> bucket;
  for (auto& b : bucket) b.resize(std::min(chunk, end - begin));
  const overlap_detail::GridStrides<D> strides(grid);
  for (std::size_t start = begin; start < end; start += chunk) {
    const std::size_t n = std::min(end, start + chunk) - start;
    const double* radius = p.radius.data() + start;
    // The next chunk's grains are fetched into the cache while this one is
    // computed. After a DEM step they are mostly out of the cache, and the
    // velocities, read grain by grain in the order of the sets, would
    // otherwise each wait on memory.
    if (start + chunk < end) {
      const std::size_t next = start + chunk;
      const std::size_t m = std::min(end, next + chunk) - next;
      auto fetch = [](const void* data, std::size_t bytes) {
        const char* b = static_cast<const char*>(data);
        for (std::size_t at = 0; at < bytes; at += 64) __builtin_prefetch(b + at);
      };
      fetch(p.position.data() + next, m * sizeof(p.position[0]));
      fetch(p.velocity.data() + next, m * sizeof(p.velocity[0]));
      fetch(p.radius.data() + next, m * sizeof(double));
    }
    for (int k = 0; k < D; ++k) {
      if (grid.graded(k)) {
        cut_graded_axis(grid, k, p, start, n, *cuts);
        continue;
      }
      const double origin = grid.origin[k];
      const double h = grid.spacing[k];
      const double inv_h = 1.0 / h;
      const double last = grid.cells[k];
      // Along a periodic axis the grain is taken at its image in the
      // period [origin, origin + period) (a grain may be up to half the
      // Verlet skin outside between list builds).
      const double period = grid.periodic[k] ? last * h : 0.0;
      const double inv_period = grid.periodic[k] ? 1.0 / period : 0.0;
      // The image's cell, in [0, cells) even where rounding puts it on an end.
      const double lowest = grid.periodic[k] ? 0.0 : -1.0;
      const double highest = grid.periodic[k] ? last - 1.0 : last;
      int* home = cuts->home[k].data();
      int* other = cuts->other[k].data();
      double* dist = cuts->dist[k].data();
      int* mask = cuts->mask.data();
#pragma omp simd
      for (std::size_t g = 0; g < n; ++g) {
        const double x0 = p.position[start + g][k];
        const double x = x0 - period * std::floor((x0 - origin) * inv_period);
        const double r = radius[g];
        // As grid.cell_along, with the inverse spacing: a grain on a face
        // may land on either side, where its distance to it is +0.
        // Clamped to [-1, cells] (a NaN position to -1, outside the grid;
        // [0, cells - 1] along a periodic axis),
        // so that the conversion to int is defined.
        const double raw = std::floor((x - origin) * inv_h);
        const double cell = raw >= lowest ? (raw > highest ? highest : raw) : lowest;
        const double lo = origin + cell * h;
        const double below = x - lo;
        const double above = lo + h - x;
        // Without short-circuits, which would be branches.
        const int down = below < r ? 1 : 0;
        const int up = (1 - down) & (above < r ? 1 : 0);
        home[g] = static_cast<int>(cell);
        other[g] = home[g] + up - down;
        // +0 at least: the closed forms take distances >= +0.
        dist[g] = lane_max(0.0, down != 0 ? below : above);
        mask[g] = (k == 0 ? 0 : mask[g]) | ((down | up) << k);
      }
    }
    std::array<std::size_t, masks> filled{};
    for (std::size_t g = 0; g < n; ++g) {
      const int m = cuts->mask[g];
      bucket[m][filled[m]++] = static_cast<std::uint16_t>(g);
    }
    auto run = [&]<int Mask>() {
      cut_bucket<D, Mask>(grid, strides, p, *cuts, bucket[Mask].data(), filled[Mask], start, f, section,
                          sections);
    };
    run.template operator()<0>();
    run.template operator()<1>();
    run.template operator()<2>();
    run.template operator()<3>();
    if constexpr (D == 3) {
      run.template operator()<4>();
      run.template operator()<5>();
      run.template operator()<6>();
      run.template operator()<7>();
    }
  }
}

}  // namespace darcydem
