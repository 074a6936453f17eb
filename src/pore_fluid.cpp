#include "darcydem/fluid/pore_fluid.hpp"

#include <fmt/format.h>

#include "darcydem/core/parallel.hpp"
#include "darcydem/core/vector_math.hpp"
#include "darcydem/fluid/well_index.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace darcydem {
namespace {

/// body(a, len, face) over the interior faces normal to `axis`, in pieces
/// of its runs (FluidGrid::face_run) of at most 4096 faces: the cells
/// [a, a + len) below the faces [face, face + len). Pieces run in parallel
/// on a large grid, so the body may write only what belongs to its own
/// faces.
template <int D, class F>
void for_each_face_piece(const FluidGrid<D>& grid, int axis, F&& body) {
  constexpr std::size_t piece = 4096;
  const std::size_t runs = grid.face_runs(axis);
  const std::size_t per_run = (grid.face_run(axis, 0).count + piece - 1) / piece;
  const auto pieces = static_cast<std::int64_t>(runs * per_run);
  auto one = [&](std::int64_t i) {
    const auto u = static_cast<std::size_t>(i);
    const auto run = grid.face_run(axis, u / per_run);
    const std::size_t begin = u % per_run * piece;
    body(run.cell + begin, std::min(piece, run.count - begin), run.face + begin);
  };
  if (static_cast<std::int64_t>(grid.size()) > parallel_threshold) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < pieces; ++i) one(i);
  } else {
    for (std::int64_t i = 0; i < pieces; ++i) one(i);
  }
}

}  // namespace

template <int D>
PoreFluid<D>::PoreFluid(PressureSolverKind solver, double tolerance, CgPreconditioner preconditioner)
    : solver_(solver, tolerance, preconditioner) {}

template <int D>
void PoreFluid<D>::initialize(const ParticleData<D>& particles, const std::vector<Wall<D>>& walls) {
  held_ = {};
  const std::size_t n = grid.size();
  pressure_.assign(n, 0.0);
  pressure_old_.assign(n, 0.0);
  for (int k = 0; k < D; ++k) {
    if (grid.graded(k) && grid.periodic[k])
      throw std::logic_error("PoreFluid: a periodic axis of the grid cannot be graded");
    face_gq_[k].assign(grid.face_count(k), {0.0, 0.0});
    inv_spacing_[k] = grid.graded(k) ? std::numeric_limits<double>::quiet_NaN() : 1.0 / grid.spacing[k];
  }
  build_geometry();
  volume_old_ = uniform_volume_;
  for (int a = 0; a < D; ++a) {
    std::size_t stride = 1;
    for (int k = 0; k < D; ++k) {
      face_stride_[a][k] = stride;
      // Across the cell centres a single cell along k has no pair: the
      // stencil's two corners along k are then the same face.
      corner_step_[a][k] = k == a || grid.cells[k] > 1 ? stride : 0;
      stride *= static_cast<std::size_t>(k == a ? grid.cells[k] + 1 : grid.cells[k]);
    }
  }
  build_pattern();
  source_cells_.clear();
  screens_.clear();
  for (const FluidSource<D>& source : sources) {
    for (int k = 0; k < D; ++k) {
      if (!(source.position[k] >= grid.face_at(k, 0) && source.position[k] <= grid.face_at(k, grid.cells[k])))
        throw std::logic_error("PoreFluid: the source \"" + source.name + "\" is outside the grid");
    }
    source_cells_.push_back(grid.cell_holding(source.position));
    screens_.push_back(source.screened() ? source_cells(grid, source) : std::vector<SourceCell>{});
    if (source.screened() && (D != 3 || source.radius <= 0.0 || screens_.back().empty()))
      throw std::logic_error("PoreFluid: the screened well \"" + source.name +
                             "\" needs a 3D grid, a radius and a screen in it");
  }
  source_inflow_.assign(sources.size(), 0.0);
  drain_open_.assign(sources.size(), 0);
  compute_solid(particles);
  solid_old_ = solid_;
  compute_wall_solid(walls);
  wall_solid_old_ = wall_solid_;
  compute_cell_properties();
  compute_face_fields(0.0);
  solution_ = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  initialized_ = true;
}

template <int D>
void PoreFluid<D>::follow_cell(const PeriodicCell<D>& cell) {
  for (int k = 0; k < D; ++k) {
    if (!grid.periodic[k] || grid.graded(k))
      throw std::logic_error(
          "PoreFluid::follow_cell: the grid must be uniform and periodic along every axis");
    grid.origin[k] = cell.lower[k];
    grid.spacing[k] = cell.length[k] / grid.cells[k];
  }
  take_spacing();
}

template <int D>
void PoreFluid<D>::take_spacing() {
  for (int k = 0; k < D; ++k) inv_spacing_[k] = 1.0 / grid.spacing[k];
  uniform_volume_ = grid.cell_volume();
  for (auto& w : wrap_faces_) w.area = grid.face_area(w.axis);
}

template <int D>
void PoreFluid<D>::build_geometry() {
  const std::size_t n = grid.size();
  volume_.clear();
  for (int k = 0; k < D; ++k) {
    face_area_[k].clear();
    face_inv_distance_[k].clear();
    face_weight_[k].clear();
    layer_centre_[k].clear();
    layer_inv_width_[k].clear();
    layer_inv_gap_[k].clear();
    if (!grid.graded(k)) continue;
    for (int i = 0; i < grid.cells[k]; ++i) {
      layer_centre_[k].push_back(grid.centre_at(k, i));
      layer_inv_width_[k].push_back(1.0 / grid.width(k, i));
      if (i > 0) layer_inv_gap_[k].push_back(1.0 / (layer_centre_[k][i] - layer_centre_[k][i - 1]));
    }
  }
  if (!grid.any_graded()) {
    uniform_volume_ = grid.cell_volume();
    return;
  }
  uniform_volume_ = std::numeric_limits<double>::quiet_NaN();
  volume_.resize(n);
  for (int k = 0; k < D; ++k) {
    face_area_[k].assign(n, 0.0);
    face_inv_distance_[k].assign(n, 0.0);
    face_weight_[k].assign(n, 0.0);
  }
  for (std::size_t c = 0; c < n; ++c) {
    const auto cc = grid.coords(c);
    volume_[c] = grid.cell_volume(cc);
    for (int k = 0; k < D; ++k) {
      if (cc[k] + 1 >= grid.cells[k]) continue;  // no interior face above
      const double ha = grid.width(k, cc[k]);
      const double hb = grid.width(k, cc[k] + 1);
      face_area_[k][c] = grid.face_area(k, cc);
      face_inv_distance_[k][c] = 2.0 / (ha + hb);
      face_weight_[k][c] = ha / (ha + hb);
    }
  }
}

template <int D>
void PoreFluid<D>::set_pressure(const std::vector<double>& u) {
  if (!initialized_) throw std::logic_error("PoreFluid::set_pressure before initialize");
  if (u.size() != grid.size()) {
    throw std::invalid_argument(
        fmt::format("pore pressure: {} values given for a grid of {} cells", u.size(), grid.size()));
  }
  pressure_ = u;
  pressure_old_ = u;
  held_ = {};
  compute_face_fields(time_);
}

template <int D>
void PoreFluid<D>::compute_solid(const ParticleData<D>& particles) {
  // Grains in fixed blocks (their number depends on the grain count only),
  // each summed into its own arrays in parallel, then the blocks added in
  // order: the same result for any number of threads.
  static_assert(D + 1 <= lane_count);
  const std::size_t count = particles.size();
  const std::size_t blocks = std::clamp<std::size_t>(count / 25'000, 1, 8);
  const std::size_t n = grid.size();
  if (block_solid_.size() != blocks || block_solid_[0].cell.size() != n) {
    block_solid_.assign(blocks, SolidSums{});
    for (SolidSums& sums : block_solid_) {
      sums.cell.assign(n, Lanes{});
      for (int k = 0; k < D; ++k) sums.face_flux[k].assign(grid.face_count(k), 0.0);
    }
  }
  // Members of a clump whose members overlap count their share of its
  // volume (ParticleData::volume_scale).
  const double* scale = particles.volume_scale.empty() ? nullptr : particles.volume_scale.data();
  auto sum_block = [&](std::size_t b) {
    SolidSums& sums = block_solid_[b];
    Lanes* cell = sums.cell.data();
    std::fill(cell + sums.cell_lo, cell + sums.cell_hi, Lanes{});
    for (int k = 0; k < D; ++k) {
      std::fill(sums.face_flux[k].begin() + static_cast<std::ptrdiff_t>(sums.face_lo[k]),
                sums.face_flux[k].begin() + static_cast<std::ptrdiff_t>(sums.face_hi[k]), 0.0);
    }
    std::size_t lo = n;
    std::size_t hi = 0;
    std::array<std::size_t, D> face_lo;
    std::array<std::size_t, D> face_hi{};
    for (int k = 0; k < D; ++k) face_lo[k] = grid.face_count(k);
    for_each_overlap(
        particles, count * b / blocks, count * (b + 1) / blocks,
        [&](std::size_t c, std::size_t i, double v) {
          if (scale != nullptr) v *= scale[i];
          const Vec<D>& u = particles.velocity[i];
          Lanes weights{1.0, u[0], u[1], 0.0};
          if constexpr (D == 3) weights[3] = u[2];
          cell[c] += v * weights;
          lo = std::min(lo, c);
          hi = std::max(hi, c + 1);
        },
        [&](int axis, std::size_t face, std::size_t i, double area) {
          if (scale != nullptr) area *= scale[i];
          sums.face_flux[axis][face] += area * particles.velocity[i][axis];
          face_lo[axis] = std::min(face_lo[axis], face);
          face_hi[axis] = std::max(face_hi[axis], face + 1);
        },
        carry_with_solid);
    sums.cell_lo = std::min(lo, hi);
    sums.cell_hi = hi;
    for (int k = 0; k < D; ++k) {
      sums.face_lo[k] = std::min(face_lo[k], face_hi[k]);
      sums.face_hi[k] = face_hi[k];
    }
  };
  const auto nb = static_cast<std::int64_t>(blocks);
#pragma omp parallel for schedule(static) if (blocks > 1)
  for (std::int64_t b = 0; b < nb; ++b) sum_block(static_cast<std::size_t>(b));
  // Block after block, each over its range (zero elsewhere): per cell the
  // same additions in the same order as over the whole grid.
  std::vector<Lanes>& total = block_total_;
  total.assign(n, Lanes{});
  for (const SolidSums& sums : block_solid_) {
    for (std::size_t c = sums.cell_lo; c < sums.cell_hi; ++c) total[c] += sums.cell[c];
  }
  solid_.resize(n);
  solid_flux_.resize(n);
  for (std::size_t c = 0; c < n; ++c) {
    solid_[c] = total[c][0];
    for (int k = 0; k < D; ++k) solid_flux_[c][k] = total[c][1 + k];
  }
  for (int k = 0; k < D; ++k) {
    solid_face_flux_[k].assign(grid.face_count(k), 0.0);
    for (const SolidSums& sums : block_solid_) {
      for (std::size_t f = sums.face_lo[k]; f < sums.face_hi[k]; ++f)
        solid_face_flux_[k][f] += sums.face_flux[k][f];
    }
  }
}

template <int D>
void PoreFluid<D>::compute_wall_solid(const std::vector<Wall<D>>& walls) {
  const std::size_t n = grid.size();
  if (solid_walls.empty() && wall_solid_.size() == n) return;  // zeros, as they were
  wall_solid_.assign(n, 0.0);
  for (std::size_t w : solid_walls) {
    if (w >= walls.size())
      throw std::logic_error("PoreFluid: a solid wall that is not among the walls given");
  }
  // The planes' half-spaces: in each cell, all but the part of it in the
  // region they leave to the water (their union, so that platens meeting at
  // a cell's edges count their overlap once).
  const auto [wet_lo, wet_hi] = planes_wet_region(walls);
  const bool planes =
      std::any_of(solid_walls.begin(), solid_walls.end(), [&](std::size_t w) { return !walls[w].is_box(); });
  auto cell_bounds = [&](const std::array<int, D>& c, Vec<D>& corner, Vec<D>& far) {
    for (int k = 0; k < D; ++k) {
      corner[k] = grid.face_at(k, c[k]);
      far[k] = grid.face_at(k, c[k] + 1);
    }
  };
  if (planes) {
    for (std::size_t c = 0; c < n; ++c) {
      Vec<D> corner;
      Vec<D> far;
      cell_bounds(grid.coords(c), corner, far);
      if ((corner.array() >= wet_lo.array()).all() && (far.array() <= wet_hi.array()).all()) continue;
      double cell = 1.0;
      double wet = 1.0;
      for (int k = 0; k < D; ++k) {
        cell *= far[k] - corner[k];
        wet *= std::max(0.0, std::min(far[k], wet_hi[k]) - std::max(corner[k], wet_lo[k]));
      }
      wall_solid_[c] = std::max(0.0, cell - wet);
    }
  }
  // The boxes: each its exact volume in each cell, less its part behind
  // the planes.
  for (std::size_t w : solid_walls) {
    if (!walls[w].is_box()) continue;
    const std::optional<SolidBox<D>> box = displaced_box(walls[w]);
    if (!box) continue;
    for_each_box_cell(grid, *box, [&](const std::array<int, D>& c, double v) {
      if (planes && v > 0.0) {
        Vec<D> corner;
        Vec<D> far;
        cell_bounds(c, corner, far);
        const Vec<D> from = corner.cwiseMax(wet_lo);
        const Vec<D> to = far.cwiseMin(wet_hi);
        v = (to.array() > from.array()).all() ? box_cell_volume(*box, from, to) : 0.0;
      }
      wall_solid_[grid.index(c)] += v;
    });
  }
  compute_open_faces(walls);
}

template <int D>
void PoreFluid<D>::compute_cell_properties() {
  // Every cell (and face) on its own: in parallel on a large grid, with the
  // same result for any number of threads.
  const std::size_t n = grid.size();
  porosity_.resize(n);
  porosity_used_.resize(n);
  solid_velocity_.resize(n);
  const bool update_kappa = !permeability_frozen || kappa_.size() != n;
  kappa_.resize(n);
  cell_drag_.resize(n);
  const bool ergun = drag == DragLaw::ergun;
  if (ergun) {
    blend_atan_.resize(n);
    n_power_.resize(n);
  }
  // Cells in runs, so that Ergun/Wen-Yu's atan and power are computed for a
  // run at once (core/vector_math.hpp); the runs in parallel on a large grid.
  constexpr std::size_t run = 512;
  auto cells_of_run = [&](std::int64_t r) {
    const std::size_t begin = static_cast<std::size_t>(r) * run;
    const std::size_t end = std::min(n, begin + run);
    for (std::size_t c = begin; c < end; ++c) {
      const double volume = volume_of(c);
      porosity_[c] = 1.0 - (solid_[c] + wall_solid_[c]) / volume;
      porosity_used_[c] = std::clamp(porosity_[c], permeability.min_porosity, permeability.max_porosity);
      const double inv_solid = solid_[c] > 1e-12 * volume ? 1.0 / solid_[c] : 0.0;
      solid_velocity_[c] = solid_flux_[c] * inv_solid;
      if (update_kappa) {
        if (permeability.model == PermeabilityModel::constant) {
          kappa_[c] = permeability.intrinsic;
        } else {
          kappa_[c] = kozeny_carman(permeability.diameter, porosity_used_[c]) * permeability.anisotropy;
        }
      }
    }
    if (ergun) {
      // n_power_ holds the atan's arguments until the power overwrites them.
      for (std::size_t c = begin; c < end; ++c) n_power_[c] = ErgunWenYu::blend_argument(porosity_used_[c]);
      atan_batch(n_power_.data() + begin, blend_atan_.data() + begin, end - begin);
      power_law_batch(porosity_used_.data() + begin, ErgunWenYu::wen_yu_exponent, n_power_.data() + begin,
                      end - begin);
    }
    for (std::size_t c = begin; c < end; ++c) {
      const double nu = porosity_used_[c];
      CellDrag& cd = cell_drag_[c];
      cd = CellDrag{};
      for (int k = 0; k < D; ++k) cd.solid_velocity[k] = solid_velocity_[c][k];
      cd.inv_n = 1.0 / nu;
      if (ergun) {
        const ErgunWenYu e = ErgunWenYu::with(nu, blend_atan_[c], n_power_[c], fluid);
        const double per_solid = 1.0 / (1.0 - nu);
        cd.law = {e.phi * e.ergun_viscous * per_solid, e.phi * e.ergun_inertial * per_solid,
                  (1.0 - e.phi) * e.wen_yu * per_solid, fluid.density * nu / fluid.viscosity};
      } else {
        const double per_solid = nu * nu * fluid.viscosity / (1.0 - nu);
        for (int k = 0; k < D; ++k) cd.law[k] = per_solid / kappa_[c][k];
      }
    }
  };
  const auto runs = static_cast<std::int64_t>((n + run - 1) / run);
  if (static_cast<std::int64_t>(n) > parallel_threshold) {
#pragma omp parallel for schedule(static)
    for (std::int64_t r = 0; r < runs; ++r) cells_of_run(r);
  } else {
    for (std::int64_t r = 0; r < runs; ++r) cells_of_run(r);
  }
  // Darcy conductance kappa/mu of each interior face: the harmonic mean of
  // its two cells' (on a graded axis weighted by their widths, the two
  // half-cells in series: (h_a + h_b) / (h_a / kappa_a + h_b / kappa_b)).
  for (int k = 0; k < D; ++k) {
    face_lambda_[k].resize(n, 0.0);
    double* lambda = face_lambda_[k].data();
    const std::size_t s = grid.stride(k);
    const double inv_mu = 1.0 / fluid.viscosity;
    const double* weight = face_weight_[k].empty() ? nullptr : face_weight_[k].data();
    for_each_face_piece(grid, k, [&](std::size_t a0, std::size_t len, std::size_t) {
      if (weight != nullptr) {
        for (std::size_t a = a0; a < a0 + len; ++a) {
          const double ka = kappa_[a][k];
          const double kb = kappa_[a + s][k];
          lambda[a] = ka * kb / (weight[a] * kb + (1.0 - weight[a]) * ka) * inv_mu;
        }
        return;
      }
      for (std::size_t a = a0; a < a0 + len; ++a) {
        const double ka = kappa_[a][k];
        const double kb = kappa_[a + s][k];
        lambda[a] = 2.0 * ka * kb / (ka + kb) * inv_mu;
      }
    });
    // Impermeable walls close the part of each face they cover.
    if (!face_open_[k].empty()) {
      const double* open = face_open_[k].data();
      for_each_face_piece(grid, k, [&](std::size_t a0, std::size_t len, std::size_t f0) {
        for (std::size_t j = 0; j < len; ++j) lambda[a0 + j] *= open[f0 + j];
      });
    }
  }
  close_barrier_faces(face_lambda_);
  for (std::size_t w = 0; w < wrap_faces_.size(); ++w) {
    const WrapFace& f = wrap_faces_[w];
    const double ka = kappa_[f.low][f.axis];
    const double kb = kappa_[f.high][f.axis];
    wrap_lambda_[w] = 2.0 * ka * kb / (ka + kb) / fluid.viscosity;
    if (!face_open_[f.axis].empty()) wrap_lambda_[w] *= wrap_open(f);
  }
}

template <int D>
void PoreFluid<D>::build_pattern() {
  const std::size_t n = grid.size();
  faces_.clear();
  wrap_faces_.clear();
  boundary_faces_.clear();
  std::vector<Eigen::Triplet<double>> triplets;
  for (std::size_t c = 0; c < n; ++c) {
    const auto cc = grid.coords(c);
    triplets.emplace_back(static_cast<int>(c), static_cast<int>(c), 1.0);
    for (int k = 0; k < D; ++k) {
      if (cc[k] + 1 < grid.cells[k]) {
        auto up = cc;
        ++up[k];
        const auto b = grid.index(up);
        faces_.push_back({static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(b), k, 0, 0});
        triplets.emplace_back(static_cast<int>(c), static_cast<int>(b), 1.0);
        triplets.emplace_back(static_cast<int>(b), static_cast<int>(c), 1.0);
      }
      if (grid.periodic[k]) {
        // No boundary along k: the last layer's cells meet the first's
        // (a cell meets itself with one cell along k, which couples nothing).
        if (cc[k] + 1 == grid.cells[k] && grid.cells[k] > 1) {
          auto first = cc;
          first[k] = 0;
          auto end = cc;
          end[k] = grid.cells[k];
          const auto b = grid.index(first);
          wrap_faces_.push_back({static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(b), k,
                                 grid.face_index(k, first), grid.face_index(k, end), 0, 0,
                                 grid.cells[k] == 2});
          triplets.emplace_back(static_cast<int>(c), static_cast<int>(b), 1.0);
          triplets.emplace_back(static_cast<int>(b), static_cast<int>(c), 1.0);
        }
        continue;
      }
      if (cc[k] == 0)
        boundary_faces_.push_back({static_cast<std::uint32_t>(c), 2 * k, grid.face_index(k, cc), -1});
      if (cc[k] + 1 == grid.cells[k]) {
        auto up = cc;
        ++up[k];
        boundary_faces_.push_back({static_cast<std::uint32_t>(c), 2 * k + 1, grid.face_index(k, up), -1});
      }
    }
  }
  for (auto& bf : boundary_faces_) {
    const auto cc = grid.coords(bf.cell);
    const int axis = bf.side / 2;
    bf.area = grid.face_area(axis, cc);
    bf.half = 0.5 * grid.width(axis, cc[axis]);
  }
  for (auto& w : wrap_faces_) w.area = grid.face_area(w.axis, grid.coords(w.low));
  assign_patches();
  assign_barriers();
  matrix_.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  matrix_.setFromTriplets(triplets.begin(), triplets.end());
  matrix_.makeCompressed();
  const double* base = matrix_.valuePtr();
  auto pos = [&](std::size_t r, std::size_t c) {
    return static_cast<std::size_t>(
        &matrix_.coeffRef(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) - base);
  };
  diag_pos_.resize(n);
  for (std::size_t c = 0; c < n; ++c) diag_pos_[c] = pos(c, c);
  for (auto& f : faces_) {
    f.pos_ab = pos(f.a, f.b);
    f.pos_ba = pos(f.b, f.a);
  }
  for (auto& w : wrap_faces_) {
    w.pos_lh = pos(w.low, w.high);
    w.pos_hl = pos(w.high, w.low);
  }
  wrap_lambda_.assign(wrap_faces_.size(), 0.0);
  wrap_carried_.assign(wrap_faces_.size(), 0.0);
  rhs_.resize(static_cast<Eigen::Index>(n));
  std::vector<std::size_t> strides(D);
  std::size_t stride = 1;
  for (int k = 0; k < D; ++k) {
    strides[static_cast<std::size_t>(k)] = stride;
    stride *= static_cast<std::size_t>(grid.cells[k]);
  }
  operator_.resize(n, strides);
  for (const auto& w : wrap_faces_) operator_.extra.push_back({w.low, w.high, 0.0});
}

template <int D>
void PoreFluid<D>::assign_patches() {
  patch_faces_.assign(patches.size(), 0);
  patch_area_.assign(patches.size(), 0.0);
  patch_inflow_.assign(patches.size(), 0.0);
  for (auto& bf : boundary_faces_) {
    const Vec<D> centre = grid.centre(grid.coords(bf.cell));
    bf.patch = -1;
    for (std::size_t p = 0; p < patches.size(); ++p) {
      if (patches[p].side == bf.side && patches[p].holds(centre)) {
        bf.patch = static_cast<int>(p);
        ++patch_faces_[p];
        patch_area_[p] += bf.area;
        break;
      }
    }
  }
}

template <int D>
void PoreFluid<D>::assign_barriers() {
  blocked_.clear();
  barrier_faces_.assign(barriers.size(), 0);
  for (std::size_t b = 0; b < barriers.size(); ++b) {
    const auto& barrier = barriers[b];
    const int k = barrier.axis;
    // The plane of faces nearest `at` (the scene reader checks that it is
    // one), between cell layers plane - 1 and plane along k.
    const int plane = grid.nearest_face(k, barrier.at);
    if (plane < 1 || plane >= grid.cells[k]) continue;
    for (std::size_t c = 0; c < grid.size(); ++c) {
      auto cc = grid.coords(c);
      if (cc[k] != plane - 1) continue;
      if (!barrier.holds(grid.centre(cc))) continue;
      ++cc[k];
      blocked_.push_back({k, c, grid.face_index(k, cc), b});
      ++barrier_faces_[b];
    }
  }
}

template <int D>
void PoreFluid<D>::close_barrier_faces(std::array<std::vector<double>, D>& per_cell_below) {
  for (const auto& f : blocked_) per_cell_below[f.axis][f.cell_below] = 0.0;
}

template <int D>
void PoreFluid<D>::close_barrier_fields() {
  for (const auto& f : blocked_) face_gq_[f.axis][f.face] = {0.0, 0.0};
}

template <int D>
double PoreFluid<D>::side_lambda(int axis, std::size_t cell) const {
  return kappa_[cell][axis] / fluid.viscosity;
}

template <int D>
void PoreFluid<D>::update(const ParticleData<D>& particles, double dt, double time,
                          const std::vector<Wall<D>>& walls) {
  if (!initialized_) throw std::logic_error("PoreFluid::update before initialize");
  held_ = {};  // new fields: the grains' forces are due again
  const std::size_t n = grid.size();
  using Clock = std::chrono::steady_clock;
  auto lap = [last = Clock::now()]() mutable {
    const auto now = Clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    return s;
  };
  compute_solid(particles);
  compute_wall_solid(walls);
  last_times_.overlaps = lap();
  compute_cell_properties();
  last_times_.properties = lap();
  pressure_older_.swap(pressure_old_);
  pressure_old_ = pressure_;
  if (drained) {
    drain_freely(time);
    last_times_.fields = lap();
    return;
  }

  // Darcy conductances and the fluid carried by the moving skeleton on the
  // interior faces, axis by axis over the runs of faces
  // (FluidGrid::face_run): the face between cell a and a + s is [k][a].
  for (int k = 0; k < D; ++k) {
    const std::size_t s = grid.stride(k);
    // On a grid with graded axes each face's area and the distance between
    // its cells' centres; else the same for all.
    const bool graded = !face_area_[k].empty();
    const double uniform_area = graded ? 0.0 : grid.face_area(k);
    const double coefficient = graded ? 0.0 : dt * uniform_area / grid.spacing[k];
    const double* face_area = graded ? face_area_[k].data() : nullptr;
    const double* inv_distance = graded ? face_inv_distance_[k].data() : nullptr;
    const double* lambda = face_lambda_[k].data();
    double* upper = operator_.upper[static_cast<std::size_t>(k)].data();
    carried_[k].resize(n, 0.0);
    double* carried = carried_[k].data();
    for_each_face_piece(grid, k, [&](std::size_t a0, std::size_t len, std::size_t f0) {
      if (graded) {
        for (std::size_t a = a0; a < a0 + len; ++a)
          upper[a] = dt * face_area[a] * inv_distance[a] * lambda[a];
      } else {
        for (std::size_t a = a0; a < a0 + len; ++a) upper[a] = coefficient * lambda[a];
      }
      if (!carry_with_solid) return;
      // Pore fluid carried across the face by the skeleton: the
      // skeleton's volume flux (mean solid velocity of the two cells,
      // weighted by their solid volumes, times the area) minus the solid
      // that crosses the face (the grains' exact sections times their
      // velocities). The Biot term accounts for the solid; this for the
      // fluid that moves with it.
      const double* section_flux = solid_face_flux_[k].data() + f0;
      for (std::size_t j = 0; j < len; ++j) {
        const std::size_t a = a0 + j;
        const double area = graded ? face_area[a] : uniform_area;
        const double vs = solid_[a] + solid_[a + s];
        const double v_mix = vs > 0.0 ? (solid_flux_[a][k] + solid_flux_[a + s][k]) / vs : 0.0;
        carried[a] = dt * (v_mix * area - section_flux[j]);
      }
      if (!face_open_[k].empty()) {
        for (std::size_t j = 0; j < len; ++j) carried[a0 + j] *= face_open_[k][f0 + j];
      }
    });
  }
  if (carry_with_solid) close_barrier_faces(carried_);
  // The same across a periodic grid's ends. A grain's section on the face
  // there is at face 0 or at face `cells`, whichever side its centre is on.
  for (std::size_t w = 0; w < wrap_faces_.size(); ++w) {
    const WrapFace& f = wrap_faces_[w];
    const int k = f.axis;
    const double area = f.area;
    operator_.extra[w].g = dt * area / grid.spacing[k] * wrap_lambda_[w];
    wrap_carried_[w] = 0.0;
    if (!carry_with_solid) continue;
    const double vs = solid_[f.low] + solid_[f.high];
    const double v_mix = vs > 0.0 ? (solid_flux_[f.low][k] + solid_flux_[f.high][k]) / vs : 0.0;
    const double section_flux = solid_face_flux_[k][f.face_first] + solid_face_flux_[k][f.face_last];
    wrap_carried_[w] = dt * (v_mix * area - section_flux);
    if (!face_open_[k].empty()) wrap_carried_[w] *= wrap_open(f);
  }
  // The cells' growth since the last fluid step (a grid that follows a
  // deforming cell): pore volume gained, as solid lost would be.
  const double growth = grid.any_graded() ? 0.0 : uniform_volume_ - volume_old_;
  // Per cell, into the grid's stencil (GridOperator): the storage and the
  // conductances of its faces on the diagonal; the stored pressure, the
  // Biot source and what its faces carry in on the right-hand side. A
  // cell's lower face along k is [k][c - s_k]; where c is on the grid's
  // first layer along k that is an entry of the last layer, which stays
  // zero.
  Eigen::VectorXd& diagonal = operator_.diagonal;
  const bool carry = carry_with_solid;
  // In blocks of cells (in parallel on a large grid), each in loops the
  // compiler vectorises: first the cell's own faces, then its lower ones.
  constexpr std::size_t block = 4096;
  auto cells_of_block = [&](std::int64_t b) {
    const std::size_t begin = static_cast<std::size_t>(b) * block;
    const std::size_t end = std::min(n, begin + block);
    double* diag = diagonal.data();
    double* rhs = rhs_.data();
    for (std::size_t c = begin; c < end; ++c) {
      const double storage = storage_of(c);
      diag[c] = storage;
      rhs[c] = storage * pressure_[c] + (solid_[c] - solid_old_[c]) + (wall_solid_[c] - wall_solid_old_[c]) -
               growth;
    }
    for (int k = 0; k < D; ++k) {
      const std::size_t s = grid.stride(k);
      const double* upper = operator_.upper[static_cast<std::size_t>(k)].data();
      const double* carried = carried_[k].data();
      for (std::size_t c = begin; c < end; ++c) diag[c] += upper[c];
      for (std::size_t c = std::max(begin, s); c < end; ++c) diag[c] += upper[c - s];
      if (!carry) continue;
      for (std::size_t c = begin; c < end; ++c) rhs[c] -= carried[c];
      for (std::size_t c = std::max(begin, s); c < end; ++c) rhs[c] += carried[c - s];
    }
  };
  const auto blocks = static_cast<std::int64_t>((n + block - 1) / block);
  if (static_cast<std::int64_t>(n) > parallel_threshold) {
#pragma omp parallel for schedule(static)
    for (std::int64_t b = 0; b < blocks; ++b) cells_of_block(b);
  } else {
    for (std::int64_t b = 0; b < blocks; ++b) cells_of_block(b);
  }
  for (std::size_t w = 0; w < wrap_faces_.size(); ++w) {
    const WrapFace& f = wrap_faces_[w];
    const double g = operator_.extra[w].g;
    diagonal[f.low] += g;
    diagonal[f.high] += g;
    rhs_[f.low] -= wrap_carried_[w];
    rhs_[f.high] += wrap_carried_[w];
  }
  double solid_change = 0.0;  // the pore volume lost
  double solid_moved = 0.0;   // sum of its magnitudes per cell, for the balance's gross flow
  for (std::size_t c = 0; c < n; ++c) {
    const double d_solid = (solid_[c] - solid_old_[c]) + (wall_solid_[c] - wall_solid_old_[c]) - growth;
    solid_change += d_solid;
    solid_moved += std::abs(d_solid);
  }
  // Boundaries.
  boundary_carried_.assign(boundary_faces_.size(), 0.0);
  for (std::size_t i = 0; i < boundary_faces_.size(); ++i) {
    const BoundaryFace& bf = boundary_faces_[i];
    const FluidBoundary& side = condition_of(bf);
    const int axis = bf.side / 2;
    const double area = bf.area;
    const double open = open_of(bf);  // what impermeable walls leave of the face
    if (side.type == FluidBoundaryType::drained) {
      const double t = dt * side_lambda(axis, bf.cell) * open * area / bf.half;
      diagonal[bf.cell] += t;
      rhs_[bf.cell] += t * side.value.at(time);
      if (carry) {
        // The pore fluid the skeleton carries across a drained side, as
        // across an interior face, with the boundary cell's solid
        // velocity: it comes from (or goes to) the water outside at the
        // side's pressure, so it passes without Darcy's resistance. Without
        // it, water that merely follows the grains across the side would
        // have to be drawn through the half cell by a pressure drop, which
        // drains a consolidating bed faster than Terzaghi (by about n h/2
        // of its drainage length).
        const double fluid_flux = solid_velocity_[bf.cell][axis] * area - solid_face_flux_[axis][bf.index];
        const bool upper = (bf.side & 1) != 0;
        const double carried_in = dt * open * (upper ? -fluid_flux : fluid_flux);
        rhs_[bf.cell] += carried_in;
        boundary_carried_[i] = carried_in / (dt * area);
      }
    } else if (side.type == FluidBoundaryType::flux) {
      rhs_[bf.cell] += dt * side.value.at(time) * open * area;
    }
  }
  // Sources (pore_fluid_sources.cpp): their water, or the pressures they
  // hold, into their cells' rows. With drains (sources that take water
  // out only) the sources' part is assembled, solved and taken out again
  // until the drains stand open or shut as the solution has them.
  const bool any_drain =
      std::any_of(sources.begin(), sources.end(), [](const FluidSource<D>& s) { return s.drains(); });
  struct Assembled {
    Eigen::VectorXd diagonal;
    std::vector<Eigen::VectorXd> upper;
    std::vector<GridOperator::Coupling> extra;
    Eigen::VectorXd rhs;
  };
  std::optional<Assembled> before_sources;
  if (any_drain) before_sources = Assembled{diagonal, operator_.upper, operator_.extra, rhs_};
  const std::size_t max_passes = 2 * sources.size() + 2;
  last_times_.assembly = 0.0;
  last_times_.solve = 0.0;
  for (std::size_t pass = 1;; ++pass) {
    const SourcePass placed = assemble_sources(dt, time);

    // Initial guess (CG): the pressure extrapolated linearly from the last
    // two fluid steps, which follows a smoothly changing flow.
    const bool extrapolate = updates_ > 0 && pressure_older_.size() == n;
    for (std::size_t c = 0; c < n; ++c) {
      solution_[static_cast<Eigen::Index>(c)] =
          extrapolate ? 2.0 * pressure_old_[c] - pressure_older_[c] : pressure_old_[c];
    }
    if (solver_.kind() == PressureSolverKind::cholesky) {
      // The same entries into the stored matrix.
      double* values = matrix_.valuePtr();
      for (std::size_t c = 0; c < n; ++c) values[diag_pos_[c]] = diagonal[static_cast<Eigen::Index>(c)];
      for (const Face& f : faces_) {
        const double t = operator_.upper[static_cast<std::size_t>(f.axis)][f.a];
        values[f.pos_ab] = -t;
        values[f.pos_ba] = -t;
      }
      for (std::size_t w = 0; w < wrap_faces_.size(); ++w) {
        const WrapFace& f = wrap_faces_[w];
        const double g = operator_.extra[w].g;
        // With two cells along the axis the entry also holds the stencil face.
        values[f.pos_lh] = (f.shared ? values[f.pos_lh] : 0.0) - g;
        values[f.pos_hl] = (f.shared ? values[f.pos_hl] : 0.0) - g;
      }
    }
    last_times_.assembly += lap();
    const SolveStats stats = solver_.kind() == PressureSolverKind::cholesky
                                 ? solver_.solve(matrix_, rhs_, solution_)
                                 : solver_.solve(operator_, rhs_, solution_);
    if (pass == 1) {
      last_solve_ = stats;
    } else {
      last_solve_.iterations += stats.iterations;
      last_solve_.residual = std::max(last_solve_.residual, stats.residual);
    }
    if (!placed.given_screens.empty()) superpose_given_screens(placed.given_screens, dt);
    last_times_.solve += lap();
    for (std::size_t c = 0; c < n; ++c) pressure_[c] = solution_[static_cast<Eigen::Index>(c)];
    take_source_inflows(placed, dt, time);
    if (!any_drain || !settle_drains(time)) break;
    if (pass == max_passes) {
      throw std::runtime_error(fmt::format(
          "pore pressure: the drains (sources with drain = true) did not settle open or shut in {} passes at "
          "t = {:.6g} s; give them cells further apart, or a smaller step",
          max_passes, time));
    }
    diagonal = before_sources->diagonal;
    operator_.upper = before_sources->upper;
    operator_.extra = before_sources->extra;
    rhs_ = before_sources->rhs;
  }

  compute_face_fields(time);
  // Balance: summed over the cells, the interior fluxes cancel and
  // inflow = stored + pore change.
  FluidBalance b;
  for (std::size_t c = 0; c < n; ++c) {
    b.stored += storage_of(c) * (pressure_[c] - pressure_old_[c]);
  }
  b.pore_change = -solid_change;
  // Each side's and each patch's flow counts in the gross on its own: on
  // one side a patch's inflow and the rest's outflow can cancel.
  std::array<double, 2 * D> rest = side_inflow_;
  for (std::size_t p = 0; p < patches.size(); ++p) {
    rest[patches[p].side] -= patch_inflow_[p];
    b.gross += std::abs(patch_inflow_[p] * dt);
  }
  for (int s = 0; s < 2 * D; ++s) {
    b.inflow += side_inflow_[s] * dt;
    b.gross += std::abs(rest[s] * dt);
  }
  for (double q : source_inflow_) {
    b.inflow += q * dt;
    b.gross += std::abs(q * dt);
  }
  b.gross += solid_moved;
  b.gross += std::abs(b.stored);
  close_step(b, time);
  last_times_.fields = lap();
}

template <int D>
void PoreFluid<D>::close_step(const FluidBalance& b, double time) {
  last_ = b;
  total_.gross += b.gross;
  total_.inflow += b.inflow;
  total_.stored += b.stored;
  total_.pore_change += b.pore_change;
  solid_old_ = solid_;
  wall_solid_old_ = wall_solid_;
  volume_old_ = uniform_volume_;
  time_ = time;
  ++updates_;
}

template <int D>
void PoreFluid<D>::drain_freely(double time) {
  const std::size_t n = grid.size();
  const double growth = grid.any_graded() ? 0.0 : uniform_volume_ - volume_old_;
  FluidBalance b;
  for (std::size_t c = 0; c < n; ++c) {
    const double lost = (solid_[c] - solid_old_[c]) + (wall_solid_[c] - wall_solid_old_[c]) - growth;
    b.pore_change -= lost;
    b.gross += std::abs(lost);
    b.stored -= storage_of(c) * pressure_old_[c];  // the water the pressure's release lets go
  }
  // What flows in: the pore volume gained and the water the stored
  // pressure held.
  b.inflow = b.stored + b.pore_change;
  b.gross += std::abs(b.stored) + std::abs(b.inflow);
  pressure_.assign(n, 0.0);
  side_inflow_.fill(0.0);
  std::fill(patch_inflow_.begin(), patch_inflow_.end(), 0.0);
  std::fill(source_inflow_.begin(), source_inflow_.end(), 0.0);
  for (auto& carried : carried_) std::fill(carried.begin(), carried.end(), 0.0);
  std::fill(wrap_carried_.begin(), wrap_carried_.end(), 0.0);
  std::fill(boundary_carried_.begin(), boundary_carried_.end(), 0.0);
  last_solve_ = {};
  last_times_.assembly = 0.0;
  last_times_.solve = 0.0;
  compute_face_fields(time);
  close_step(b, time);
}

template <int D>
double PoreFluid<D>::mean_pressure() const {
  double sum = 0.0;
  double volume = 0.0;
  for (std::size_t c = 0; c < pressure_.size(); ++c) {
    sum += pressure_[c] * volume_of(c);
    volume += volume_of(c);
  }
  return volume > 0.0 ? sum / volume : 0.0;
}

template <int D>
void PoreFluid<D>::compute_face_fields(double time) {
  for (int k = 0; k < D; ++k) {
    const std::size_t s = grid.stride(k);
    const double inv_h = inv_spacing_[k];
    const double* lambda = face_lambda_[k].data();
    const double* inv_distance = face_inv_distance_[k].empty() ? nullptr : face_inv_distance_[k].data();
    std::array<double, 2>* gq = face_gq_[k].data();
    for_each_face_piece(grid, k, [&](std::size_t a0, std::size_t len, std::size_t f0) {
      if (inv_distance != nullptr) {
        for (std::size_t j = 0; j < len; ++j) {
          const std::size_t a = a0 + j;
          const double g = (pressure_[a + s] - pressure_[a]) * inv_distance[a];
          gq[f0 + j] = {g, -lambda[a] * g};
        }
        return;
      }
      for (std::size_t j = 0; j < len; ++j) {
        const std::size_t a = a0 + j;
        const double g = (pressure_[a + s] - pressure_[a]) * inv_h;
        gq[f0 + j] = {g, -lambda[a] * g};
      }
    });
  }
  close_barrier_fields();
  // A face an impermeable wall covers whole: no water passes, as at a
  // barrier (the cell beyond is cut off).
  for (int k = 0; k < D; ++k) {
    for (std::size_t f = 0; f < face_open_[k].size(); ++f) {
      if (face_open_[k][f] == 0.0) face_gq_[k][f] = {0.0, 0.0};
    }
  }
  for (std::size_t w = 0; w < wrap_faces_.size(); ++w) {
    const WrapFace& f = wrap_faces_[w];
    const double g = (pressure_[f.high] - pressure_[f.low]) * inv_spacing_[f.axis];
    // Closed whole by an impermeable wall: nothing, as at a barrier.
    face_gq_[f.axis][f.face_first] = wrap_open(f) == 0.0 ? std::array<double, 2>{0.0, 0.0}
                                                         : std::array<double, 2>{g, -wrap_lambda_[w] * g};
    face_gq_[f.axis][f.face_last] = face_gq_[f.axis][f.face_first];
  }
  side_inflow_.fill(0.0);
  std::fill(patch_inflow_.begin(), patch_inflow_.end(), 0.0);
  for (std::size_t i = 0; i < boundary_faces_.size(); ++i) {
    const BoundaryFace& bf = boundary_faces_[i];
    const FluidBoundary& side = condition_of(bf);
    const int axis = bf.side / 2;
    const bool upper = (bf.side & 1) != 0;
    // The face's conductance, over its open part (impermeable walls).
    const double open = open_of(bf);
    const double lambda = side_lambda(axis, bf.cell) * open;
    double g = 0.0;
    double inflow = 0.0;  // into the grid over the whole face, m/s
    if (open == 0.0) {
      // Closed by a wall standing on it: no flow, as at no_flow.
    } else if (side.type == FluidBoundaryType::drained) {
      const double ub = side.value.at(time);
      g = upper ? (ub - pressure_[bf.cell]) / bf.half : (pressure_[bf.cell] - ub) / bf.half;
      const double q = -lambda * g;  // along +axis
      inflow = upper ? -q : q;
      // And the water the skeleton carried in across it (update).
      if (i < boundary_carried_.size()) inflow += boundary_carried_[i];
    } else if (side.type == FluidBoundaryType::flux) {
      inflow = side.value.at(time) * open;
      const double q = upper ? -inflow : inflow;
      g = -q / lambda;
    }
    face_gq_[axis][bf.index] = {g, -lambda * g};
    side_inflow_[bf.side] += inflow * bf.area;
    if (bf.patch >= 0) patch_inflow_[static_cast<std::size_t>(bf.patch)] += inflow * bf.area;
  }
}

template <int D>
double PoreFluid<D>::side_pressure(int side) const {
  const int patch = side - 2 * D;
  double force = 0.0;
  double area = 0.0;
  for (const BoundaryFace& bf : boundary_faces_) {
    if (patch >= 0 ? bf.patch != patch : bf.side != side) continue;
    const double g = face_gq_[bf.side / 2][bf.index][0];
    const bool upper = (bf.side & 1) != 0;
    force += bf.area * (upper ? pressure_[bf.cell] + g * bf.half : pressure_[bf.cell] - g * bf.half);
    area += bf.area;
  }
  return area > 0.0 ? force / area : std::numeric_limits<double>::quiet_NaN();
}

template <int D>
std::vector<Vec<D>> PoreFluid<D>::darcy_velocity() const {
  std::vector<Vec<D>> v(grid.size());
  for (std::size_t c = 0; c < grid.size(); ++c) {
    auto cc = grid.coords(c);
    for (int k = 0; k < D; ++k) {
      auto up = cc;
      ++up[k];
      v[c][k] = 0.5 * (face_gq_[k][grid.face_index(k, cc)][1] + face_gq_[k][grid.face_index(k, up)][1]);
    }
  }
  return v;
}

template <int D>
double PoreFluid<D>::critical_time_step(const ParticleData<D>& p, double dem_step,
                                        bool water_stiffness) const {
  double m_min = std::numeric_limits<double>::infinity();
  double r_min = std::numeric_limits<double>::infinity();
  double rho_min = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.inv_mass[i] == 0.0) continue;
    const double m = 1.0 / p.inv_mass[i];
    m_min = std::min(m_min, m);
    r_min = std::min(r_min, p.radius[i]);
    rho_min = std::min(rho_min, m / p.solid_volume(i));
  }
  if (!std::isfinite(m_min)) return dem_step;
  double n_min = 1.0;
  double kappa_min = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < grid.size(); ++c) {
    if (solid_[c] <= 0.0) continue;
    n_min = std::min(n_min, porosity_[c]);
    kappa_min = std::min(kappa_min, kappa_[c].minCoeff());
  }
  n_min = std::clamp(n_min, permeability.min_porosity, permeability.max_porosity);
  // Undrained stiffness of the pore fluid against a grain: modulus K_f/n
  // over a cell, k = (K_f/n) A/h, taken along the cell's shortest side.
  double geometry = 0.0;
  // V / h_k^2 = (the other sides' product) / h_k: on a graded grid at
  // most the widest other sides over the narrowest h_k.
  for (int k = 0; k < D && !grid.any_graded(); ++k)
    geometry = std::max(geometry, grid.cell_volume() / (grid.spacing[k] * grid.spacing[k]));
  for (int k = 0; k < D && grid.any_graded(); ++k) {
    double others = 1.0;
    for (int j = 0; j < D; ++j) {
      if (j == k) continue;
      double widest = 0.0;
      for (int i = 0; i < grid.cells[j]; ++i) widest = std::max(widest, grid.width(j, i));
      others *= widest;
    }
    geometry = std::max(geometry, others / grid.min_width(k));
  }
  const double k_fluid = water_stiffness ? fluid.bulk_modulus / n_min * geometry : 0.0;
  const double dt_stiff = 1.0 / std::sqrt(1.0 / (dem_step * dem_step) + k_fluid / m_min);
  // Drag relaxation time m / (beta V_p / (1-n)), for the explicit drag.
  const double beta = drag == DragLaw::darcy ? n_min * n_min * fluid.viscosity / kappa_min
                                             : ergun_wen_yu_beta(n_min, 2.0 * r_min, 0.0, fluid);
  const double dt_drag = rho_min * (1.0 - n_min) / beta;
  return std::min(dt_stiff, dt_drag);
}

template class PoreFluid<2>;
template class PoreFluid<3>;

}  // namespace darcydem
