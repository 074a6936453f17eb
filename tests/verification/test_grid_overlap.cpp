// Verification 4 of issue 3: a grain moved across cell faces in small steps.
// The solid volume of each cell must change continuously (by at most the
// grain's largest cross-section times the step, plus round-off) and the
// cells' volumes must add up to the grain's volume to 1e-12.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <tuple>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"

using namespace darcydem;

namespace {

template <int D>
void sweep(const Vec<D>& from, const Vec<D>& to, double radius) {
  PoreFluid<D> fluid;
  fluid.grid.origin = Vec<D>::Zero();
  fluid.grid.spacing = Vec<D>::Constant(1.0);
  fluid.grid.cells.fill(4);
  ParticleData<D> p;
  p.add(from, radius, 1000.0, 0, false);
  const double volume = particle_volume<D>(radius);
  // Largest cross-section: a chord 2r (x 1 m) in 2D, a disc pi r^2 in 3D.
  const double section = D == 2 ? 2.0 * radius : std::numbers::pi * radius * radius;
  const int steps = 4000;
  const double step = (to - from).norm() / steps;
  std::vector<double> last;
  double worst_sum = 0.0;
  double worst_jump = 0.0;
  for (int s = 0; s <= steps; ++s) {
    p.position[0] = from + (to - from) * (static_cast<double>(s) / steps);
    std::vector<double> cells(fluid.grid.size(), 0.0);
    fluid.for_each_overlap(p, [&](std::size_t c, std::size_t, double v) { cells[c] += v; });
    double sum = 0.0;
    for (double v : cells) sum += v;
    worst_sum = std::max(worst_sum, std::abs(sum - volume) / volume);
    if (!last.empty()) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        worst_jump = std::max(worst_jump, std::abs(cells[c] - last[c]) / (section * step));
      }
    }
    last = cells;
  }
  EXPECT_LT(worst_sum, 1e-12);
  // Continuity: the change per step is bounded by section x step; a jump
  // (a grain's share switching cells at once) would be ~ 1 / step larger.
  EXPECT_LE(worst_jump, 1.0 + 1e-6);
}

}  // namespace

TEST(GridOverlap, DiscAcrossAFace) { sweep<2>(Vec<2>(1.2, 1.5), Vec<2>(1.8, 1.5), 0.3); }
TEST(GridOverlap, DiscAcrossACorner) { sweep<2>(Vec<2>(1.2, 1.3), Vec<2>(2.75, 2.8), 0.45); }
TEST(GridOverlap, SphereAcrossAFace) { sweep<3>(Vec<3>(1.5, 1.5, 1.2), Vec<3>(1.5, 1.5, 1.8), 0.3); }
TEST(GridOverlap, SphereAcrossAnEdge) { sweep<3>(Vec<3>(1.2, 1.3, 1.5), Vec<3>(2.8, 2.7, 1.5), 0.4); }
TEST(GridOverlap, SphereAcrossACorner) { sweep<3>(Vec<3>(1.3, 1.2, 1.25), Vec<3>(2.7, 2.8, 2.75), 0.45); }

TEST(GridOverlap, GrainsInAFullGridAddUpToTheirVolume) {
  // Many spheres anywhere inside the grid: the total solid volume is the sum
  // of their volumes, whatever faces they cut.
  PoreFluid<3> fluid;
  fluid.grid.origin = Vec<3>::Zero();
  fluid.grid.spacing = Vec<3>(1.0, 0.9, 1.1);
  fluid.grid.cells = {5, 5, 5};
  ParticleData<3> p;
  double total = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double r = 0.2 + 0.0012 * i;
    const Vec<3> x(0.5 + std::fmod(0.37 * i, 4.0), 0.5 + std::fmod(0.53 * i, 3.5),
                   0.5 + std::fmod(0.71 * i, 4.5));
    p.add(x, r, 1000.0, 0, false);
    total += particle_volume<3>(r);
  }
  double sum = 0.0;
  fluid.for_each_overlap(p, [&](std::size_t, std::size_t, double v) { sum += v; });
  EXPECT_NEAR(sum, total, 1e-12 * total);
}

TEST(GridOverlap, AGrainAtANaNPositionTouchesNoCell) {
  // A blown-up grain (NaN position) lies outside the grid: no cell or face
  // receives anything from it, and its neighbours in the same group of four
  // keep their exact volumes.
  PoreFluid<3> fluid;
  fluid.grid.origin = Vec<3>::Zero();
  fluid.grid.spacing = Vec<3>::Ones();
  fluid.grid.cells = {3, 3, 3};
  ParticleData<3> p;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  p.add(Vec<3>(1.5, 1.5, 1.5), 0.3, 1000.0, 0, false);
  p.add(Vec<3>(nan, 1.5, 1.5), 0.3, 1000.0, 0, false);
  p.add(Vec<3>(1.1, 1.5, 1.5), 0.3, 1000.0, 0, false);
  std::vector<double> per_grain(3, 0.0);
  int sections_of_nan = 0;
  fluid.for_each_overlap(
      p, [&](std::size_t, std::size_t i, double v) { per_grain[i] += v; },
      [&](int, std::size_t, std::size_t i, double) { sections_of_nan += i == 1 ? 1 : 0; }, true);
  const double v = particle_volume<3>(0.3);
  EXPECT_EQ(per_grain[1], 0.0);
  EXPECT_EQ(sections_of_nan, 0);
  // Closed forms: only round-off.
  EXPECT_NEAR(per_grain[0], v, 1e-14 * v);
  EXPECT_NEAR(per_grain[2], v, 1e-14 * v);
}

TEST(GridOverlap, CellsAndFaceSectionsAgainstBoxFormulas) {
  // Every grain's share of every cell against the ball/box measure of
  // ball_overlap::in_box (inclusion-exclusion over the box's corners with
  // std::atan2), and every section it reports on a face against the area of
  // its cut disc inside the face's rectangle (the 2D in_box). The batched
  // path shares its arctangents among wedges, octants and sections and may
  // take them from the vector library: agreement to 1e-12 of the grain's
  // volume (area) leaves room for a few ulp per angle, nothing more.
  PoreFluid<3> fluid;
  fluid.grid.origin = Vec<3>(-0.1, 0.2, 0.0);
  fluid.grid.spacing = Vec<3>(1.0, 0.9, 1.1);
  fluid.grid.cells = {5, 4, 6};
  ParticleData<3> p;
  for (int i = 0; i < 300; ++i) {
    const double r = 0.2 + 0.0008 * i;
    // Centres anywhere, including within a radius of the grid's sides.
    const Vec<3> x(-0.1 + std::fmod(0.377 * i, 5.0), 0.2 + std::fmod(0.533 * i, 3.6),
                   std::fmod(0.719 * i, 6.6));
    p.add(x, r, 1000.0, 0, false);
  }
  // Centres on cell faces.
  p.add(Vec<3>(0.9, 1.1, 1.1), 0.3, 1000.0, 0, false);
  p.add(Vec<3>(1.9, 2.0, 2.2), 0.45, 1000.0, 0, false);
  // Centres outside the grid, reaching into it across one, two or three sides.
  p.add(Vec<3>(-0.25, 1.0, 1.0), 0.3, 1000.0, 0, false);
  p.add(Vec<3>(2.0, 3.9, 6.65), 0.35, 1000.0, 0, false);
  p.add(Vec<3>(4.95, -0.02, -0.1), 0.4, 1000.0, 0, false);
  const auto& grid = fluid.grid;
  std::vector<std::vector<double>> share(p.size(), std::vector<double>(grid.size(), 0.0));
  std::vector<std::array<std::vector<double>, 3>> area(p.size());
  for (auto& a : area) {
    for (int k = 0; k < 3; ++k) a[k].assign(grid.face_count(k), 0.0);
  }
  fluid.for_each_overlap(
      p, [&](std::size_t c, std::size_t i, double v) { share[i][c] += v; },
      [&](int k, std::size_t face, std::size_t i, double a) { area[i][k][face] += a; }, true);
  double worst_volume = 0.0;
  double worst_area = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    const std::array<double, 3> x{p.position[i][0], p.position[i][1], p.position[i][2]};
    const double volume = particle_volume<3>(r);
    for (std::size_t c = 0; c < grid.size(); ++c) {
      const auto cc = grid.coords(c);
      std::array<double, 3> lo{}, hi{};
      for (int k = 0; k < 3; ++k) {
        lo[k] = grid.origin[k] + cc[k] * grid.spacing[k];
        hi[k] = lo[k] + grid.spacing[k];
      }
      const double ref = ball_overlap::in_box<3>(r, x, lo, hi);
      worst_volume = std::max(worst_volume, std::abs(share[i][c] - ref) / volume);
    }
    // Sections: each face the grain's home cell shares with a neighbour
    // across a crossed plane, and the grid's outer faces. Faces elsewhere
    // must report nothing; the reference is zero there too.
    for (int k = 0; k < 3; ++k) {
      const int a1 = (k + 1) % 3;
      const int a2 = (k + 2) % 3;
      for (int f0 = 0; f0 <= grid.cells[k]; ++f0) {
        const double plane = grid.origin[k] + f0 * grid.spacing[k];
        const double dz = x[k] - plane;
        const double rho2 = r * r - dz * dz;
        for (int f1 = 0; f1 < grid.cells[a1]; ++f1) {
          for (int f2 = 0; f2 < grid.cells[a2]; ++f2) {
            std::array<int, 3> face{};
            face[k] = f0;
            face[a1] = f1;
            face[a2] = f2;
            double ref = 0.0;
            if (rho2 > 0.0) {
              const double lo1 = grid.origin[a1] + f1 * grid.spacing[a1];
              const double lo2 = grid.origin[a2] + f2 * grid.spacing[a2];
              ref = ball_overlap::in_box<2>(std::sqrt(rho2), {x[a1], x[a2]}, {lo1, lo2},
                                            {lo1 + grid.spacing[a1], lo2 + grid.spacing[a2]});
            }
            const double got = area[i][k][grid.face_index(k, face)];
            worst_area = std::max(worst_area, std::abs(got - ref) / (std::numbers::pi * r * r));
          }
        }
      }
    }
  }
  EXPECT_LT(worst_volume, 1e-12);
  EXPECT_LT(worst_area, 1e-12);
}

/// 60,000 grains of radius 0.3 on a jittered lattice of spacing 1, with
/// random velocities.
ParticleData<3> jittered_lattice() {
  ParticleData<3> p;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 40; ++j) {
      for (int k = 0; k < 25; ++k) {
        p.add(Vec<3>(i + 0.5 + jitter(rng), j + 0.5 + jitter(rng), k + 0.5 + jitter(rng)), 0.3, 1000.0, 0,
              false);
        p.velocity.back() = Vec<3>(jitter(rng), jitter(rng), jitter(rng));
      }
    }
  }
  return p;
}

/// The 40 x 25 x 20 grid (20,000 cells) over jittered_lattice(): large
/// enough for the fluid's parallel loops.
void lattice_grid(FluidGrid<3>& grid) {
  grid.origin = Vec<3>::Zero();
  grid.spacing = Vec<3>(1.5, 1.6, 1.25);
  grid.cells = {40, 25, 20};
}

/// f() run on `threads` OpenMP threads; the thread count is restored after.
template <class F>
auto on_threads(int threads, F&& f) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  auto result = f();
  omp_set_num_threads(saved);
  return result;
}

TEST(GridOverlap, SolidVolumesAreTheSameForAnyThreadCount) {
  // The solid volumes are summed in fixed blocks of grains
  // (pore_fluid.cpp), so one and two threads must give the same bits; and
  // every cell must match a plain serial sum of the overlaps up to the
  // order of the additions (1e-12 of the cell's volume).
  const ParticleData<3> p = jittered_lattice();
  auto solid = [&] {
    PoreFluid<3> fluid;
    lattice_grid(fluid.grid);
    fluid.initialize(p);
    return std::make_pair(fluid.solid_volume(), fluid.solid_velocity());
  };
  const auto one = on_threads(1, solid);
  const auto two = on_threads(2, solid);
  EXPECT_EQ(one.first, two.first);
  EXPECT_EQ(one.second, two.second);
  PoreFluid<3> fluid;
  lattice_grid(fluid.grid);
  std::vector<double> serial(fluid.grid.size(), 0.0);
  fluid.for_each_overlap(p, [&](std::size_t c, std::size_t, double v) { serial[c] += v; });
  double worst = 0.0;
  for (std::size_t c = 0; c < serial.size(); ++c) {
    worst = std::max(worst, std::abs(serial[c] - one.first[c]) / fluid.grid.cell_volume());
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(GridOverlap, FluidStepIsTheSameForAnyThreadCount) {
  // The whole fluid step on a grid large enough for its parallel loops
  // (20,000 cells): the cell and face loops write disjoint entries and the
  // balance's sums are serial, so one and two threads must give the same
  // bits for the pressure, the balance and the grains' forces, two steps
  // after the grains moved (Biot source, carried fluid, inflow).
  ParticleData<3> p = jittered_lattice();
  auto run = [&] {
    PoreFluid<3> fluid;
    lattice_grid(fluid.grid);
    fluid.fluid = {1000.0, 1e-3, 1e5};
    fluid.drag = DragLaw::ergun;
    fluid.permeability.diameter = 0.6;
    fluid.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(1e-3)};
    fluid.sides[5] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
    ParticleData<3> moving = p;
    fluid.initialize(moving);
    for (int step = 1; step <= 2; ++step) {
      for (std::size_t i = 0; i < moving.size(); ++i) moving.position[i] += 1e-3 * moving.velocity[i];
      fluid.update(moving, 1e-3, 1e-3 * step);
    }
    std::vector<Vec<3>> force(moving.size());
    fluid.particle_forces(moving, Vec<3>(0.0, 0.0, -9.81), force);
    return std::make_tuple(fluid.pressure(), fluid.total_balance().stored, force);
  };
  const auto one = on_threads(1, run);
  const auto two = on_threads(2, run);
  EXPECT_EQ(std::get<0>(one), std::get<0>(two));
  EXPECT_EQ(std::get<1>(one), std::get<1>(two));
  EXPECT_EQ(std::get<2>(one), std::get<2>(two));
  // The step did something: a pressure builds up from the inflow.
  double largest = 0.0;
  for (double u : std::get<0>(one)) largest = std::max(largest, std::abs(u));
  EXPECT_GT(largest, 0.0);
}
