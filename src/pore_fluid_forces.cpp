// The fluid at a point and its forces on the grains (pore_fluid.hpp): the
// staggered interpolation of the faces' pressure gradients and Darcy
// fluxes to a point (also across the ends of a periodic axis), the excess
// pressure between cell centres, and each grain's pressure-gradient force,
// drag and buoyancy, from the cell holding its centre or spread over the
// cells it overlaps.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "darcydem/core/parallel.hpp"
#include "darcydem/core/vector_math.hpp"
#include "darcydem/fluid/pore_fluid.hpp"

namespace darcydem {

template <int D>
void PoreFluid<D>::interpolate(const std::array<double, D>& s_of, std::array<double, D>& grad,
                               std::array<double, D>& flux) const {
  Stencil st;
  for (int k = 0; k < D; ++k)
    stencil_axis_any(k, s_of[k], st.face_cell[k], st.face_frac[k], st.centre_cell[k], st.centre_frac[k]);
  interpolate(st, grad, flux);
}

template <int D>
void PoreFluid<D>::interpolate(const Stencil& st, std::array<double, D>& grad,
                               std::array<double, D>& flux) const {
  auto component = [&]<int A>() {
    std::array<double, D> fr{};
    for (int k = 0; k < D; ++k) fr[k] = k == A ? st.face_frac[k] : st.centre_frac[k];
    const auto v = interpolate_component<A>(stencil_base<A>(st.face_cell, st.centre_cell), fr);
    grad[A] = v[0];
    flux[A] = v[1];
  };
  component.template operator()<0>();
  component.template operator()<1>();
  if constexpr (D == 3) component.template operator()<2>();
}

template <int D>
void PoreFluid<D>::centre_pair(int k, double s, std::array<int, 2>& layer, double& frac) const {
  int face_cell = 0;
  int below = 0;
  double face_frac = 0.0;
  stencil_axis_any(k, s, face_cell, face_frac, below, frac);
  layer = {below, grid.cells[k] > 1 ? below + 1 : below};
  if (grid.periodic[k] && grid.cells[k] > 1) {
    const double t = s - 0.5;
    below = std::clamp(static_cast<int>(std::floor(t)), -1, grid.cells[k] - 1);
    layer = {grid.wrapped(k, below), grid.wrapped(k, below + 1)};
    frac = std::clamp(t - below, 0.0, 1.0);
  }
}

namespace {
/// f(cell or face coordinates, weight) for the 2^D corners of a multilinear
/// interpolation between two layers per axis, with the fraction towards
/// the second.
template <int D, class F>
void for_each_corner(const std::array<std::array<int, 2>, D>& layer, const std::array<double, D>& frac,
                     F&& f) {
  for (int corner = 0; corner < (1 << D); ++corner) {
    double w = 1.0;
    std::array<int, D> c{};
    for (int k = 0; k < D; ++k) {
      const bool up = ((corner >> k) & 1) != 0;
      w *= up ? frac[k] : 1.0 - frac[k];
      c[k] = layer[k][up ? 1 : 0];
    }
    f(c, w);
  }
}
}  // namespace

template <int D>
void PoreFluid<D>::interpolate_wrapped(std::array<double, D> s, std::array<double, D>& grad,
                                       std::array<double, D>& flux) const {
  s = wrap_cell_units(s);
  for (int a = 0; a < D; ++a) {
    // Per axis, the two layers of the stencil (faces along a, cell centres
    // along the others) and the fraction between them.
    std::array<std::array<int, 2>, D> layer{};
    std::array<double, D> frac{};
    for (int k = 0; k < D; ++k) {
      if (k == a) {
        int face_cell = 0;
        int centre_cell = 0;
        double centre_frac = 0.0;
        stencil_axis(k, s[k], face_cell, frac[k], centre_cell, centre_frac);
        layer[k] = {face_cell, face_cell + 1};
      } else {
        centre_pair(k, s[k], layer[k], frac[k]);
      }
    }
    double g = 0.0;
    double q = 0.0;
    for_each_corner<D>(layer, frac, [&](const std::array<int, D>& c, double w) {
      const auto& v = face_gq_[a][grid.face_index(a, c)];
      g += w * v[0];
      q += w * v[1];
    });
    grad[a] = g;
    flux[a] = q;
  }
}

template <int D>
Vec<D> PoreFluid<D>::gradient_at(const Vec<D>& x) const {
  std::array<double, D> grad{};
  std::array<double, D> flux{};
  if (grid.any_periodic()) {
    interpolate_wrapped(cell_units(x), grad, flux);
  } else {
    interpolate(cell_units(x), grad, flux);
  }
  Vec<D> g;
  for (int k = 0; k < D; ++k) g[k] = grad[k];
  return g;
}

template <int D>
double PoreFluid<D>::pressure_at(const Vec<D>& x) const {
  // Between the cell centres around x (the stencil's centre pairs; along a
  // periodic axis, across an end the last layer and the first).
  std::array<std::array<int, 2>, D> layer{};
  std::array<double, D> frac{};
  const auto s = wrap_cell_units(cell_units(x));
  for (int k = 0; k < D; ++k) centre_pair(k, s[k], layer[k], frac[k]);
  double sum = 0.0;
  for_each_corner<D>(layer, frac, [&](const std::array<int, D>& c, double w) {
    if (w != 0.0) sum += w * pressure_[grid.index(c)];
  });
  return sum;
}

template <int D>
void PoreFluid<D>::particle_forces(const ParticleData<D>& p, const Vec<D>& gravity,
                                   std::vector<Vec<D>>& force) const {
  // In chunks of grains, in stages: loops without branches over the chunk
  // (which the compiler vectorises) locate each grain on the grid; grain by
  // grain, the staggered interpolation and the cell's coefficients are
  // loaded; then the slip, Wen-Yu's Re^0.687 for the whole chunk at once
  // (core/vector_math.hpp) and the force, again over the chunk.
  const auto started = std::chrono::steady_clock::now();
  // The chunk's arrays take about 270 bytes per grain: 17 kB for 64 grains,
  // within a 32 kB L1 data cache (with 256 grains, 70 kB, the force pass
  // took 10-20 % longer on a 2.6 GHz EPYC; docs/PERFORMANCE.md).
  constexpr std::int64_t chunk = 64;
  const auto count = static_cast<std::int64_t>(p.size());
  const bool free_water = !std::isnan(water_level);
  const bool periodic = grid.any_periodic();
  // Ergun/Wen-Yu or the Darcy law: each compiled on its own, so that a
  // grain does only its law's work.
  const double* scale = p.volume_scale.empty() ? nullptr : p.volume_scale.data();
  auto run = [&]<bool Ergun, bool Spread>(std::int64_t b) {
    const std::int64_t begin = b * chunk;
    const std::int64_t n = std::min(count, begin + chunk) - begin;
    std::array<std::array<double, chunk>, D> s;
    std::array<std::array<int, chunk>, D> face_cell, centre_cell;
    std::array<std::array<double, chunk>, D> face_frac, centre_frac;
    std::array<std::array<double, chunk>, D> grad, slip, darcy;
    std::array<double, chunk> inside, vp, inv_d, re, re_pow, speed, viscous, inertial, wen_yu;
    // Where each grain is.
    for (int k = 0; k < D; ++k) {
      const double cells = grid.cells[k];
      if (grid.graded(k)) {
        // A graded axis: each grain's layer from the faces' bins, the
        // fraction between the cell centres along x.
        for (std::int64_t j = 0; j < n; ++j) {
          s[k][j] = stencil_graded(k, p.position[begin + j][k], face_cell[k][j], face_frac[k][j],
                                   centre_cell[k][j], centre_frac[k][j]);
          const bool in = s[k][j] >= 0.0 && s[k][j] < cells;
          inside[j] = (k == 0 || inside[j] > 0.0) && in ? 1.0 : 0.0;
        }
        continue;
      }
#pragma omp simd
      for (std::int64_t j = 0; j < n; ++j)
        s[k][j] = (p.position[begin + j][k] - grid.origin[k]) * inv_spacing_[k];
      if (grid.periodic[k]) {
        // The grain's image in the period (the grid spans it).
#pragma omp simd
        for (std::int64_t j = 0; j < n; ++j) {
          const double w = s[k][j] - cells * std::floor(s[k][j] / cells);
          s[k][j] = w >= cells ? w - cells : w;
        }
      }
#pragma omp simd
      for (std::int64_t j = 0; j < n; ++j)
        stencil_axis(k, s[k][j], face_cell[k][j], face_frac[k][j], centre_cell[k][j], centre_frac[k][j]);
      for (std::int64_t j = 0; j < n; ++j) {
        const bool in = s[k][j] >= 0.0 && s[k][j] < cells;
        inside[j] = (k == 0 || inside[j] > 0.0) && in ? 1.0 : 0.0;
      }
    }
    // The stencils' lower corners, per component, and the holding cells.
    std::array<std::array<std::size_t, chunk>, D> base;
    std::array<std::size_t, chunk> cell;
    for (std::int64_t j = 0; j < n; ++j) {
      std::array<int, D> fc{};
      std::array<int, D> cc{};
      for (int k = 0; k < D; ++k) {
        fc[k] = face_cell[k][j];
        cc[k] = centre_cell[k][j];
      }
      base[0][j] = stencil_base<0>(fc, cc);
      base[1][j] = stencil_base<1>(fc, cc);
      if constexpr (D == 3) base[2][j] = stencil_base<2>(fc, cc);
      cell[j] = grid.index(fc);
    }
    // Grain by grain: the interpolated gradient and flux, the cell's values.
    for (std::int64_t j = 0; j < n; ++j) {
      const std::int64_t i = begin + j;
      const CellDrag& cd = cell_drag_[cell[j]];
      // Within half a cell of a periodic end the stencil wraps: corner by
      // corner (interpolate_wrapped).
      std::array<double, D> wrapped_grad{};
      std::array<double, D> wrapped_flux{};
      bool wrap = false;
      if (periodic && !Spread) {
        std::array<double, D> sj{};
        for (int k = 0; k < D; ++k) sj[k] = s[k][j];
        wrap = near_periodic_end(sj);
        if (wrap) interpolate_wrapped(sj, wrapped_grad, wrapped_flux);
      }
      auto component = [&]<int A>() {
        if constexpr (Spread) {
          // The means over the cells the grain overlaps (spread_drag).
          const GrainDrag& gd = grain_drag_[static_cast<std::size_t>(i)];
          grad[A][j] = gd.grad[A];
          slip[A][j] = gd.fluid_velocity[A] - p.velocity[i][A];
          if constexpr (!Ergun) darcy[A][j] = gd.law[A];
          return;
        }
        std::array<double, D> fr{};
        for (int k = 0; k < D; ++k) fr[k] = k == A ? face_frac[k][j] : centre_frac[k][j];
        const auto v = wrap ? std::array<double, 2>{wrapped_grad[A], wrapped_flux[A]}
                            : interpolate_component<A>(base[A][j], fr);
        grad[A][j] = v[0];
        slip[A][j] = cd.solid_velocity[A] + v[1] * cd.inv_n - p.velocity[i][A];
        if constexpr (!Ergun) darcy[A][j] = cd.law[A];
      };
      component.template operator()<0>();
      component.template operator()<1>();
      if constexpr (D == 3) component.template operator()<2>();
      if constexpr (Ergun) {
        const auto& law = Spread ? grain_drag_[static_cast<std::size_t>(i)].law : cd.law;
        viscous[j] = law[0];
        inertial[j] = law[1];
        wen_yu[j] = law[2];
        re[j] = law[3];
      }
    }
    // Slip speed and Re.
#pragma omp simd
    for (std::int64_t j = 0; j < n; ++j) {
      const double r = p.radius[begin + j];
      vp[j] = particle_volume<D>(r);
      inv_d[j] = 0.5 / r;
      if constexpr (Ergun) {
        double slip2 = 0.0;
        for (int k = 0; k < D; ++k) slip2 += slip[k][j] * slip[k][j];
        speed[j] = std::sqrt(slip2);
        re[j] *= 2.0 * r * speed[j];
      }
    }
    if (scale != nullptr) {
      // A member of a clump of overlapping members: its share of the volume.
      for (std::int64_t j = 0; j < n; ++j) vp[j] *= scale[begin + j];
    }
    if constexpr (Ergun) {
      // Re = 0 (no slip, as in fluid at rest) has no finite logarithm;
      // the smallest normal double gives the same C_d Re (24).
#pragma omp simd
      for (std::int64_t j = 0; j < n; ++j) re_pow[j] = lane_max(re[j], std::numeric_limits<double>::min());
      power_law_batch(re_pow.data(), 0.687, re_pow.data(), static_cast<std::size_t>(n));
    }
    // -V_p (grad u + rho_f g) + drag; zero for grains outside the grid.
    for (int k = 0; k < D; ++k) {
      const double weight = fluid.density * gravity[k];
#pragma omp simd
      for (std::int64_t j = 0; j < n; ++j) {
        // C_d Re of Wen and Yu (wen_yu_cd_re), with the batch's Re^0.687.
        double beta = 0.0;
        if constexpr (Ergun) {
          const double cd_re = re[j] < 1000.0 ? 24.0 * (1.0 + 0.15 * re_pow[j]) : 0.44 * re[j];
          beta = (viscous[j] + wen_yu[j] * cd_re) * inv_d[j] * inv_d[j] + inertial[j] * speed[j] * inv_d[j];
        } else {
          beta = darcy[k][j];
        }
        const double f = -vp[j] * (grad[k][j] + weight) + vp[j] * beta * slip[k][j];
        force[begin + j][k] = inside[j] > 0.0 ? f : 0.0;
      }
    }
    // Grains outside the grid, below a free water surface: buoyancy and
    // the drag of a lone grain in the water there. Above the grid's top
    // (within its sides) the water rises at the flux through the top face
    // below (continuity across the surface, porosity 1), interpolated
    // across the columns as the vertical component is inside; beside or
    // below the grid it is still.
    if (free_water) {
      constexpr int up = D - 1;
      for (std::int64_t j = 0; j < n; ++j) {
        const std::int64_t i = begin + j;
        if (inside[j] > 0.0 || !(p.position[i][up] < water_level)) continue;
        bool above = s[up][j] >= grid.cells[up];
        for (int k = 0; k < up; ++k) above = above && s[k][j] >= 0.0 && s[k][j] < grid.cells[k];
        Vec<D> slip = -p.velocity[i];
        if (above) {
          std::array<double, D> fr{};
          for (int k = 0; k < D; ++k) fr[k] = k == up ? face_frac[k][j] : centre_frac[k][j];
          slip[up] += interpolate_component<up>(base[up][j], fr)[1];
        }
        const double d = 2.0 * p.radius[i];
        force[i] = -vp[j] * fluid.density * gravity + vp[j] * lone_grain_drag(d, slip.norm(), fluid) * slip;
      }
    }
  };
  const std::int64_t chunks = (count + chunk - 1) / chunk;
  auto run_all = [&]<bool Ergun, bool Spread>() {
    if (count > parallel_threshold) {
#pragma omp parallel for schedule(static)
      for (std::int64_t b = 0; b < chunks; ++b) run.template operator()<Ergun, Spread>(b);
    } else {
      for (std::int64_t b = 0; b < chunks; ++b) run.template operator()<Ergun, Spread>(b);
    }
  };
  const bool ergun = drag == DragLaw::ergun;
  if (drag_cells == DragCells::overlaps) {
    spread_drag(p);
    if (ergun) {
      run_all.template operator()<true, true>();
    } else {
      run_all.template operator()<false, true>();
    }
  } else if (ergun) {
    run_all.template operator()<true, false>();
  } else {
    run_all.template operator()<false, false>();
  }
  held_ = {&force, p.size(), gravity};
  force_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

template <int D>
void PoreFluid<D>::spread_drag(const ParticleData<D>& p) const {
  // Per cell: the mean gradient -mu qbar / kappa and the fluid velocity
  // v_s + qbar / n (qbar: darcy_velocity).
  const std::vector<Vec<D>> qbar = darcy_velocity();
  std::vector<std::array<double, 2 * D>> cell(grid.size());
  for (std::size_t c = 0; c < grid.size(); ++c) {
    for (int k = 0; k < D; ++k) {
      cell[c][k] = -fluid.viscosity * qbar[c][k] / kappa_[c][k];
      cell[c][D + k] = cell_drag_[c].solid_velocity[k] + qbar[c][k] * cell_drag_[c].inv_n;
    }
  }
  // Grains in blocks in parallel; each grain's sums are its own, so the
  // result does not depend on the number of threads.
  const std::size_t count = p.size();
  grain_drag_.assign(count, GrainDrag{});
  const bool ergun = drag == DragLaw::ergun;
  const std::size_t blocks = std::clamp<std::size_t>(count / 25'000, 1, 8);
  auto block = [&](std::size_t b) {
    for_each_overlap(
        p, count * b / blocks, count * (b + 1) / blocks,
        [&](std::size_t c, std::size_t i, double v) {
          const CellDrag& cd = cell_drag_[c];
          GrainDrag& gd = grain_drag_[i];
          gd.volume += v;
          for (int m = 0; m < 4; ++m) gd.law[m] += v * cd.law[m];
          for (int k = 0; k < D; ++k) {
            gd.grad[k] += v * cell[c][k];
            const double w = ergun ? v : v * cd.law[k];
            gd.weight[k] += w;
            gd.fluid_velocity[k] += w * cell[c][D + k];
          }
        },
        [](int, std::size_t, std::size_t, double) {}, false);
  };
  const auto nb = static_cast<std::int64_t>(blocks);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (std::int64_t b = 0; b < nb; ++b) block(static_cast<std::size_t>(b));
  // Sums to means; a grain outside the grid keeps zeros (its force is not
  // the grid's).
  const bool parallel = static_cast<std::int64_t>(count) > parallel_threshold;
#pragma omp parallel for schedule(static) if (parallel)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(count); ++i) {
    GrainDrag& gd = grain_drag_[static_cast<std::size_t>(i)];
    if (gd.volume > 0.0) {
      const double inv = 1.0 / gd.volume;
      for (double& x : gd.law) x *= inv;
      for (double& x : gd.grad) x *= inv;
    }
    for (int k = 0; k < D; ++k) {
      if (gd.weight[k] > 0.0) gd.fluid_velocity[k] /= gd.weight[k];
    }
  }
}

template <int D>
bool PoreFluid<D>::in_grid(const Vec<D>& x) const {
  // As particle_forces locates grains: in cell units, inside if in [0, cells)
  // (always along a periodic axis).
  const auto s = wrap_cell_units(cell_units(x));
  bool in = true;
  for (int k = 0; k < D; ++k) in = in && s[k] >= 0.0 && s[k] < grid.cells[k];
  return in;
}

template <int D>
std::size_t PoreFluid<D>::grains_outside(const ParticleData<D>& p) const {
  return static_cast<std::size_t>(
      std::count_if(p.position.begin(), p.position.end(), [&](const Vec<D>& x) { return !in_grid(x); }));
}

template <int D>
std::size_t PoreFluid<D>::grains_in_free_water(const ParticleData<D>& p) const {
  return static_cast<std::size_t>(std::count_if(p.position.begin(), p.position.end(), [&](const Vec<D>& x) {
    return !in_grid(x) && x[D - 1] < water_level;  // false for a NaN level
  }));
}

template Vec<2> PoreFluid<2>::gradient_at(const Vec<2>&) const;
template Vec<3> PoreFluid<3>::gradient_at(const Vec<3>&) const;
template double PoreFluid<2>::pressure_at(const Vec<2>&) const;
template double PoreFluid<3>::pressure_at(const Vec<3>&) const;
template void PoreFluid<2>::particle_forces(const ParticleData<2>&, const Vec<2>&,
                                            std::vector<Vec<2>>&) const;
template void PoreFluid<3>::particle_forces(const ParticleData<3>&, const Vec<3>&,
                                            std::vector<Vec<3>>&) const;
template bool PoreFluid<2>::in_grid(const Vec<2>&) const;
template bool PoreFluid<3>::in_grid(const Vec<3>&) const;
template std::size_t PoreFluid<2>::grains_outside(const ParticleData<2>&) const;
template std::size_t PoreFluid<3>::grains_outside(const ParticleData<3>&) const;
template std::size_t PoreFluid<2>::grains_in_free_water(const ParticleData<2>&) const;
template std::size_t PoreFluid<3>::grains_in_free_water(const ParticleData<3>&) const;

}  // namespace darcydem
