// Where a particle's centre stands against a wall (Wall::touch): planes as
// before, and box walls touched on a face, an edge or a corner, from either
// side, and from inside; cylinders from inside and outside; each case
// against the nearest point worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "darcydem/walls/loaded_area.hpp"
#include "darcydem/walls/wall.hpp"

namespace darcydem {
namespace {

template <int D>
Wall<D> box(const Vec<D>& lo, const Vec<D>& hi) {
  Wall<D> w;
  w.shape = WallShape::box;
  w.point = 0.5 * (lo + hi);
  w.half = 0.5 * (hi - lo);
  return w;
}

// Round-off of a few operations on numbers of order 1.
constexpr double kTol = 1e-14;

void expect_touch(const Wall<3>::Touch& t, double gap, const Vec<3>& normal) {
  EXPECT_NEAR(t.gap, gap, kTol);
  EXPECT_NEAR((t.normal - normal).norm(), 0.0, kTol) << t.normal.transpose();
}

TEST(WallTouch, PlaneGivesTheSignedDistanceAndItsNormal) {
  Wall<3> w;
  w.point = Vec<3>(1, 2, 3);
  w.normal = Vec<3>(0, 0.6, 0.8);
  expect_touch(w.touch(Vec<3>(5, 2, 4)), 0.8, w.normal);
  expect_touch(w.touch(Vec<3>(5, 2, 2)), -0.8, w.normal);  // behind: pushed back out
}

TEST(WallTouch, PlateIsTouchedOnBothFacesOnItsEdgesAndCorners) {
  // A plate 2 x 4 in the plane z = 0, centred at the origin.
  const auto w = box<3>(Vec<3>(-1, -2, 0), Vec<3>(1, 2, 0));
  expect_touch(w.touch(Vec<3>(0.5, 1, 3)), 3.0, Vec<3>(0, 0, 1));    // above a face
  expect_touch(w.touch(Vec<3>(0.5, 1, -3)), 3.0, Vec<3>(0, 0, -1));  // below it
  // Beyond the edge x = 1: nearest point (1, 1, 0), offset (3, 0, 4).
  expect_touch(w.touch(Vec<3>(4, 1, 4)), 5.0, Vec<3>(0.6, 0, 0.8));
  // Beyond the corner (1, 2, 0): offset (1, 2, 2), length 3.
  expect_touch(w.touch(Vec<3>(2, 4, 2)), 3.0, Vec<3>(1, 2, 2) / 3.0);
  // In the plate's own plane, beyond its edge y = -2.
  expect_touch(w.touch(Vec<3>(0, -2.5, 0)), 0.5, Vec<3>(0, -1, 0));
}

TEST(WallTouch, InsideABoxTheNearestFaceWins) {
  const auto w = box<3>(Vec<3>(-1, -2, -3), Vec<3>(1, 2, 3));
  expect_touch(w.touch(Vec<3>(0.9, 0, 0)), -0.1, Vec<3>(1, 0, 0));
  expect_touch(w.touch(Vec<3>(-0.2, 1.9, 0)), -0.1, Vec<3>(0, 1, 0));
  expect_touch(w.touch(Vec<3>(0, 0, -2.5)), -0.5, Vec<3>(0, 0, -1));
}

TEST(WallTouch, SegmentIn2D) {
  // A vertical segment x = 0, y in [0, 1] (a sheet pile in 2D).
  const auto w = box<2>(Vec<2>(0, 0), Vec<2>(0, 1));
  auto t = w.touch(Vec<2>(0.3, 1.4));  // beyond its top end: offset (0.3, 0.4)
  EXPECT_NEAR(t.gap, 0.5, kTol);
  EXPECT_NEAR((t.normal - Vec<2>(0.6, 0.8)).norm(), 0.0, kTol);
  t = w.touch(Vec<2>(-0.25, 0.5));  // beside it, upstream
  EXPECT_NEAR(t.gap, 0.25, kTol);
  EXPECT_NEAR((t.normal - Vec<2>(-1, 0)).norm(), 0.0, kTol);
}

TEST(WallTouch, RotatedBoxesUseTheirOwnAxes) {
  // A 2D segment of half-length 1 along its own x, turned by 30 degrees:
  // its end is at (cos 30, sin 30).
  auto seg = box<2>(Vec<2>(-1, 0), Vec<2>(1, 0));
  const double c = std::sqrt(3.0) / 2.0;
  seg.axes << c, -0.5, 0.5, c;
  auto t = seg.touch(Vec<2>(2.0 * c, 1.0));  // beyond the end, along the segment
  EXPECT_NEAR(t.gap, 1.0, kTol);
  EXPECT_NEAR((t.normal - Vec<2>(c, 0.5)).norm(), 0.0, kTol);
  t = seg.touch(Vec<2>(-0.25, 0.5 * c));  // half a unit off its middle, across it
  EXPECT_NEAR(t.gap, 0.5, kTol);
  EXPECT_NEAR((t.normal - Vec<2>(-0.5, c)).norm(), 0.0, kTol);
  // A 3D plate 2 x 4 turned by 90 degrees about z: it spans y in [-1, 1]
  // and x in [-2, 2] at z = 0.
  auto plate = box<3>(Vec<3>(-1, -2, 0), Vec<3>(1, 2, 0));
  plate.axes << 0, -1, 0, 1, 0, 0, 0, 0, 1;
  expect_touch(plate.touch(Vec<3>(1.5, 0.5, 1)), 1.0, Vec<3>(0, 0, 1));  // over it
  expect_touch(plate.touch(Vec<3>(0, 4, 0)), 3.0, Vec<3>(0, 1, 0));      // beyond its edge y = 1
  expect_touch(plate.touch(Vec<3>(5, 1, 4)), 5.0, Vec<3>(0.6, 0, 0.8));  // beyond its edge x = 2
}

TEST(WallTouch, ABoxThatMovesSidewaysHasMovedAPlaneDoesNot) {
  auto plate = box<3>(Vec<3>(0, 0, 0), Vec<3>(1, 1, 0));
  plate.point_at_build = plate.point;
  plate.point += Vec<3>(0.3, 0.4, 0);
  EXPECT_NEAR(plate.moved_since_build(), 0.5, kTol);
  Wall<3> floor;
  floor.normal = Vec<3>(0, 0, 1);
  floor.point = Vec<3>(0.3, 0.4, 0.1);
  EXPECT_NEAR(floor.moved_since_build(), 0.1, kTol);
}

template <int D>
Wall<D> cylinder(const Vec<D>& centre, double radius, const Vec<D>& axis, bool from_inside) {
  Wall<D> w;
  w.shape = WallShape::cylinder;
  w.point = centre;
  w.radius = radius;
  w.axis = axis;
  w.from_inside = from_inside;
  return w;
}

TEST(WallTouch, ACylinderIsTouchedAcrossItsAxisFromTheSideItFaces) {
  // Radius 5 about the axis (0, 0.6, 0.8) through (1, 1, 1). A point at
  // (4, 1, 1) + 7 (0, 0.6, 0.8) is 3 from the axis along x: 2 inside the
  // wall, its normal (from the wall towards the point) -x.
  const Vec<3> axis(0, 0.6, 0.8);
  const auto drum = cylinder<3>(Vec<3>(1, 1, 1), 5.0, axis, true);
  expect_touch(drum.touch(Vec<3>(4, 1, 1) + 7.0 * axis), 2.0, Vec<3>(-1, 0, 0));
  // Across the axis along (0, 0.8, -0.6), 6 from it: outside, pushed back in.
  const Vec<3> across(0, 0.8, -0.6);
  expect_touch(drum.touch(Vec<3>(1, 1, 1) + 6.0 * across - 2.0 * axis), -1.0, -across);
  // Touched from outside (a pile): the same points, gaps of the other sign.
  const auto pile = cylinder<3>(Vec<3>(1, 1, 1), 5.0, axis, false);
  expect_touch(pile.touch(Vec<3>(4, 1, 1) + 7.0 * axis), -2.0, Vec<3>(1, 0, 0));
  expect_touch(pile.touch(Vec<3>(1, 1, 1) + 6.0 * across), 1.0, across);
  // On the axis: the gap is the radius, the normal some unit across it.
  const auto on_axis = drum.touch(Vec<3>(1, 1, 1) + 3.0 * axis);
  EXPECT_NEAR(on_axis.gap, 5.0, kTol);
  EXPECT_NEAR(on_axis.normal.norm(), 1.0, kTol);
  EXPECT_NEAR(on_axis.normal.dot(axis), 0.0, kTol);
  // Moving along its axis it has not moved towards any particle.
  auto moved = drum;
  moved.mark_build();
  moved.point += 2.0 * axis + Vec<3>(0.3, 0.4 * 0.8, -0.4 * 0.6);
  EXPECT_NEAR(moved.moved_since_build(), 0.5, kTol);
  // A change of radius moves its surface by as much, added to the shift.
  moved.radius -= 0.25;
  EXPECT_NEAR(moved.moved_since_build(), 0.75, kTol);
}

// A cylinder's servo changes its radius, not its place: touched from
// inside it shrinks while the load is short of the target, from outside
// it grows, at gain x the shortfall (clamped at max_speed).
TEST(WallTouch, ACylindersServoChangesItsRadiusTowardsTheGrains) {
  for (const bool inside : {true, false}) {
    auto w = cylinder<3>(Vec<3>(1, 1, 1), 5.0, Vec<3>(0, 0, 1), inside);
    w.motion = WallMotion::servo;
    w.servo.target_force = 10.0;
    w.servo.gain = 0.01;
    w.servo.max_speed = 1.0;
    w.radial_load = 4.0;
    w.advance(0.5, 0.0);  // speed 0.06 m/s for 0.5 s
    EXPECT_NEAR(w.radius, inside ? 4.97 : 5.03, kTol);
    EXPECT_NEAR((w.point - Vec<3>(1, 1, 1)).norm(), 0.0, kTol);
    EXPECT_NEAR(w.radial_speed, inside ? -0.06 : 0.06, kTol);
    // Its surface at (1, 1, 1) + 5 x, anywhere along the axis, moves
    // along the radius.
    EXPECT_NEAR((w.surface_velocity(Vec<3>(6, 1, 7)) - Vec<3>(w.radial_speed, 0, 0)).norm(), 0.0, kTol);
    w.radial_load = 10.0 + 1e4;  // far over: at max_speed the other way
    w.advance(0.5, 0.5);
    EXPECT_NEAR(w.radial_speed, inside ? 1.0 : -1.0, kTol);
  }
}

TEST(WallTouch, A2DCylinderIsACircle) {
  // Radius 2 about (1, -1): (1, -1) + (0.6, 0.8) is 1 from the centre.
  const auto drum = cylinder<2>(Vec<2>(1, -1), 2.0, Vec<2>::Zero(), true);
  const auto t = drum.touch(Vec<2>(1.6, -0.2));
  EXPECT_NEAR(t.gap, 1.0, kTol);
  EXPECT_NEAR((t.normal - Vec<2>(-0.6, -0.8)).norm(), 0.0, kTol);
  const auto ring = cylinder<2>(Vec<2>(1, -1), 2.0, Vec<2>::Zero(), false);
  const auto u = ring.touch(Vec<2>(1, -4));
  EXPECT_NEAR(u.gap, 1.0, kTol);
  EXPECT_NEAR((u.normal - Vec<2>(0, -1)).norm(), 0.0, kTol);
}

}  // namespace
}  // namespace darcydem

namespace darcydem {
namespace {

Wall<3> plane3(const Vec<3>& point, const Vec<3>& normal) {
  Wall<3> w;
  w.point = point;
  w.normal = normal;
  return w;
}

// The loaded area of a plane (walls/loaded_area.hpp), by hand: a box of
// planes 2 x 3 (x, y) under a lid normal to z; the same with y periodic
// over 5; in a cylinder of radius 2 along z; and the walls crossed.
// A box turned step by step about a pivot is the box placed turned: its
// axes are the rotation's, its centre has gone round the pivot; the
// surface's velocity is omega x (x - pivot) plus the translation; and the
// contact list's bound on its move covers every point of it.
TEST(WallTouch, ABoxThatTurnsIsTheBoxPlacedTurned) {
  const double omega = 0.7;
  const double dt = 1e-3;
  const int steps = 1000;
  const double angle = omega * dt * steps;
  const Vec<3> axis = Vec<3>(1.0, 2.0, 2.0) / 3.0;
  Wall<3> w = box<3>(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.4, 0.2, 0.1));
  w.pivot = Vec<3>(-0.1, 0.05, 0.0);
  w.axis = axis;
  w.spin = omega;
  w.velocity = Vec<3>(0.01, 0.0, -0.02);
  w.motion = WallMotion::velocity;
  const Vec<3> centre0 = w.point;
  const Vec<3> pivot0 = w.pivot;
  // Sample points round the box, in its own axes at the start.
  std::vector<Vec<3>> local;
  for (double a : {-0.3, 0.0, 0.25})
    for (double b : {-0.2, 0.03, 0.15})
      for (double c : {-0.12, 0.0, 0.09}) local.emplace_back(a, b, c);
  std::vector<double> gap0;
  for (const auto& d : local) gap0.push_back(w.gap(centre0 + d));
  w.mark_build();
  double max_move = 0.0;
  for (int s = 0; s < steps; ++s) {
    w.advance(dt, s * dt);
    // Every point the particles may touch has moved no more than the bound.
    for (const auto& d : local) {
      const Vec<3> x = centre0 + d;
      max_move = std::max(max_move, std::abs(w.gap(x) - gap0[&d - local.data()]));
      EXPECT_LE(std::abs(w.gap(x) - gap0[&d - local.data()]), w.moved_since_build() + 1e-15);
    }
  }
  EXPECT_GT(max_move, 0.05);  // it did sweep through the points
  // Placed: turned by the angle about the axis through the pivot, which
  // has moved with the wall's velocity; the axes orthonormal.
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  const Vec<3> pivot = pivot0 + w.velocity * dt * steps;
  EXPECT_NEAR((w.pivot - pivot).norm(), 0.0, 1e-13);  // 1000 additions
  const Vec<3> centre = pivot + r * (centre0 - pivot0);
  EXPECT_NEAR((w.point - centre).norm(), 0.0, 1e-13);
  EXPECT_NEAR((w.axes - r).norm(), 0.0, 1e-13);
  EXPECT_NEAR((w.axes.transpose() * w.axes - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-15);
  Wall<3> placed = box<3>(centre - w.half, centre + w.half);
  placed.axes = r;
  for (const auto& d : local) {
    const Vec<3> x = centre + r * d;
    EXPECT_NEAR(w.gap(x), placed.gap(x), 1e-13);
    EXPECT_NEAR(w.gap(x), gap0[&d - local.data()], 1e-13);  // it carried the points with it
  }
  const Vec<3> c(0.3, -0.2, 0.4);
  EXPECT_NEAR((w.surface_velocity(c) - (w.velocity + omega * axis.cross(c - w.pivot))).norm(), 0.0, 1e-16);
  EXPECT_NEAR((w.angular_velocity() - omega * axis).norm(), 0.0, 1e-16);
}

// A 2D plane (a line) turned counter-clockwise about a pivot: its normal is
// the rotation's, its point stays on it; its bound on the move is the
// angle times the reach its last build measured, and before a build that
// saw it turn, the bound is infinite (rebuild at once).
TEST(WallTouch, APlaneThatTurnsSweepsByItsReach) {
  Wall<2> w;
  w.point = Vec<2>(0.3, 0.0);
  w.normal = Vec<2>(0.0, 1.0);
  w.pivot = Vec<2>(0.1, 0.0);
  w.reach = std::numeric_limits<double>::infinity();
  w.spin = -0.5;
  w.advance(1e-3, 0.0);
  EXPECT_TRUE(std::isinf(w.moved_since_build()));
  w.mark_build();
  w.reach = 2.0;  // as WallContactList::build measures it: farthest centre + skin
  for (int s = 0; s < 999; ++s) w.advance(1e-3, (s + 1) * 1e-3);
  const double angle = -0.5;
  EXPECT_NEAR((w.normal - Vec<2>(-std::sin(angle), std::cos(angle))).norm(), 0.0, 1e-14);
  EXPECT_NEAR((w.point - w.pivot).dot(w.normal), 0.0, 1e-15);
  EXPECT_NEAR(w.moved_since_build(), 0.5 * 0.999 * 2.0, 1e-13);
  // 2D: counter-clockwise, omega x arm = omega (-arm_y, arm_x).
  EXPECT_NEAR((w.surface_velocity(Vec<2>(0.1, 1.0)) - Vec<2>(0.5, 0.0)).norm(), 0.0, 1e-16);
  // Its moment about the pivot: a force (0, 1) at (1.1, 0) turns it
  // counter-clockwise by 1 N m, and a couple adds.
  EXPECT_NEAR(w.moment_about_axis(Vec<2>(1.1, 0.0), Vec<2>(0.0, 1.0), AngVec<2>(0.25)), 1.25, 1e-15);
}

TEST(LoadedArea, IsTheCrossSectionTheOtherWallsBound) {
  std::vector<Wall<3>> walls = {
      plane3(Vec<3>(0, 0, 4), Vec<3>(0, 0, -1)),  // the lid
      plane3(Vec<3>(-1, 0, 0), Vec<3>(1, 0, 0)), plane3(Vec<3>(1, 0, 0), Vec<3>(-1, 0, 0)),
      plane3(Vec<3>(0, -1, 0), Vec<3>(0, 1, 0)), plane3(Vec<3>(0, 2, 0), Vec<3>(0, -1, 0))};
  PeriodicCell<3> none;
  EXPECT_DOUBLE_EQ(loaded_area(walls, 0, none).area, 6.0);
  // A side wall's area: the lid and an absent floor leave z unbounded.
  EXPECT_NE(
      loaded_area(walls, 1, none).why_not.find("along z needs one plane wall facing +z and one facing -z"),
      std::string::npos);
  walls.push_back(plane3(Vec<3>(0, 0, 0), Vec<3>(0, 0, 1)));  // the floor
  EXPECT_DOUBLE_EQ(loaded_area(walls, 1, none).area, 3.0 * 4.0);
  EXPECT_DOUBLE_EQ(loaded_area(walls, 3, none).area, 2.0 * 4.0);
  // Periodic along y: the period, not the walls (there are none along y).
  std::vector<Wall<3>> periodic_walls = {walls[0], walls[1], walls[2]};
  PeriodicCell<3> cell;
  cell.set_axis(1, -2.0, 3.0);
  EXPECT_DOUBLE_EQ(loaded_area(periodic_walls, 0, cell).area, 2.0 * 5.0);
  // A triaxial cell: a cylinder along z, touched from inside.
  Wall<3> cylinder;
  cylinder.shape = WallShape::cylinder;
  cylinder.axis = Vec<3>(0, 0, 1);
  cylinder.radius = 2.0;
  std::vector<Wall<3>> cell_walls = {walls[0], cylinder};
  EXPECT_DOUBLE_EQ(loaded_area(cell_walls, 0, none).area, std::numbers::pi * 4.0);
  // The cylinder's own: its lateral surface, 2 pi R times the height the
  // lid and a floor bound (4), or the period along its axis (3).
  EXPECT_NE(loaded_area(cell_walls, 1, none).why_not.find("its height is not bounded"), std::string::npos);
  cell_walls.push_back(walls[5]);  // the floor
  EXPECT_DOUBLE_EQ(loaded_area(cell_walls, 1, none).area, 2.0 * std::numbers::pi * 2.0 * 4.0);
  PeriodicCell<3> along_z;
  along_z.set_axis(2, 1.0, 4.0);
  EXPECT_DOUBLE_EQ(loaded_area(std::vector<Wall<3>>{cylinder}, 0, along_z).area,
                   2.0 * std::numbers::pi * 2.0 * 3.0);
  cylinder.axis = Vec<3>(0.6, 0.8, 0.0);
  EXPECT_NE(loaded_area(std::vector<Wall<3>>{cylinder}, 0, along_z).why_not.find("not along x, y or z"),
            std::string::npos);
  // Crossed: the +x wall moved past the -x one.
  walls[2].point.x() = -1.5;
  EXPECT_NE(loaded_area(walls, 0, none).why_not.find("have crossed"), std::string::npos);
  // A box has none.
  EXPECT_NE(loaded_area(std::vector<Wall<3>>{box<3>(Vec<3>(0, 0, 0), Vec<3>(1, 1, 1))}, 0, none).why_not, "");
}

}  // namespace
}  // namespace darcydem
