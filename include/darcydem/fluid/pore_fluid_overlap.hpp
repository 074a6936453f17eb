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
// (which faces it crosses), then the grains of a chunk are sorted by the set
// of axes they cross, and each set is processed by code compiled for it:
// no branch depends on a grain's position. In 3D the arctangents of the
// wedges, octants and sections are shared (ball_overlap::PairAngles) and
// computed together for all the grains of a set (core/vector_math.hpp).
#include <algorithm>
#include <array>
#include <cstdint>
#include <numbers>
#include <vector>

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
template <int K, std::size_t N>
inline void beyond_exactly(std::array<double, N>& m) {
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

/// Scratch space of one chunk.
struct OverlapScratch {
  std::vector<double> ys, xs, angle;
};

/// The section of a grain on the face of its J-th crossing axis
/// (cut_sections): a (D-1)-ball of radius rho = sqrt(r^2 - d_J^2), shared
/// among the faces beyond the other crossed planes in the same way as the
/// volume among the cells.
template <int D, int K, int J, class G>
void section_on(const FluidGrid<D>& grid, const GridStrides<D>& strides, const GrainCut<D>& cut,
                const std::array<int, 3>& axes, const std::array<bool, 3>& in, const std::array<double, 3>& d,
                const std::array<ball_overlap::PairAngles, 3>& pa, double r, std::size_t i, G& section) {
  namespace bo = ball_overlap;
  constexpr int others = K - 1;
  // The other crossing axes, in order.
  constexpr int L0 = J == 0 ? 1 : 0;
  constexpr int L1 = J == 2 ? 1 : 2;
  // The pair (J, l) and, in it, the angle of d_l.
  auto pair_of = [&](auto l) -> const bo::PairAngles& {
    return pa[pair_slot(std::min(J, decltype(l)::value), std::max(J, decltype(l)::value))];
  };
  auto theta = [&](auto l) { return decltype(l)::value > J ? pair_of(l).theta_v : pair_of(l).theta_u; };
  using l0 = std::integral_constant<int, L0>;
  using l1 = std::integral_constant<int, L1>;
  const double rho2 = std::max(0.0, r * r - d[J] * d[J]);
  std::array<double, 1 << others> ms{};
  if constexpr (D == 2) {
    const double rho = std::sqrt(rho2);
    ms[0] = 2.0 * rho;
    if constexpr (others == 1) ms[1] = std::max(0.0, rho - d[L0]);
  } else {
    ms[0] = std::numbers::pi * rho2;
    if constexpr (others >= 1) ms[1] = bo::section_beyond(rho2, d[L0], pair_of(l0{}), theta(l0{}));
    if constexpr (others == 2) {
      ms[2] = bo::section_beyond(rho2, d[L1], pair_of(l1{}), theta(l1{}));
      ms[3] = bo::section_beyond(rho2, d[L0], d[L1], pair_of(l0{}), theta(l0{}), pair_of(l1{}), theta(l1{}));
    }
  }
  beyond_exactly<others>(ms);
  // The face between home and other along k (inside if 0..cells), moved
  // across the other crossed planes of s (inside there if 0..cells-1).
  const int k = axes[J];
  const auto& fs = strides.face[k];
  const int along = std::max(cut.home[k], cut.other[k]);
  std::int64_t base = static_cast<std::int64_t>(along) * fs[k];
  for (int a = 0; a < D; ++a) {
    if (a != k) base += static_cast<std::int64_t>(cut.home[a]) * fs[a];
  }
  // Moving across the other crossed plane l: its index step, and whether
  // the home coordinate there (replaced) or the neighbour's is in range.
  std::array<std::int64_t, 2> shift{};
  std::array<bool, 2> home_l{};
  std::array<bool, 2> other_l{};
  const std::array<int, 2> ls = {L0, L1};
  for (int t = 0; t < others; ++t) {
    const int a = axes[ls[t]];
    shift[t] = static_cast<std::int64_t>(cut.other[a] - cut.home[a]) * fs[a];
    home_l[t] = cut.home[a] >= 0 && cut.home[a] < grid.cells[a];
    other_l[t] = in[ls[t]];
  }
  // In range along k and across the axes not crossed; across a crossed
  // plane l, home_l or other_l as the face moved or not.
  bool rest_ok = along >= 0 && along <= grid.cells[k];
  for (int a = 0; a < D; ++a) {
    bool crossed = a == k;
    for (int t = 0; t < others; ++t) crossed = crossed || a == axes[ls[t]];
    if (!crossed) rest_ok = rest_ok && cut.home[a] >= 0 && cut.home[a] < grid.cells[a];
  }
  for (int s = 0; s < (1 << others); ++s) {
    std::int64_t face = base;
    bool inside = rest_ok;
    for (int t = 0; t < others; ++t) {
      const bool moved = ((s >> t) & 1) != 0;
      face += moved ? shift[t] : 0;
      inside = inside && (moved ? other_l[t] : home_l[t]);
    }
    if (ms[s] > 0.0 && inside) section(k, static_cast<std::size_t>(face), i, ms[s]);
  }
}

/// The sections of a grain on the faces it crosses (cut_bucket), as
/// section(axis, face index, grain, area). `in[j]`: the neighbour across
/// crossing axis j lies in the grid along that axis.
template <int D, int K, class G>
void cut_sections(const FluidGrid<D>& grid, const GridStrides<D>& strides, const GrainCut<D>& cut,
                  const std::array<int, 3>& axes, const std::array<bool, 3>& in,
                  const std::array<double, 3>& d, const std::array<ball_overlap::PairAngles, 3>& pa, double r,
                  std::size_t i, G& section) {
  section_on<D, K, 0>(grid, strides, cut, axes, in, d, pa, r, i, section);
  if constexpr (K >= 2) section_on<D, K, 1>(grid, strides, cut, axes, in, d, pa, r, i, section);
  if constexpr (K == 3) section_on<D, K, 2>(grid, strides, cut, axes, in, d, pa, r, i, section);
}

/// The grains `members` (indices into the chunk starting at `start`), which
/// all cross exactly the faces of the axes in Mask.
template <int D, int Mask, class F, class G>
void cut_bucket(const FluidGrid<D>& grid, const GridStrides<D>& strides, const ParticleData<D>& p,
                const GrainCut<D>* cuts, const std::uint16_t* members, std::size_t count, std::size_t start,
                OverlapScratch& scratch, F& f, G& section, bool sections) {
  namespace bo = ball_overlap;
  constexpr int K = __builtin_popcount(Mask);
  constexpr int subsets = 1 << K;
  std::array<int, 3> axes{};
  for (int j = 0; j < K; ++j) axes[j] = axis_of<Mask>(j);
  // Arctangents, 3 per pair of crossing axes and 3 more for the octant.
  constexpr int pairs_count = K * (K - 1) / 2;
  constexpr int per_grain = D == 3 ? 3 * pairs_count + (K == 3 ? 3 : 0) : 0;
  if constexpr (per_grain > 0) {
    scratch.ys.resize(per_grain * count);
    scratch.xs.resize(per_grain * count);
    scratch.angle.resize(per_grain * count);
    for (std::size_t g = 0; g < count; ++g) {
      const GrainCut<D>& cut = cuts[members[g]];
      const double r = p.radius[start + members[g]];
      double* y = scratch.ys.data() + per_grain * g;
      double* x = scratch.xs.data() + per_grain * g;
      for (int j = 0; j < K; ++j) {
        for (int l = j + 1; l < K; ++l) {
          const double u = cut.dist[axes[j]];
          const double v = cut.dist[axes[l]];
          const double w = bo::pair_chord(r, u, v);
          const int s = 3 * pair_slot(j, l);
          y[s] = w;
          x[s] = u;
          y[s + 1] = w;
          x[s + 1] = v;
          y[s + 2] = u * v;
          x[s + 2] = r * w;
        }
      }
      if constexpr (K == 3) {
        const double a = cut.dist[0];
        const double b = cut.dist[1];
        const double zm = bo::pair_chord(r, a, b);
        y[9] = a;
        x[9] = b;
        y[10] = zm * b;
        x[10] = r * a;
        y[11] = zm * a;
        x[11] = r * b;
      }
    }
    atan2_batch(scratch.ys.data(), scratch.xs.data(), scratch.angle.data(), per_grain * count);
  }
  for (std::size_t g = 0; g < count; ++g) {
    const GrainCut<D>& cut = cuts[members[g]];
    const std::size_t i = start + members[g];
    const double r = p.radius[i];
    std::array<double, 3> d{};
    for (int j = 0; j < K; ++j) d[j] = cut.dist[axes[j]];
    // Pair angles (3D): w is the first atan2's y.
    std::array<bo::PairAngles, 3> pa{};
    if constexpr (per_grain > 0) {
      const double* a = scratch.angle.data() + per_grain * g;
      const double* y = scratch.ys.data() + per_grain * g;
      for (int s = 0; s < pairs_count; ++s) pa[s] = {y[3 * s], a[3 * s], a[3 * s + 1], a[3 * s + 2]};
    }
    // M(T) for every subset T of the crossing axes (bit j: axes[j]).
    std::array<double, subsets> m{};
    m[0] = particle_volume<D>(r);
    if constexpr (D == 2) {
      for (int j = 0; j < K; ++j) m[1 << j] = bo::segment_area(r, d[j]);
      if constexpr (K == 2) m[3] = bo::corner_area(r, d[0], d[1]);
    } else {
      for (int j = 0; j < K; ++j) m[1 << j] = bo::cap_volume(r, d[j]);
      for (int j = 0; j < K; ++j) {
        for (int l = j + 1; l < K; ++l) {
          m[(1 << j) | (1 << l)] = bo::wedge_volume(r, d[j], d[l], pa[pair_slot(j, l)]);
        }
      }
      if constexpr (K == 3) {
        const double* a = scratch.angle.data() + per_grain * g + 9;
        m[7] = bo::octant_volume(r, d[0], d[1], d[2], pa[0], pa[1], pa[2], {a[0], a[1], a[2]});
      }
    }
    beyond_exactly<K>(m);
    // The cell of subset s: home, moved across the crossed faces of s.
    std::int64_t home = 0;
    std::array<bool, D> home_ok{};
    for (int k = 0; k < D; ++k) {
      home += static_cast<std::int64_t>(cut.home[k]) * strides.cell[k];
      home_ok[k] = cut.home[k] >= 0 && cut.home[k] < grid.cells[k];
    }
    std::array<bool, 3> in{};
    for (int j = 0; j < K; ++j) {
      const int k = axes[j];
      in[j] = cut.other[k] >= 0 && cut.other[k] < grid.cells[k];
    }
    for (int s = 0; s < subsets; ++s) {
      std::int64_t cell = home;
      std::array<bool, D> ok = home_ok;
      for (int j = 0; j < K; ++j) {
        if ((s >> j) & 1) {
          const int k = axes[j];
          cell += static_cast<std::int64_t>(cut.other[k] - cut.home[k]) * strides.cell[k];
          ok[k] = in[j];
        }
      }
      bool inside = true;
      for (int k = 0; k < D; ++k) inside = inside && ok[k];
      if (m[s] > 0.0 && inside) f(static_cast<std::size_t>(cell), i, m[s]);
    }
    if constexpr (K > 0) {
      if (sections) cut_sections<D, K>(grid, strides, cut, axes, in, d, pa, r, i, section);
    }
  }
}

}  // namespace overlap_detail

template <int D>
template <class F, class G>
void PoreFluid<D>::for_each_overlap(const ParticleData<D>& p, std::size_t begin, std::size_t end, F&& f,
                                    G&& section, bool sections) const {
  using overlap_detail::cut_bucket;
  using overlap_detail::GrainCut;
  constexpr std::size_t chunk = 1024;
  constexpr int masks = 1 << D;
  std::vector<GrainCut<D>> cuts(std::min(chunk, end - begin));
  std::array<std::vector<std::uint16_t>, masks> bucket;
  for (auto& b : bucket) b.resize(cuts.size());
  overlap_detail::OverlapScratch scratch;
  const overlap_detail::GridStrides<D> strides(grid);
  std::array<double, D> inv_h{};
  for (int k = 0; k < D; ++k) inv_h[k] = 1.0 / grid.spacing[k];
  for (std::size_t start = begin; start < end; start += chunk) {
    const std::size_t stop = std::min(end, start + chunk);
    std::array<std::size_t, masks> filled{};
    for (std::size_t i = start; i < stop; ++i) {
      GrainCut<D>& cut = cuts[i - start];
      const double r = p.radius[i];
      const Vec<D>& x = p.position[i];
      int mask = 0;
      for (int k = 0; k < D; ++k) {
        // As grid.cell_along, with the inverse spacing: a grain on a face
        // may land on either side, where its distance to it is +0.
        cut.home[k] =
            FluidGrid<D>::clamp_cell(std::floor((x[k] - grid.origin[k]) * inv_h[k]), -1, grid.cells[k]);
        const double lo = grid.origin[k] + cut.home[k] * grid.spacing[k];
        const double below = x[k] - lo;
        const double above = lo + grid.spacing[k] - x[k];
        const bool down = below < r;
        const bool up = !down && above < r;
        cut.other[k] = cut.home[k] + (up ? 1 : 0) - (down ? 1 : 0);
        // +0 at least: the closed forms take distances >= +0.
        cut.dist[k] = std::max(0.0, down ? below : above);
        mask |= (down || up) ? (1 << k) : 0;
      }
      bucket[mask][filled[mask]++] = static_cast<std::uint16_t>(i - start);
    }
    auto run = [&]<int Mask>() {
      cut_bucket<D, Mask>(grid, strides, p, cuts.data(), bucket[Mask].data(), filled[Mask], start, scratch, f,
                          section, sections);
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
