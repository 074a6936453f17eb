// Box walls (plates, segments, boxes) against what the mechanics says
// without the code: a grain hitting a plate's corner feels a central force
// from that corner, so its angular momentum about it is conserved and,
// frictionless and elastic, its speed too; in the stiff limit it leaves as
// a hard ball reflected about the normal at first touch. A grain resting on
// a plate loads it with its weight; one whose centre is beyond the edge
// rolls off. A plate moving into a free grain sends it off at twice its
// speed (an elastic bounce in the plate's frame).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dem_setup.hpp"

namespace darcydem {
namespace {

using darcydem::testing::single_material;

template <int D>
Wall<D> box_wall(const Vec<D>& lo, const Vec<D>& hi, const char* name = "plate") {
  Wall<D> w;
  w.name = name;
  w.shape = WallShape::box;
  w.point = 0.5 * (lo + hi);
  w.half = 0.5 * (hi - lo);
  return w;
}

/// Angular momentum per unit mass about c: a number in 2D, a vector in 3D.
double moment(const Vec<2>& x, const Vec<2>& v) { return x.x() * v.y() - x.y() * v.x(); }
Vec<3> moment(const Vec<3>& x, const Vec<3>& v) {
  return {x.y() * v.z() - x.z() * v.y(), x.z() * v.x() - x.x() * v.z(), x.x() * v.y() - x.y() * v.x()};
}
double size_of(double m) { return std::abs(m); }
double size_of(const Vec<3>& m) { return m.norm(); }

// A grain falls onto the corner of a plate (in 2D, the end of a segment):
// the plate covers x_k <= 0 for k < D-1 on the plane x_{D-1} = 0 (2L
// wide), and the grain (r = 1 mm) comes down at 0.1 m/s from 0.02 r above
// the plate's plane, at an impact parameter b = r/2 from the corner, along
// the plate's diagonal in 3D; frictionless and elastic. The whole set-up
// is turned by `turn` about the corner (the plate a rotated box). Prepared.
template <int D>
Simulation<D> grain_over_corner(const Eigen::Matrix<double, D, D>& turn) {
  const double r = 1e-3;
  const double v = 0.1;
  const double m = 2500.0 * particle_volume<D>(r);
  ContactSpec spec;
  // The largest overlap, were the whole speed normal, is 1e-3 r: the
  // stiff limit within about that fraction.
  const double max_overlap = 1e-3 * r;
  spec.normal_stiffness = m * v * v / (max_overlap * max_overlap);
  spec.restitution = 1.0;
  spec.friction = 0.0;
  auto sim = single_material<D>(2500.0, spec);
  Vec<D> lo = Vec<D>::Constant(-2.0 * r);
  Vec<D> hi = Vec<D>::Zero();
  lo[D - 1] = 0.0;
  auto plate = box_wall<D>(lo, hi);
  plate.point = turn * plate.point;
  plate.axes = turn;
  sim.walls.push_back(plate);
  Vec<D> x = Vec<D>::Constant(0.5 * r / std::sqrt(D - 1.0));
  x[D - 1] = 1.02 * r;
  Vec<D> v0 = Vec<D>::Zero();
  v0[D - 1] = -v;
  sim.particles.add(turn * x, r, 2500.0, 0, false, turn * v0);
  sim.time_step = 0.01 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  return sim;
}

template <int D>
void corner_scattering() {
  const double r = 1e-3;
  const double v = 0.1;
  const double b = 0.5 * r;
  auto sim = grain_over_corner<D>(Eigen::Matrix<double, D, D>::Identity());
  const auto l0 = moment(sim.particles.position[0], sim.particles.velocity[0]);
  const Vec<D> v0 = sim.particles.velocity[0];
  // Down to the corner (0.02 r at v), then until the grain is as high again
  // as it started (the contact over): about 4000 steps.
  while (sim.time < 0.02 * r / v) sim.step();
  for (int s = 0; s < 2'000'000 && sim.particles.position[0][D - 1] < 1.02 * r; ++s) sim.step();
  ASSERT_GE(sim.particles.position[0][D - 1], 1.02 * r) << "the grain did not come back up";
  const Vec<D> x1 = sim.particles.position[0];
  const Vec<D> v1 = sim.particles.velocity[0];
  // Central force about the corner: each kick adds a velocity parallel to
  // x and each drift moves x along v, so x cross v is kept to round-off:
  // the drift's rounding of x (|x| about 2 b) moves it by up to about
  // 2.5e-16 L per step, 1e-12 over the 4000 steps (measured 1.3e-12 in 3D, 2.5e-12 in 2D).
  EXPECT_LT(size_of(moment(x1, v1) - l0), 1e-11 * size_of(l0));
  // No damping, no friction: the speed comes back, up to the leapfrog's
  // error on a linear spring switched on between steps, of order
  // (omega dt)^2 = 1e-4 (measured 7e-8: it mostly cancels on and off).
  EXPECT_NEAR(v1.norm(), v, 1e-4 * v);
  // Hard-ball reflection about n = (x - corner)/r at first touch, when the
  // centre is at height sqrt(r^2 - b^2) above the corner.
  Vec<D> n = Vec<D>::Constant(b / std::sqrt(D - 1.0) / r);
  n[D - 1] = std::sqrt(r * r - b * b) / r;
  const Vec<D> hard = v0 - 2.0 * v0.dot(n) * n;
  // Soft contact: the grain turns about a point up to max_overlap closer,
  // which shifts the angle by about 2 max_overlap / (r cos) = 2.3e-3 rad.
  const double angle = std::acos(std::clamp(v1.normalized().dot(hard.normalized()), -1.0, 1.0));
  EXPECT_LT(angle, 5e-3) << "left along " << v1.transpose() << ", hard ball " << hard.transpose();
  // It really was deflected sideways (a plane would have sent it straight
  // back up): 60 degrees from the vertical for b = r/2.
  EXPECT_GT(v1[0], 0.4 * v);
}

TEST(BoxWall, CornerScattersADiscLikeAHardDisc) { corner_scattering<2>(); }
TEST(BoxWall, CornerScattersASphereLikeAHardSphere) { corner_scattering<3>(); }

// The same corner turned as a whole (plate, grain and velocity) by a
// rotation R about the corner, the plate given as a rotated box: physics
// does not depend on the axes, so the grain leaves along R times the
// unturned run's velocity, to the round-off of the turned coordinates
// (some 1e-16 of r per step over the 40 000 steps, 4e-12, in a collision
// that does not amplify it; measured 2.4e-12 in 2D, 1.4e-12 in 3D).
template <int D>
Vec<D> corner_bounce(const Eigen::Matrix<double, D, D>& turn) {
  const double r = 1e-3;
  const double v = 0.1;
  auto sim = grain_over_corner<D>(turn);
  // Down 0.15 r to the touch (1.5e-3 s), the bounce (3e-5 s), away.
  while (sim.time < 0.4 * r / v) sim.step();
  return sim.particles.velocity[0];
}

TEST(BoxWall, ARotatedPlateBouncesAsTheUnturnedOne) {
  const double v = 0.1;
  const auto still2 = corner_bounce<2>(Eigen::Matrix2d::Identity());
  const double a = 0.5236;  // about 30 degrees
  Eigen::Matrix2d turn2;
  turn2 << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  const auto turned2 = corner_bounce<2>(turn2);
  EXPECT_GT(still2.x(), 0.4 * v);  // deflected by the corner, as above
  EXPECT_LT((turned2 - turn2 * still2).norm(), 1e-10 * v) << turned2.transpose();
  // 3D: 40 degrees about an oblique axis (Rodrigues' formula).
  const Vec<3> u = Vec<3>(1.0, 2.0, 2.0) / 3.0;
  const double b = 0.6981;
  Eigen::Matrix3d ux;
  ux << 0.0, -u.z(), u.y(), u.z(), 0.0, -u.x(), -u.y(), u.x(), 0.0;
  const Eigen::Matrix3d turn3 =
      std::cos(b) * Eigen::Matrix3d::Identity() + std::sin(b) * ux + (1.0 - std::cos(b)) * u * u.transpose();
  const auto still3 = corner_bounce<3>(Eigen::Matrix3d::Identity());
  const auto turned3 = corner_bounce<3>(turn3);
  EXPECT_GT(still3.x(), 0.2 * v);
  EXPECT_LT((turned3 - turn3 * still3).norm(), 1e-10 * v) << turned3.transpose();
}

// Two grains on a horizontal plate 4 r wide: one with its centre over the
// plate rests on it and loads it with its weight; one with its centre a
// quarter radius beyond the edge is pushed outwards by the edge, rolls off
// and falls past the plate.
template <int D>
void rest_and_roll_off() {
  const double r = 5e-4;
  const double g = 9.81;
  const double m = 2650.0 * particle_volume<D>(r);
  ContactSpec spec;
  spec.normal_stiffness = m * g / (1e-4 * r);
  spec.restitution = 0.5;
  spec.friction = 0.5;
  auto sim = single_material<D>(2650.0, spec);
  Vec<D> lo = Vec<D>::Constant(-2.0 * r);
  Vec<D> hi = Vec<D>::Constant(2.0 * r);
  lo[D - 1] = hi[D - 1] = 0.0;
  sim.walls.push_back(box_wall<D>(lo, hi, "resting"));
  // The second plate, far away along the last horizontal axis.
  const double shift = 100.0 * r;
  lo[0] += shift;
  hi[0] += shift;
  sim.walls.push_back(box_wall<D>(lo, hi, "edge"));
  Vec<D> on = Vec<D>::Zero();
  on[D - 1] = r;
  sim.particles.add(on, r, 2650.0, 0, false);
  Vec<D> beyond = on;
  beyond[0] = shift + 2.25 * r;  // the centre 0.25 r beyond the edge x = 2 r
  sim.particles.add(beyond, r, 2650.0, 0, false);
  sim.gravity[D - 1] = -g;
  sim.damping.local = 0.3;
  sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  while (sim.time < 0.1) sim.step();
  // At rest on the plate: its load is m g (damped to far below 1e-6 of it
  // after 0.1 s, some 5000 periods of the contact), straight down.
  EXPECT_NEAR(sim.walls[0].force[D - 1], -m * g, 1e-6 * m * g);
  EXPECT_NEAR(sim.particles.position[0][D - 1], r - m * g / spec.normal_stiffness, 1e-6 * r);
  // Rolled off: well below the plate and past its edge, no longer touching.
  EXPECT_LT(sim.particles.position[1][D - 1], -2.0 * r);
  EXPECT_GT(sim.particles.position[1][0], shift + 2.0 * r);
  EXPECT_EQ(sim.walls[1].force.norm(), 0.0);
}

TEST(BoxWall, PlateCarriesADiscAndItsEdgeLetsAnotherRollOff) { rest_and_roll_off<2>(); }
TEST(BoxWall, PlateCarriesASphereAndItsEdgeLetsAnotherRollOff) { rest_and_roll_off<3>(); }

// A grain on an inclined plate (a box turned by theta = 30 degrees about
// the out-of-plane axis, in 3D about y) under gravity. Classical
// mechanics: it rolls without slipping when mu >= tan(theta) / 3 (disc) or
// 2 tan(theta) / 7 (sphere), accelerating at 2/3 or 5/7 of g sin(theta);
// with less friction it slides and rolls at once, accelerating at
// g (sin(theta) - mu cos(theta)). Measured between 0.02 and 0.05 s (after
// the contact's start-up). Sliding, the tangential force is mu F_n
// exactly: 1e-9 (measured 1.4e-13). Rolling, the tangential spring
// oscillates about its mean: 1e-3 (measured 6.7e-5 in 2D, 5.7e-5 in 3D).
template <int D>
double incline_acceleration(double mu) {
  const double r = 1e-3;
  const double g = 9.81;
  const double theta = std::numbers::pi / 6.0;
  const double m = 2500.0 * particle_volume<D>(r);
  ContactSpec spec;
  spec.normal_stiffness = m * g * std::cos(theta) / (1e-4 * r);
  spec.restitution = 0.5;
  spec.friction = mu;
  auto sim = single_material<D>(2500.0, spec);
  // The plate 60 mm long down the slope, 20 mm wide, turned by -theta so
  // that its own first axis points down the slope.
  Vec<D> lo = Vec<D>::Constant(-0.01);
  Vec<D> hi = Vec<D>::Constant(0.01);
  lo[0] = -0.03;
  hi[0] = 0.03;
  lo[D - 1] = hi[D - 1] = 0.0;
  auto plate = box_wall<D>(lo, hi);
  Vec<D> down = Vec<D>::Zero();  // the plate's first axis: down the slope
  Vec<D> up = Vec<D>::Zero();    // its normal
  down[0] = std::cos(theta);
  down[D - 1] = -std::sin(theta);
  up[0] = std::sin(theta);
  up[D - 1] = std::cos(theta);
  plate.axes.setIdentity();
  plate.axes.col(0) = down;
  plate.axes.col(D - 1) = up;
  sim.walls.push_back(plate);
  // Resting on it 20 mm up the slope from its middle.
  const Vec<D> x = -0.02 * down + (r - m * g * std::cos(theta) / spec.normal_stiffness) * up;
  sim.particles.add(x, r, 2500.0, 0, false);
  sim.gravity[D - 1] = -g;
  sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  while (sim.time < 0.02) sim.step();
  const double t1 = sim.time;
  const double v1 = sim.particles.velocity[0].dot(down);
  while (sim.time < 0.05) sim.step();
  EXPECT_NEAR(sim.particles.velocity[0].dot(up), 0.0, 1e-6) << "left the plate";
  return (sim.particles.velocity[0].dot(down) - v1) / (sim.time - t1);
}

TEST(BoxWall, DiscOnAnInclinedPlateRollsOrSlidesAsTheTextbookSays) {
  const double g_sin = 9.81 * 0.5;
  const double rolling = 2.0 / 3.0 * g_sin;                          // mu = 0.5 > tan 30 / 3 = 0.192
  const double sliding = g_sin - 0.1 * 9.81 * std::sqrt(3.0) / 2.0;  // mu = 0.1 < 0.192
  EXPECT_NEAR(incline_acceleration<2>(0.5), rolling, 1e-3 * rolling);
  EXPECT_NEAR(incline_acceleration<2>(0.1), sliding, 1e-9 * sliding);
}

TEST(BoxWall, SphereOnAnInclinedPlateRollsOrSlidesAsTheTextbookSays) {
  const double g_sin = 9.81 * 0.5;
  const double rolling = 5.0 / 7.0 * g_sin;                          // mu = 0.5 > 2 tan 30 / 7 = 0.165
  const double sliding = g_sin - 0.1 * 9.81 * std::sqrt(3.0) / 2.0;  // mu = 0.1 < 0.165
  EXPECT_NEAR(incline_acceleration<3>(0.5), rolling, 1e-3 * rolling);
  EXPECT_NEAR(incline_acceleration<3>(0.1), sliding, 1e-9 * sliding);
}

// A vertical plate moving at V along x meets a free disc (no gravity,
// frictionless, elastic): in the plate's frame the disc bounces back at V,
// so it leaves at 2 V; the plate goes on at V whatever it meets.
TEST(BoxWall, MovingPlateSendsAGrainOffAtTwiceItsSpeed) {
  const double r = 5e-4;
  const double speed = 0.05;
  const double m = 2650.0 * particle_volume<2>(r);
  ContactSpec spec;
  spec.normal_stiffness = m * speed * speed / (1e-3 * r * 1e-3 * r);
  spec.restitution = 1.0;
  auto sim = single_material<2>(2650.0, spec);
  auto plate = box_wall<2>(Vec<2>(-2.0 * r, -r), Vec<2>(-2.0 * r, r));
  plate.motion = WallMotion::velocity;
  plate.velocity = Vec<2>(speed, 0.0);
  sim.walls.push_back(plate);
  sim.particles.add(Vec<2>(0.0, 0.0), r, 2650.0, 0, false);
  sim.time_step = 0.01 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  const double end = 4.0 * r / speed;  // reached after r / V, gone well before
  while (sim.time < end) sim.step();
  // The leapfrog on a linear spring switched on between steps: (omega dt)^2
  // = 1e-4 (measured 3e-6).
  EXPECT_NEAR(sim.particles.velocity[0].x(), 2.0 * speed, 2e-4 * speed);
  EXPECT_NEAR(sim.particles.velocity[0].y(), 0.0, 1e-12 * speed);
  EXPECT_NEAR(sim.walls[0].point.x(), -2.0 * r + speed * sim.time, 1e-12);
  EXPECT_EQ(sim.walls[0].force.norm(), 0.0);  // apart again
}

}  // namespace
}  // namespace darcydem
