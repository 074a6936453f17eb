#pragma once
// PoreFluid::for_each_overlap: how each grain's volume is shared among the
// cells it overlaps. Cells are at least one grain diameter wide (checked when
// the scene is read), so a grain crosses at most one face per axis. With d_k
// the distance from the centre to the crossed face along axis k, the part of
// the grain beyond the faces of a set T of axes is the cap, wedge or octant
// M(T) (ball_overlap.hpp), and the part in the cell reached by crossing
// exactly the faces of S follows by inclusion-exclusion:
//   vol(S) = sum over T with S in T of (-1)^{|T| - |S|} M(T).
// The parts add up to the grain's volume (minus what lies outside the grid).
// Optionally it also reports the grain's cross-section on every face it
// crosses (the solid area through which it moves across that face).
#include <numbers>

#include "darcydem/fluid/ball_overlap.hpp"
#include "darcydem/fluid/pore_fluid.hpp"

namespace darcydem {

/// Inclusion-exclusion over the subsets T of `all` that contain s:
/// sum (-1)^{|T| - |s|} m[T], the measure beyond exactly the planes of s
/// when m[T] is the measure beyond (at least) the planes of T.
template <std::size_t N>
inline double beyond_exactly(const std::array<double, N>& m, int s, int all) {
  double v = 0.0;
  for (int t = s;; t = (t + 1) | s) {
    v += ((__builtin_popcount(t ^ s) & 1) != 0 ? -m[t] : m[t]);
    if (t == all) break;
  }
  return v;
}

template <int D>
template <class F, class G>
void PoreFluid<D>::for_each_overlap(const ParticleData<D>& p, F&& f, G&& section, bool sections) const {
  namespace bo = ball_overlap;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const Vec<D>& x = p.position[i];
    std::array<int, D> home{};
    std::array<int, D> other{};
    std::array<int, D> axes{};  // crossing axes
    std::array<double, D> dist{};
    int crossing = 0;
    for (int k = 0; k < D; ++k) {
      home[k] = grid.cell_along(k, x[k]);
      const double lo = grid.origin[k] + home[k] * grid.spacing[k];
      const double hi = lo + grid.spacing[k];
      if (x[k] - r < lo) {
        other[k] = home[k] - 1;
        dist[crossing] = x[k] - lo;
        axes[crossing++] = k;
      } else if (x[k] + r > hi) {
        other[k] = home[k] + 1;
        dist[crossing] = hi - x[k];
        axes[crossing++] = k;
      } else {
        other[k] = home[k];
      }
    }
    if (crossing == 0) {
      if (grid.inside(home)) f(grid.index(home), i, particle_volume<D>(r));
      continue;
    }
    // M(T) for every subset T of the crossing axes (bit j: axes[j]).
    std::array<double, 8> m{};
    for (int t = 0; t < (1 << crossing); ++t) {
      std::array<double, 3> d{};
      int n = 0;
      for (int j = 0; j < crossing; ++j) {
        if ((t >> j) & 1) d[n++] = dist[j];
      }
      if constexpr (D == 2) {
        m[t] = n == 0   ? particle_volume<2>(r)
               : n == 1 ? bo::segment_area(r, d[0])
                        : bo::corner_area(r, d[0], d[1]);
      } else {
        m[t] = n == 0   ? particle_volume<3>(r)
               : n == 1 ? bo::cap_volume(r, d[0])
               : n == 2 ? bo::wedge_volume(r, d[0], d[1])
                        : bo::octant_volume(r, d[0], d[1], d[2]);
      }
    }
    const int all = (1 << crossing) - 1;
    // Sections of the grain on the faces it crosses: on the face of axis
    // axes[j], a (D-1)-ball of radius rho = sqrt(r^2 - d_j^2), shared among
    // the faces beyond the other crossed planes in the same way.
    if (sections) {
      for (int j = 0; j < crossing; ++j) {
        const double rho = std::sqrt(std::max(0.0, r * r - dist[j] * dist[j]));
        std::array<int, 2> others{};
        int no = 0;
        for (int l = 0; l < crossing; ++l) {
          if (l != j) others[no++] = l;
        }
        std::array<double, 4> ms{};
        for (int t = 0; t < (1 << no); ++t) {
          std::array<double, 2> d{};
          int n = 0;
          for (int l = 0; l < no; ++l) {
            if ((t >> l) & 1) d[n++] = dist[others[l]];
          }
          if constexpr (D == 2) {
            ms[t] = n == 0 ? 2.0 * rho : std::max(0.0, rho - d[0]);
          } else {
            ms[t] = n == 0   ? std::numbers::pi * rho * rho
                    : n == 1 ? bo::segment_area(rho, d[0])
                             : bo::corner_area(rho, d[0], d[1]);
          }
        }
        const int oall = (1 << no) - 1;
        for (int s = 0; s <= oall; ++s) {
          const double a = beyond_exactly(ms, s, oall);
          const int k = axes[j];
          std::array<int, D> face = home;
          face[k] = std::max(home[k], other[k]);
          for (int l = 0; l < no; ++l) {
            if ((s >> l) & 1) face[axes[others[l]]] = other[axes[others[l]]];
          }
          bool in = face[k] >= 0 && face[k] <= grid.cells[k];
          for (int m2 = 0; m2 < D; ++m2) {
            if (m2 != k && (face[m2] < 0 || face[m2] >= grid.cells[m2])) in = false;
          }
          if (a > 0.0 && in) section(k, face, i, a);
        }
      }
    }
    for (int s = 0; s <= all; ++s) {
      const double v = beyond_exactly(m, s, all);
      std::array<int, D> cell = home;
      for (int j = 0; j < crossing; ++j) {
        if ((s >> j) & 1) cell[axes[j]] = other[axes[j]];
      }
      if (v > 0.0 && grid.inside(cell)) f(grid.index(cell), i, v);
    }
  }
}

}  // namespace darcydem
