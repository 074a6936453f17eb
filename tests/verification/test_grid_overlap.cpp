// Verification 4 of issue 3: a grain moved across cell faces in small steps.
// The solid volume of each cell must change continuously (by at most the
// grain's largest cross-section times the step, plus round-off) and the
// cells' volumes must add up to the grain's volume to 1e-12.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
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
