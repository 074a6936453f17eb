// Box walls that take up pore volume (`[[wall]] displaces_fluid = true`):
// a rod pushed into a saturated grid expels its own volume through the
// drained side, as the geometry of its cross-section says; a wall's part of
// a cell is solid in the porosity.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
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
  w.shape = WallShape::box;
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

/// Pushes the rod (or a platen) in for `steps` fluid steps of dt,
/// checking each one: the pore volume falls by the rod's volume swept into
/// the grid, `entry_rate` dt (its section in the grid's top plane times
/// its speed), and that volume leaves through the drained side `drained`
/// (the top unless given), less what the pore water's compression stores.
/// `face` (if given) maps the wall's place along its axis to where its
/// solid's face stands, for a plane in the grid's first layer (below):
/// the volume swept is then entry_rate dt times the face's move over the
/// wall's.
template <int D>
void push_rod(PoreFluid<D>& f, Wall<D> rod, double entry_rate, double dt, int steps, int drained = 2 * D - 1,
              const std::function<double(double)>& face = {}) {
  ParticleData<D> none;
  std::vector<Wall<D>> walls{rod};
  f.initialize(none, walls);
  double time = 0.0;
  double worst_out = 0.0;  // largest |out - entry| / entry after the first step
  for (int s = 0; s < steps; ++s) {
    const double before = walls[0].point[D - 1];
    walls[0].advance(dt, time);
    time += dt;
    f.update(none, dt, time, walls);
    const double after = walls[0].point[D - 1];
    const double swept = face ? (face(before) - face(after)) / (before - after) : 1.0;
    const FluidBalance& b = f.last_balance();
    // The rod's volume in the grid comes from the exact overlaps with the
    // cells (each ~1e-6 m^3, round-off 1e-22); a step changes it by
    // entry_rate dt ~ 1e-8 m^3: 1e-9 of that is far above the round-off
    // and far below any error of the geometry (a cell face's share is
    // 1e-2 of it).
    ASSERT_NEAR(b.pore_change, -entry_rate * dt * swept, 1e-9 * std::abs(entry_rate * dt)) << "step " << s;
    // Conservation to round-off (the solver's tolerance is 1e-13).
    ASSERT_LT(std::abs(b.imbalance()), 1e-10 * b.gross) << "step " << s;
    // Out through the top: what the rod pushed in, less the stored
    // compression, sum n V du / K_f: with pressures of some hundred Pa
    // changing over the time the rod takes to cross a cell (10 s), at K_f
    // = 2e9 Pa that is below 1e-4 of the flow. The first step fills the
    // storage from rest; it is left out.
    const double out = -f.side_inflow(drained) * dt;
    if (s > 0) {
      ASSERT_NEAR(out, entry_rate * dt, 1e-4 * std::abs(entry_rate * dt)) << "step " << s;
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

/// Where the solid of a plane facing down (-z) at height z stands, under a
/// grid's top side at `top` whose top layer is `layer` wide: a
/// hundred-thousandth of the layer below the side while the plane is on or
/// above it (so that it stands on the side), that offset shrinking in
/// proportion as the plane crosses the layer, and on the plane below it
/// (behind_plane, PoreFluid::displaced_box).
double face_below_top(double z, double top, double layer) {
  return std::min(z, top) - 1e-5 * layer * std::max(1.0 - (top - z) / layer, 0.0);
}

/// A plane wall through `point` with unit `normal` (into the domain),
/// moving at v.
template <int D>
Wall<D> moving_plane(const Vec<D>& point, const Vec<D>& normal, const Vec<D>& v) {
  Wall<D> w;
  w.name = "platen";
  w.point = point;
  w.normal = normal;
  w.motion = WallMotion::velocity;
  w.velocity = v;
  return w;
}

TEST(SolidWalls, APlatenPushedDownExpelsItsAreaTimesItsSpeed3D) {
  // A plane facing down (normal -z) over the whole 4 x 4 cm grid of 1 cm
  // cells, from z = 0.075 down at 1 mm/s for 40 steps of 0.5 s, across the
  // faces at 0.07 and 0.06: the solid above it grows by the grid's section
  // times v per second. The top, under the platen, is closed; that water
  // leaves through the bottom, drained.
  PoreFluid<3> f = empty_grid<3>(0.01, {4, 4, 8});
  f.sides[5] = {};
  f.sides[4] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  const double v = 1e-3;
  const Wall<3> platen =
      moving_plane<3>(Vec<3>(0.01, 0.02, 0.075), Vec<3>(0.0, 0.0, -1.0), Vec<3>(0.0, 0.0, -v));
  // In the top layer the face moves at 1 - 1e-5 of the platen's speed.
  push_rod<3>(f, platen, 0.04 * 0.04 * v, 0.5, 40, 4, [](double z) { return face_below_top(z, 0.08, 0.01); });
  // Now at z = 0.055: the layer between 0.05 and 0.06 is half solid, the
  // two above it solid, the rest free.
  for (int k = 0; k < 8; ++k) {
    const double expected = k < 5 ? 1.0 : k == 5 ? 0.5 : 0.0;
    EXPECT_NEAR(f.porosity()[f.grid.index({2, 1, k})], expected, 1e-12) << "layer " << k;
  }
}

TEST(SolidWalls, ASidePlatenPushedInExpelsItsHeightTimesItsSpeed2D) {
  // A plane facing +x (solid behind it, at smaller x) moved from x = 0.013
  // to 0.028 m at 1 mm/s across the 2D grid's faces at 0.02: the solid
  // grows by the grid's height, 6 cm, times v per second; out through the
  // drained top.
  PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
  const double v = 1e-3;
  const Wall<2> platen = moving_plane<2>(Vec<2>(0.013, 0.0), Vec<2>(1.0, 0.0), Vec<2>(v, 0.0));
  push_rod<2>(f, platen, 0.06 * v, 0.5, 30);
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

/// Steady upward flow through the empty grid of empty_grid<3> (cells of
/// 1 cm, 4 x 4 x 8, k = 1e-10 m^2, mu = 1e-3 Pa s): q = 1e-5 m/s in at the
/// bottom, the top drained, so u(z) = (q mu / k)(H - z) = 100 (0.08 - z)
/// Pa, linear. With K_f = 2e9 Pa the grid's consolidation time is about
/// H^2 mu n / (k K_f) = 3e-5 s: three implicit steps of 1 s reach the
/// steady state to the solver's tolerance. `walls[0]` is fixed.
PoreFluid<3> steady_column(std::vector<Wall<3>>& walls) {
  PoreFluid<3> f = empty_grid<3>(0.01, {4, 4, 8});
  f.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(1e-5)};
  walls[0].motion = WallMotion::fixed;
  ParticleData<3> none;
  f.initialize(none, walls);
  for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
  return f;
}

// The thrust of the excess pore pressure on a box wall that displaces the
// fluid, -(integral of u n dA) over its wetted surface: in a pressure
// field linear in space, closed forms.

TEST(WallThrust, ABoxInsideTheGridFeelsMinusItsVolumeTimesTheGradient) {
  // A box 1.5 x 1 x 2 cm turned 0.4 rad about (1, 2, 3), centred in the
  // grid, all of it inside: Archimedes in the excess pressure, -V grad u
  // = V q mu / k = 3e-6 x 100 = 3e-4 N upwards, whatever its orientation.
  const Eigen::Matrix3d axes =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Vec<3> centre(0.02, 0.02, 0.04);
  const Vec<3> half(0.0075, 0.005, 0.01);
  std::vector<Wall<3>> walls{moving_box<3>(centre - half, centre + half, Vec<3>::Zero(), axes)};
  const PoreFluid<3> f = steady_column(walls);
  const double gradient = -1e-5 * 1e-3 / 1e-10;  // Pa/m
  // The field: linear to the solver's tolerance (1e-13 relative).
  EXPECT_NEAR(f.pressure_at(Vec<3>(0.02, 0.02, 0.005)), -gradient * 0.075, 1e-9);
  const Vec<3> thrust = f.wall_thrust(walls, 0);
  const double expected = -3e-6 * gradient;
  // The cells' parts of the box are exact to round-off (1e-12 of the box)
  // and the gradient uniform to the solver's tolerance: 1e-9 of the thrust
  // is far above both and far below any error of the formula (a cell's
  // share of the box is 1e-2 of it or more).
  EXPECT_NEAR(thrust.z(), expected, 1e-9 * expected);
  EXPECT_NEAR(thrust.x(), 0.0, 1e-9 * expected);
  EXPECT_NEAR(thrust.y(), 0.0, 1e-9 * expected);
}

TEST(WallThrust, ABoxThroughASideFeelsThePressureOnItsWettedFaceOnly) {
  // A rod 1.5 x 1.5 cm through the bottom side (the inlet, u = 8 Pa
  // there), its upper end at z = 0.03 m inside the grid: the water pushes
  // on that end only, down, with u(0.03) = 5 Pa: -5 A. Without the side's
  // term (its section times the inlet's pressure) the volume's term alone
  // would give +3 A, the wrong way.
  const double a = 0.015 * 0.015;
  std::vector<Wall<3>> walls{
      moving_box<3>(Vec<3>(0.012, 0.007, -0.02), Vec<3>(0.027, 0.022, 0.03), Vec<3>::Zero())};
  const PoreFluid<3> f = steady_column(walls);
  const Vec<3> down = f.wall_thrust(walls, 0);
  EXPECT_NEAR(down.z(), -5.0 * a, 1e-9 * 5.0 * a);
  EXPECT_NEAR(down.x(), 0.0, 1e-9 * 5.0 * a);
  // The same rod through the drained top (u = 0 there), its lower end at
  // z = 0.05: u = 3 Pa pushes it up, +3 A.
  std::vector<Wall<3>> top{
      moving_box<3>(Vec<3>(0.012, 0.007, 0.05), Vec<3>(0.027, 0.022, 0.11), Vec<3>::Zero())};
  const PoreFluid<3> g = steady_column(top);
  EXPECT_NEAR(g.wall_thrust(top, 0).z(), 3.0 * a, 1e-9 * 3.0 * a);
  // Beyond the grid: no water on it.
  Wall<3> away = top[0];
  away.point.z() += 0.1;
  EXPECT_EQ(g.wall_thrust(std::vector<Wall<3>>{away}, 0), Vec<3>::Zero());
}

TEST(WallThrust, APlatenFeelsThePressureOnItsFaceAlongItsNormal) {
  // In the steady column, u = 100 (0.08 - z) Pa over the 4 x 4 cm grid
  // (A = 1.6e-3 m^2): a plane facing down at z = 0.055 (solid above it)
  // takes u(0.055) = 2.5 Pa on its face, pushing it up: +2.5 A; a floor
  // facing up at z = 0.02 (solid below) takes u = 6 Pa, pushing it down:
  // -6 A. Nothing across: the thrust on a plane is along its normal.
  const double a = 0.04 * 0.04;
  std::vector<Wall<3>> above{
      moving_plane<3>(Vec<3>(0.0, 0.0, 0.055), Vec<3>(0.0, 0.0, -1.0), Vec<3>::Zero())};
  const PoreFluid<3> f = steady_column(above);
  const Vec<3> up = f.wall_thrust(above, 0);
  // The pressures to the solver's tolerance, the volumes exact: as for
  // the boxes above, 1e-9 of the thrust.
  EXPECT_NEAR(up.z(), 2.5 * a, 1e-9 * 2.5 * a);
  EXPECT_EQ(up.x(), 0.0);
  EXPECT_EQ(up.y(), 0.0);
  std::vector<Wall<3>> floor{
      moving_plane<3>(Vec<3>(0.03, 0.01, 0.02), Vec<3>(0.0, 0.0, 1.0), Vec<3>::Zero())};
  const PoreFluid<3> g = steady_column(floor);
  EXPECT_NEAR(g.wall_thrust(floor, 0).z(), -6.0 * a, 1e-9 * 6.0 * a);
  // On the grid's bottom side, and below it, the floor takes the side's
  // pressure, the inlet's 8 Pa, as at a face kept 1e-5 of a cell (1e-7 m)
  // inside the grid: u = 8 - 1e-5 Pa.
  for (double z : {0.0, -0.01}) {
    floor[0].point.z() = z;
    EXPECT_NEAR(g.wall_thrust(floor, 0).z(), -(8.0 - 1e-5) * a, 1e-9 * 8.0 * a) << "floor at z = " << z;
  }
}

TEST(WallThrust, PlatensThatMeetCountTheirSharedSolidOnceAndTakeTheSectionTheOthersBound) {
  // A cell of four platens in the steady column (u = 100 (0.08 - z) Pa,
  // grid 6 x 4 x 8 cells of 1 cm): x_low at x = 0.015 (facing +x), x_high
  // at 0.043 (facing -x), both beyond the first layers (where a plane's
  // solid keeps a sliver inside the grid), a floor at z = 0.02 (facing +z), a lid at 0.06
  // (facing -z); the water is in [0.015, 0.043] x [0, 0.04] x [0.02, 0.06],
  // the rest of the grid solid. By hand: the walls' volume is the grid's
  // less that, 1.92e-4 - 0.028 x 0.04 x 0.04 = 1.472e-4 m^3; a corner cell
  // below the floor and beside x_low is solid once (1e-6 m^3, not 1.5e-6:
  // the platens overlap there). Each platen takes the water's thrust over
  // the section the others bound: the lid u(0.06) = 2 Pa over 0.028 x 0.04
  // (+2.24e-3 N along z), the floor u(0.02) = 6 Pa (-6.72e-3 N), each side
  // the integral of u over 0.04 x [0.02, 0.06], 0.04 x 0.16 = 6.4e-3 N,
  // pushing it out. The grid's whole section instead would give the lid
  // 3.2e-3 N and each side 1.28e-2 N.
  std::vector<Wall<3>> walls{moving_plane<3>(Vec<3>(0.015, 0.0, 0.0), Vec<3>(1.0, 0.0, 0.0), Vec<3>::Zero()),
                             moving_plane<3>(Vec<3>(0.043, 0.0, 0.0), Vec<3>(-1.0, 0.0, 0.0), Vec<3>::Zero()),
                             moving_plane<3>(Vec<3>(0.0, 0.0, 0.02), Vec<3>(0.0, 0.0, 1.0), Vec<3>::Zero()),
                             moving_plane<3>(Vec<3>(0.0, 0.0, 0.06), Vec<3>(0.0, 0.0, -1.0), Vec<3>::Zero())};
  for (auto& w : walls) w.motion = WallMotion::fixed;
  PoreFluid<3> f = empty_grid<3>(0.01, {6, 4, 8});
  f.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(1e-5)};
  f.solid_walls = {0, 1, 2, 3};
  ParticleData<3> none;
  f.initialize(none, walls);
  for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
  double total = 0.0;
  for (double v : f.wall_volume()) total += v;
  // The volumes exact to round-off (1e-16 of a cell, 1e-6 m^3).
  EXPECT_NEAR(total, 1.472e-4, 1e-18);
  EXPECT_NEAR(f.wall_volume()[f.grid.index({1, 2, 1})], 1e-6, 1e-20);
  EXPECT_NEAR(f.wall_volume()[f.grid.index({1, 2, 2})], 0.5e-6, 1e-20);
  EXPECT_NEAR(f.wall_volume()[f.grid.index({4, 2, 6})], 1e-6, 1e-20);
  EXPECT_NEAR(f.wall_volume()[f.grid.index({4, 2, 5})], 0.7e-6, 1e-20);
  // The thrusts: the pressures to the solver's tolerance, the sections
  // exact, and on whole cells the faces' pressures integrate the linear u
  // exactly: 1e-9 of each, as for the single platen above.
  const double lid = 2.0 * 0.028 * 0.04;
  const double floor = 6.0 * 0.028 * 0.04;
  const double side = 0.04 * 0.16;
  EXPECT_NEAR(f.wall_thrust(walls, 3).z(), lid, 1e-9 * lid);
  EXPECT_NEAR(f.wall_thrust(walls, 2).z(), -floor, 1e-9 * floor);
  EXPECT_NEAR(f.wall_thrust(walls, 1).x(), side, 1e-9 * side);
  EXPECT_NEAR(f.wall_thrust(walls, 0).x(), -side, 1e-9 * side);
  // A box that displaces the fluid, reaching behind x_low: only its part
  // in the water counts, [0.015, 0.025] x [0.01, 0.02] x [0.03, 0.04].
  walls.push_back(moving_box<3>(Vec<3>(0.01, 0.01, 0.03), Vec<3>(0.025, 0.02, 0.04), Vec<3>::Zero()));
  walls.back().motion = WallMotion::fixed;
  PoreFluid<3> g = empty_grid<3>(0.01, {6, 4, 8});
  g.solid_walls = {0, 1, 2, 3, 4};
  g.initialize(none, walls);
  total = 0.0;
  for (double v : g.wall_volume()) total += v;
  EXPECT_NEAR(total, 1.472e-4 + 1e-6, 1e-18);
  EXPECT_NEAR(g.wall_volume()[g.grid.index({1, 1, 3})], 1e-6, 1e-20);  // x_low's half and the box's
}

TEST(WallThrust, APlateAcrossTheFlowHoldsThePressureDifference2D) {
  // A 2D grid of 1 cm cells, 6 x 6, drained at 50 Pa below and 0 above,
  // with an impermeable plate across its whole width at y = 0.03: no flow,
  // 50 Pa everywhere below it and 0 above, so the plate takes 50 Pa over
  // 6 cm, 3 N/m upwards. A box wall over x in [0.01, 0.03], y in [0.02,
  // 0.04] across the plate feels 50 Pa on its lower face and nothing on
  // its upper one: 50 x 0.02 = 1 N/m upwards (the jump across the barrier
  // in its section; the cells' gradients are zero).
  PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
  f.sides[2] = {FluidBoundaryType::drained, TimeSeries::constant(50.0)};
  FluidBarrier<2> plate;
  plate.name = "plate";
  plate.axis = 1;
  plate.at = 0.03;
  plate.lo = {0.0, 0.03};
  plate.hi = {0.06, 0.03};
  f.barriers = {plate};
  std::vector<Wall<2>> walls{moving_box<2>(Vec<2>(0.01, 0.02), Vec<2>(0.03, 0.04), Vec<2>::Zero())};
  walls[0].motion = WallMotion::fixed;
  ParticleData<2> none;
  f.initialize(none, walls);
  for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
  ASSERT_EQ(f.barrier_faces(0), 6u);
  // The pressures to the solver's tolerance; the thrusts are sums of a few
  // of them times exact areas.
  const Vec<2> on_plate = f.barrier_thrust(0);
  EXPECT_NEAR(on_plate.y(), 3.0, 1e-9);
  EXPECT_EQ(on_plate.x(), 0.0);
  const Vec<2> on_box = f.wall_thrust(walls, 0);
  EXPECT_NEAR(on_box.y(), 1.0, 1e-9);
  EXPECT_NEAR(on_box.x(), 0.0, 1e-9);
}

// Impermeable walls (`impermeable = true` on a box with a thickness or a
// plane): they displace the fluid and close the faces they cover.

/// The 2D grid of 6 x 6 cells of 1 cm, drained at 50 Pa below and 0 above,
/// with `walls` fixed and impermeable (walls[0] unless `impermeable` is
/// false), stepped to the steady state (as steady_column).
PoreFluid<2> drained_square(std::vector<Wall<2>>& walls, bool impermeable = true) {
  PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
  f.sides[2] = {FluidBoundaryType::drained, TimeSeries::constant(50.0)};
  for (auto& w : walls) w.motion = WallMotion::fixed;
  if (!walls.empty() && impermeable) f.impermeable_walls = {0};
  ParticleData<2> none;
  f.initialize(none, walls);
  for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
  return f;
}

TEST(ImpermeableWalls, APlatenSealsTheColumnAndHoldsTheInletPressure3D) {
  // The 4 x 4 x 8 grid drained at 8 Pa below and 0 above, an impermeable
  // plane facing down at z = 0.055: it closes the faces above it (and the
  // drained top), so no water flows and the excess pressure is 8 Pa
  // everywhere below it; the platen takes 8 Pa over A = 1.6e-3 m^2,
  // pushing it up. A permeable platen lets the flow through: u = 2.5 Pa at
  // its face.
  const double a = 0.04 * 0.04;
  for (const bool impermeable : {true, false}) {
    PoreFluid<3> f = empty_grid<3>(0.01, {4, 4, 8});
    f.sides[4] = {FluidBoundaryType::drained, TimeSeries::constant(8.0)};
    if (impermeable) f.impermeable_walls = {0};
    std::vector<Wall<3>> walls{
        moving_plane<3>(Vec<3>(0.0, 0.0, 0.055), Vec<3>(0.0, 0.0, -1.0), Vec<3>::Zero())};
    walls[0].motion = WallMotion::fixed;
    ParticleData<3> none;
    f.initialize(none, walls);
    for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
    const double expected = impermeable ? 8.0 : 2.5;
    // The pressures to the solver's tolerance (1e-13), the areas exact.
    EXPECT_NEAR(f.wall_thrust(walls, 0).z(), expected * a, 1e-9 * expected * a) << impermeable;
    if (!impermeable) continue;
    for (int k = 0; k <= 5; ++k)
      EXPECT_NEAR(f.pressure()[f.grid.index({1, 2, k})], 8.0, 1e-9) << "layer " << k;
    // Closed: nothing through the top, to round-off through the bottom.
    EXPECT_EQ(f.side_inflow(5), 0.0);
    EXPECT_LT(std::abs(f.side_inflow(4)), 1e-20);
  }
}

TEST(ImpermeableWalls, ABoxAcrossTheFlowHoldsThePressureDifference2D) {
  // An impermeable box over the whole width of drained_square, y in
  // [0.025, 0.035], off the faces: it covers the faces at y = 0.03, so it
  // stops the flow as an impermeable plate there would: 50 Pa below, 0
  // above; its lower face takes 50 Pa over 6 cm, its upper one nothing:
  // 3 N/m upwards (as APlateAcrossTheFlowHoldsThePressureDifference2D).
  std::vector<Wall<2>> walls{moving_box<2>(Vec<2>(-0.01, 0.025), Vec<2>(0.07, 0.035), Vec<2>::Zero())};
  const PoreFluid<2> f = drained_square(walls);
  EXPECT_NEAR(f.pressure()[f.grid.index({3, 2})], 50.0, 1e-9);
  EXPECT_NEAR(f.pressure()[f.grid.index({3, 3})], 0.0, 1e-9);
  const Vec<2> thrust = f.wall_thrust(walls, 0);
  EXPECT_NEAR(thrust.y(), 3.0, 1e-9);
  EXPECT_NEAR(thrust.x(), 0.0, 1e-9);
  // Permeable, the same box lets the flow through (constant k): the
  // pressure falls across it.
  const PoreFluid<2> g = drained_square(walls, false);
  EXPECT_GT(g.pressure()[g.grid.index({3, 3})], 10.0);
}

TEST(ImpermeableWalls, ALidOverAChannelPassesFlowBelowItOnlyAndFeelsThePressureAlongIt2D) {
  // A 2D grid of 1 cm cells, 6 x 6, drained at 60 Pa on the left and 0 on
  // the right (k = 1e-10 m^2, mu = 1e-3 Pa s), with an impermeable box
  // over y in [0.035, 0.08]: the water flows along x below it only, in a
  // channel 0.035 m high (the layer it cuts in half passes half its
  // faces' area), with u = 60 (0.06 - x) / 0.06 Pa: q = (k / mu) 1000 Pa/m
  // = 1e-4 m/s, 3.5e-6 m^2/s in and out. On the lid's lower face the
  // pressure is linear along it, so the cells' values (at their centres)
  // give its integral exactly: 30 Pa x 0.06 m = 1.8 N/m upwards.
  PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
  f.sides[3] = {};
  f.sides[0] = {FluidBoundaryType::drained, TimeSeries::constant(60.0)};
  f.sides[1] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.impermeable_walls = {0};
  std::vector<Wall<2>> walls{moving_box<2>(Vec<2>(0.0, 0.035), Vec<2>(0.06, 0.08), Vec<2>::Zero())};
  walls[0].motion = WallMotion::fixed;
  ParticleData<2> none;
  f.initialize(none, walls);
  for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
  // The flows: exact areas times a gradient to the solver's tolerance.
  EXPECT_NEAR(f.side_inflow(0), 3.5e-6, 1e-9 * 3.5e-6);
  EXPECT_NEAR(f.side_inflow(1), -3.5e-6, 1e-9 * 3.5e-6);
  for (int j = 0; j <= 3; ++j) EXPECT_NEAR(f.pressure()[f.grid.index({1, j})], 45.0, 1e-9) << "row " << j;
  const Vec<2> thrust = f.wall_thrust(walls, 0);
  EXPECT_NEAR(thrust.y(), 1.8, 1e-9);
  EXPECT_EQ(thrust.x(), 0.0);  // its ends lie on the grid's sides: no water beyond them
}

TEST(ImpermeableWalls, ALidOverAGridPeriodicAcrossItSealsItAsOverAClosedOne2D) {
  // drained_square periodic along x, under an impermeable plane facing
  // down at y = 0.035 (its solid spans the period and beyond): no water
  // flows, 50 Pa below it, and it takes 50 Pa over the period's 6 cm,
  // 3 N/m, as over the grid closed at its ends.
  for (const bool periodic : {true, false}) {
    PoreFluid<2> f = empty_grid<2>(0.01, {6, 6});
    f.grid.periodic = {periodic, false};
    f.sides[2] = {FluidBoundaryType::drained, TimeSeries::constant(50.0)};
    f.impermeable_walls = {0};
    std::vector<Wall<2>> walls{moving_plane<2>(Vec<2>(0.0, 0.035), Vec<2>(0.0, -1.0), Vec<2>::Zero())};
    walls[0].motion = WallMotion::fixed;
    ParticleData<2> none;
    f.initialize(none, walls);
    for (int s = 1; s <= 3; ++s) f.update(none, 1.0, s, walls);
    EXPECT_NEAR(f.wall_thrust(walls, 0).y(), 3.0, 1e-9) << periodic;
    EXPECT_EQ(f.side_inflow(3), 0.0) << periodic;
    for (int i = 0; i < 6; ++i) EXPECT_NEAR(f.pressure()[f.grid.index({i, 3})], 50.0, 1e-9) << periodic;
  }
}

TEST(ImpermeableWalls, ABlockOnTheFacesIsFourBarriersAroundItsCells2D) {
  // An impermeable box filling the cells x in [0.01, 0.03], y in [0.02,
  // 0.04] of drained_square: the flow goes round it. Its faces lie on the
  // grid's, so the water outside it must see what barriers on those four
  // sides give (an independent path: FluidBarrier, checked against Harr's
  // sheet pile), cell by cell to the solver's tolerance.
  std::vector<Wall<2>> walls{moving_box<2>(Vec<2>(0.01, 0.02), Vec<2>(0.03, 0.04), Vec<2>::Zero())};
  const PoreFluid<2> f = drained_square(walls);
  std::vector<Wall<2>> none;
  PoreFluid<2> b = empty_grid<2>(0.01, {6, 6});
  b.sides[2] = {FluidBoundaryType::drained, TimeSeries::constant(50.0)};
  b.solid_walls.clear();
  auto barrier = [](int axis, double at, Vec<2> lo, Vec<2> hi) {
    FluidBarrier<2> fb;
    fb.name = "side";
    fb.axis = axis;
    fb.at = at;
    fb.lo = {lo.x(), lo.y()};
    fb.hi = {hi.x(), hi.y()};
    return fb;
  };
  b.barriers = {barrier(1, 0.02, {0.01, 0.02}, {0.03, 0.02}), barrier(1, 0.04, {0.01, 0.04}, {0.03, 0.04}),
                barrier(0, 0.01, {0.01, 0.02}, {0.01, 0.04}), barrier(0, 0.03, {0.03, 0.02}, {0.03, 0.04})};
  ParticleData<2> grains;
  b.initialize(grains, none);
  for (int s = 1; s <= 3; ++s) b.update(grains, 1.0, s, none);
  int compared = 0;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) {
      if (i >= 1 && i < 3 && j >= 2 && j < 4) continue;  // inside the block: cut off
      const std::size_t c = f.grid.index({i, j});
      EXPECT_NEAR(f.pressure()[c], b.pressure()[c], 1e-9) << i << ", " << j;
      ++compared;
    }
  }
  EXPECT_EQ(compared, 32);
  // It does go round: the cells beside the block differ from the straight
  // drop 50 (0.06 - y) / 0.06.
  EXPECT_GT(std::abs(f.pressure()[f.grid.index({0, 2})] - 50.0 * (0.06 - 0.025) / 0.06), 0.1);
  // And the flows through the drained sides, the same to the tolerance.
  for (int side : {2, 3})
    EXPECT_NEAR(f.side_inflow(side), b.side_inflow(side), 1e-9 * std::abs(b.side_inflow(2)));
}

TEST(ImpermeableWalls, APlatenMovingDownOrUpPassesItsVolumeThroughTheFloorOnly3D) {
  // APlatenPushedDownExpelsItsAreaTimesItsSpeed3D with the top drained
  // too: the impermeable platen covers the top, so all the water it
  // expels leaves through the floor, none through the top; drawn back up,
  // it draws the water in through the floor. It crosses the faces at 0.07
  // and 0.06 in mid-step (from 0.0752 to 0.0552 m) and lands on them (from
  // 0.075): each step's water passes the face the platen crosses then (a
  // face closes once it was covered at the last step too).
  const double v = 1e-3;
  const double a = 0.04 * 0.04;
  for (const double start : {0.0752, 0.075}) {
    for (const double sense : {-1.0, 1.0}) {
      PoreFluid<3> f = empty_grid<3>(0.01, {4, 4, 8});
      f.sides[4] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
      f.impermeable_walls = {0};
      const double z0 = sense < 0.0 ? start : start - 0.02;
      const Wall<3> platen =
          moving_plane<3>(Vec<3>(0.01, 0.02, z0), Vec<3>(0.0, 0.0, -1.0), Vec<3>(0.0, 0.0, sense * v));
      push_rod<3>(f, platen, -sense * a * v, 0.5, 40, 4,
                  [](double z) { return face_below_top(z, 0.08, 0.01); });
      EXPECT_EQ(f.side_inflow(5), 0.0) << start << " " << sense;
    }
  }
}

}  // namespace
