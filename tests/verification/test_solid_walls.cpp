// Box walls that take up pore volume (`[[wall]] displaces_fluid = true`):
// a rod pushed into a saturated grid expels its own volume through the
// drained side, as the geometry of its cross-section says; a wall's part of
// a cell is solid in the porosity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/walls/wall.hpp"

using namespace darcydem;

namespace {

/// A box wall [lo, hi], turned by `axes` about its centre, moving at v.
template <int D>
Wall<D> moving_box(const Vec<D>& lo, const Vec<D>& hi, const Vec<D>& v,
                   const Eigen::Matrix<double, D, D>& axes = Eigen::Matrix<double, D, D>::Identity()) {
  Wall<D> w;
  w.name = "rod";
  w.is_box = true;
  w.point = 0.5 * (lo + hi);
  w.half = 0.5 * (hi - lo);
  w.axes = axes;
  w.motion = WallMotion::velocity;
  w.velocity = v;
  return w;
}

/// A grid of cells of side h with no grains, constant permeability, the
/// top (the last axis's upper side) drained and the others closed; the
/// walls `solid` take up pore volume.
template <int D>
PoreFluid<D> empty_grid(double h, const std::array<int, D>& cells) {
  PoreFluid<D> f(PressureSolverKind::cg, 1e-13);
  f.grid.spacing = Vec<D>::Constant(h);
  f.grid.cells = cells;
  f.fluid = {1000.0, 1e-3, 2e9};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<D>::Constant(1e-10);
  f.sides[2 * D - 1] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.solid_walls = {0};
  return f;
}

/// Pushes the rod down for `steps` fluid steps of dt, checking each one:
/// the pore volume falls by the rod's volume swept into the grid,
/// `entry_rate` dt (its section in the grid's top plane times its speed),
/// and that volume leaves through the drained top, less what the pore
/// water's compression stores.
template <int D>
void push_rod(PoreFluid<D>& f, Wall<D> rod, double entry_rate, double dt, int steps) {
  ParticleData<D> none;
  std::vector<Wall<D>> walls{rod};
  f.initialize(none, walls);
  double time = 0.0;
  double worst_out = 0.0;  // largest |out - entry| / entry after the first step
  for (int s = 0; s < steps; ++s) {
    walls[0].advance(dt);
    time += dt;
    f.update(none, dt, time, walls);
    const FluidBalance& b = f.last_balance();
    // The rod's volume in the grid comes from the exact overlaps with the
    // cells (each ~1e-6 m^3, round-off 1e-22); a step changes it by
    // entry_rate dt ~ 1e-8 m^3: 1e-9 of that is far above the round-off
    // and far below any error of the geometry (a cell face's share is
    // 1e-2 of it).
    ASSERT_NEAR(b.pore_change, -entry_rate * dt, 1e-9 * entry_rate * dt) << "step " << s;
    // Conservation to round-off (the solver's tolerance is 1e-13).
    ASSERT_LT(std::abs(b.imbalance()), 1e-10 * b.gross) << "step " << s;
    // Out through the top: what the rod pushed in, less the stored
    // compression, sum n V du / K_f: with pressures of some hundred Pa
    // changing over the time the rod takes to cross a cell (10 s), at K_f
    // = 2e9 Pa that is below 1e-4 of the flow. The first step fills the
    // storage from rest; it is left out.
    const double out = -f.side_inflow(2 * D - 1) * dt;
    if (s > 0) {
      ASSERT_NEAR(out, entry_rate * dt, 1e-4 * entry_rate * dt) << "step " << s;
      worst_out = std::max(worst_out, std::abs(out / (entry_rate * dt) - 1.0));
    }
  }
  std::printf("%dD rod: outflow against the rod's entry, worst %.2e relative\n", D, worst_out);
}

TEST(SolidWalls, ARodPushedIntoTheGridExpelsItsVolumeThroughTheDrainedTop3D) {
  // Cells of 1 cm, 4 x 4 x 8; the rod 1.5 x 1.5 cm (off the cells' faces),
  // from 3 cm above the top to 0.5 cm below it, pushed down at 1 mm/s
  // for 40 steps of 0.5 s: its tip crosses two layers of faces.
  PoreFluid<3> f = empty_grid<3>(0.01, {4, 4, 8});
  const double v = 1e-3;
  const Wall<3> rod =
      moving_box<3>(Vec<3>(0.012, 0.007, 0.075), Vec<3>(0.027, 0.022, 0.11), Vec<3>(0.0, 0.0, -v));
  push_rod<3>(f, rod, 0.015 * 0.015 * v, 0.5, 40);
  // Where it stands now (tip at 0.075 - 0.02 = 0.055 m), the cell
  // (1, 1, 7) between z = 0.07 and 0.08 holds the rod's part over x in
  // [0.012, 0.02] and y in [0.01, 0.02], the whole cell height.
  const std::size_t c = f.grid.index({1, 1, 7});
  EXPECT_NEAR(f.wall_volume()[c], 0.008 * 0.01 * 0.01, 1e-18);
  EXPECT_NEAR(f.porosity()[c], 1.0 - 0.8, 1e-12);
}

TEST(SolidWalls, ATiltedRodExpelsItsSectionInTheTopPlaneTimesItsSpeed2D) {
  // A rectangle 6 mm wide, tilted 30 degrees from the vertical, pushed
  // down at 1 mm/s across the top line of a 2D grid of 1 cm cells: the
  // line cuts it over w / cos(30 deg), and that much times v enters per
  // second (per metre of thickness).
  const double tilt = std::numbers::pi / 6;
  const double w = 0.006;
  PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
  const double v = 1e-3;
  // Its long axis 4 cm; centred 1 cm above the top (y = 0.06) and 2.3 cm
  // along x, so that the top line crosses its long sides only.
  const Eigen::Matrix2d axes = Eigen::Rotation2Dd(tilt).toRotationMatrix();
  const Vec<2> centre(0.023, 0.07);
  const Wall<2> rod =
      moving_box<2>(centre - Vec<2>(0.5 * w, 0.02), centre + Vec<2>(0.5 * w, 0.02), Vec<2>(0.0, -v), axes);
  // Its ends are 2 cos(30 deg) = 1.73 cm above and below its centre: over
  // 30 steps of 0.5 s it moves 1.5 cm, its lower end below the top line
  // from the start and its upper end above it to the last.
  push_rod<2>(f, rod, w / std::cos(tilt) * v, 0.5, 30);
}

TEST(SolidWalls, AFixedWallTakesItsShareOfEachCellsPorosity) {
  // A fixed box over x in [0, 0.015] of a 2D grid of 1 cm cells: the first
  // column is solid, the second half so; nothing flows (a fixed wall
  // changes no volume).
  PoreFluid<2> f = empty_grid<2>(0.01, {3, 2});
  ParticleData<2> none;
  std::vector<Wall<2>> walls{moving_box<2>(Vec<2>(0.0, -0.01), Vec<2>(0.015, 0.03), Vec<2>::Zero())};
  walls[0].motion = WallMotion::fixed;
  f.initialize(none, walls);
  f.update(none, 1.0, 1.0, walls);
  for (int j = 0; j < 2; ++j) {
    EXPECT_NEAR(f.porosity()[f.grid.index({0, j})], 0.0, 1e-12);
    EXPECT_NEAR(f.porosity()[f.grid.index({1, j})], 0.5, 1e-12);
    EXPECT_NEAR(f.porosity()[f.grid.index({2, j})], 1.0, 1e-12);
  }
  EXPECT_EQ(f.last_balance().pore_change, 0.0);
  for (double u : f.pressure()) EXPECT_EQ(u, 0.0);
}

}  // namespace
