// Clumps (rigid bodies of several particles) against the mechanics of
// rigid bodies. A dumbbell of two equal spheres on a common axle has the
// mass, the rolling inertia (2/5 M r^2) and the contacts per unit mass of
// one of its spheres alone: rolling down a slope it must go exactly as that
// sphere does. A free axisymmetric clump precesses about its angular
// momentum at |L| / I_perp (Euler's torque-free top); a free asymmetric one
// keeps its angular momentum and energy while it tumbles. Two clumps that
// collide without friction keep their total momentum and angular momentum
// to round-off (the contact forces are equal, opposite and along the line
// of the members' centres) and, elastic, their kinetic energy.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/particles/ball_union.hpp"
#include "darcydem/particles/clumps.hpp"
#include "darcydem/simulation/runner.hpp"
#include "dem_setup.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

namespace darcydem {
namespace {

using darcydem::testing::plane;
using darcydem::testing::read_probes;
using darcydem::testing::scene_from_text;
using darcydem::testing::scene_variant;
using darcydem::testing::single_material;
using darcydem::testing::temp_dir;

constexpr double kDensity = 2500.0;

/// A clump of the given members (centres and radii, m, about any point),
/// at x turned by q, moving at v; returns its number.
template <int D>
std::size_t add_clump(Simulation<D>& sim, const std::vector<Vec<D>>& centres,
                      const std::vector<double>& radii, const Vec<D>& x, const Orientation<D>& q,
                      const Vec<D>& v = Vec<D>::Zero()) {
  const ClumpShape<D> shape = make_clump_shape<D>(centres, radii);
  // The shape is scaled to a bounding radius of 1: scale it back.
  const double reach = radii[0] / shape.radius[0];
  const std::size_t c = sim.clumps.add(sim.particles, shape, reach, x, q, kDensity, 0, false, v);
  sim.clumps.refresh(sim.particles);
  return c;
}

/// The total angular momentum of the clumps about the origin (kg m^2/s).
template <int D>
AngVec<D> angular_momentum(const Simulation<D>& sim) {
  const auto& c = sim.clumps;
  AngVec<D> l = AngVec<D>::Zero();
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto r = rotation_matrix(c.orientation[k]);
    l += c.mass[k] * cross(c.position[k], c.velocity[k]);
    if constexpr (D == 2) {
      l += c.inertia[k].cwiseProduct(c.angular_velocity[k]);
    } else {
      l += r * c.inertia[k].cwiseProduct(r.transpose() * c.angular_velocity[k]);
    }
  }
  return l;
}

template <int D>
double clump_kinetic_energy(const Simulation<D>& sim) {
  const auto& c = sim.clumps;
  double e = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const auto r = rotation_matrix(c.orientation[k]);
    AngVec<D> w = c.angular_velocity[k];
    if constexpr (D == 3) w = r.transpose() * w;
    e += 0.5 * c.mass[k] * c.velocity[k].squaredNorm() + 0.5 * w.dot(c.inertia[k].cwiseProduct(w));
  }
  return e;
}

Orientation<3> identity3() { return ClumpShape<3>::identity_orientation(); }

// The shape's mass properties by hand: two spheres of radius r touching at
// the origin, along x. Volume 2 (4/3 pi r^3); about the axis 2 (2/5) m r^2,
// across it 2 ((2/5) m r^2 + m r^2). The shape is scaled to a bounding
// radius of 1 (2r = 1). Round-off only: 1e-12.
TEST(Clump, ADumbbellHasTheMassAndInertiaOfItsTwoSpheres) {
  const double r = 0.5;
  const auto shape = make_clump_shape<3>({Vec<3>(-r, 0, 0), Vec<3>(r, 0, 0)}, {r, r});
  const double v = particle_volume<3>(r);
  EXPECT_NEAR(shape.volume, 2.0 * v, 1e-12);
  EXPECT_NEAR(shape.inertia_per_density.minCoeff(), 2.0 * 0.4 * v * r * r, 1e-12);
  EXPECT_NEAR(shape.inertia_per_density.maxCoeff(), 2.0 * 1.4 * v * r * r, 1e-12);
  // Placed as given (orientation identity), its members lie along x.
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 1.0});
  sim.clumps.add(sim.particles, shape, 1e-3, Vec<3>(0, 0, 0), identity3(), kDensity, 0, false,
                 Vec<3>::Zero());
  EXPECT_NEAR(sim.particles.position[0].x(), -0.5e-3, 1e-15);
  EXPECT_NEAR(sim.particles.position[1].x(), 0.5e-3, 1e-15);
  EXPECT_NEAR(sim.particles.position[0].tail<2>().norm(), 0.0, 1e-15);
  // A member inside another adds nothing, and cannot share the volume.
  EXPECT_THROW(make_clump_shape<3>({Vec<3>(0, 0, 0), Vec<3>(0.4, 0, 0)}, {1.0, 0.5}), std::invalid_argument);
}

/// The volume of two balls of radius a whose centres are d apart, and the
/// second moments of the union about its centre along and across the axis:
/// per half, u from -d/2 to a along the axis from that ball's centre, the
/// slice a disc of area pi (a^2 - u^2) at x = u + d/2 (closed forms of
/// polynomials in u).
struct TwoBalls {
  double volume;
  double along;   ///< integral of x^2 dV
  double across;  ///< integral of y^2 dV
};
TwoBalls two_balls(double a, double d) {
  const double pi = std::numbers::pi;
  const double h = 0.5 * d;
  auto v = [&](double u) { return pi * (a * a * u - u * u * u / 3.0); };
  // (a^2 - u^2)(u + h)^2 expanded: -u^4 - 2h u^3 + (a^2 - h^2) u^2 + 2 a^2 h u + a^2 h^2.
  auto x2 = [&](double u) {
    return pi * (-std::pow(u, 5) / 5.0 - h * std::pow(u, 4) / 2.0 + (a * a - h * h) * std::pow(u, 3) / 3.0 +
                 a * a * h * u * u + a * a * h * h * u);
  };
  // pi (a^2 - u^2)^2 / 4.
  auto y2 = [&](double u) {
    return pi / 4.0 * (std::pow(a, 4) * u - 2.0 * a * a * std::pow(u, 3) / 3.0 + std::pow(u, 5) / 5.0);
  };
  return {2.0 * (v(a) - v(-h)), 2.0 * (x2(a) - x2(-h)), 2.0 * (y2(a) - y2(-h))};
}

// PFC's clumps are pebbles that overlap. Two equal spheres a radius apart
// make one solid, the union: its mass and moments of inertia are the
// union's (closed form above; ball_union.hpp's to 1e-12), not the members'
// sums (16 % more volume: the lens would count twice), and each member
// carries half of it, its mass and its solid for the pore fluid.
TEST(Clump, OverlappingMembersHaveTheMassAndInertiaOfTheirUnion) {
  const double a = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  add_clump<3>(sim, {Vec<3>(0, 0, 0), Vec<3>(a, 0, 0)}, {a, a}, Vec<3>(0, 0, 0), identity3());
  const TwoBalls u = two_balls(a, a);
  const double m = kDensity * u.volume;
  EXPECT_NEAR(sim.clumps.mass[0] / m, 1.0, 1e-12);
  // Principal moments ascending: the axis (the two across moments), then
  // the two across (the along moment and one across).
  const AngVec<3> expect(2.0 * u.across, u.along + u.across, u.along + u.across);
  EXPECT_LT((sim.clumps.inertia[0] - kDensity * expect).norm(), 1e-12 * kDensity * expect.norm());
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(1.0 / sim.particles.inv_mass[i] / (0.5 * m), 1.0, 1e-12);
    EXPECT_NEAR(sim.particles.solid_volume(i) / (0.5 * u.volume), 1.0, 1e-12);
  }
  EXPECT_GT(2.0 * particle_volume<3>(a) / u.volume, 1.15);  // the sums would be this wrong
  std::printf("overlapping pair: mass %+.2e, inertia %.2e\n", sim.clumps.mass[0] / m - 1.0,
              (sim.clumps.inertia[0] - kDensity * expect).norm() / (kDensity * expect.norm()));
}

// An uneven clump of three overlapping spheres (radii 1, 0.5 and 0.6 mm):
// its members' centres are not where the union's volume is, so shares in
// proportion to the members' own volumes would put the weight 0.04 mm off
// the centre of mass (asserted above 0.02 mm), and gravity would turn a
// falling clump with the moment m g times that. The shares are chosen to
// put the weight at the centre of mass: in free fall it keeps no spin but
// round-off's (1e-10 rad/s, as for the touching spheres) and falls as a
// point mass (1e-12 of the distance).
TEST(Clump, AnUnevenClumpOfOverlappingSpheresFallsWithoutSpin) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  const std::vector<Vec<3>> centres{Vec<3>(0, 0, 0), Vec<3>(1.2 * r, 0, 0),
                                    Vec<3>(0.3 * r, 0.9 * r, 0.2 * r)};
  const std::vector<double> radii{r, 0.5 * r, 0.6 * r};
  // The proportional shares' miss: how far their weight is from the
  // union's centre of mass, the test's reason to be.
  const auto u = ball_union_moments<3>(centres, radii);
  double own = 0.0;
  Vec<3> proportional = Vec<3>::Zero();
  for (std::size_t i = 0; i < 3; ++i) {
    own += particle_volume<3>(radii[i]);
    proportional += particle_volume<3>(radii[i]) * centres[i];
  }
  ASSERT_GT((proportional / own - u.centroid()).norm(), 0.02 * r);
  const Vec<3> v0(0.1, -0.05, 0.2);
  add_clump<3>(sim, centres, radii, Vec<3>(0, 0, 1), identity3(), v0);
  EXPECT_NEAR(sim.clumps.mass[0] / (kDensity * u.volume), 1.0, 1e-12);
  sim.gravity = Vec<3>(1.0, -2.0, -9.81);
  sim.time_step = 1e-5;
  sim.prepare();
  const Vec<3> x0 = sim.clumps.position[0];
  sim.advance(10'000);
  const double t = sim.time;
  const Vec<3> expect = x0 + v0 * t + 0.5 * sim.gravity * t * t;
  EXPECT_LT((sim.clumps.position[0] - expect).norm(), 1e-12 * (expect - x0).norm());
  EXPECT_LT(sim.clumps.angular_velocity[0].norm(), 1e-10);
  EXPECT_EQ(sim.contact_count(), 0u);
  std::printf("uneven clump in free fall: position %.2e of the distance, spin %.2e rad/s\n",
              (sim.clumps.position[0] - expect).norm() / (expect - x0).norm(),
              sim.clumps.angular_velocity[0].norm());
}

// Members of one clump never touch each other: a lone clump of four
// touching spheres in free fall has no contact, and falls as a point mass,
// x = x0 + v0 t + g t^2 / 2, which velocity Verlet integrates exactly (to
// round-off: 1e-12 of the distance), without turning: the members' weights
// have no moment about the centre of mass but round-off's (1e-20 N m), which
// spins it at no more than 1e-10 rad/s over the fall (a turn of 1e-12 rad).
TEST(Clump, AClumpOfTouchingSpheresFallsFreelyWithoutContactsOrSpin) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  const double h = r * std::sqrt(3.0);  // a triangle of side 2r, and one on top
  const Vec<3> v0(0.1, -0.05, 0.2);
  add_clump<3>(
      sim,
      {Vec<3>(0, 0, 0), Vec<3>(2 * r, 0, 0), Vec<3>(r, h, 0), Vec<3>(r, h / 3, std::sqrt(8.0 / 3.0) * r)},
      {r, r, r, r}, Vec<3>(0, 0, 1), identity3(), v0);
  sim.gravity = Vec<3>(0, 0, -9.81);
  sim.time_step = 1e-5;
  const Vec<3> x0 = sim.clumps.position[0];
  const Vec<3> arm0 = sim.particles.position[3] - x0;
  sim.prepare();
  sim.advance(5000);
  EXPECT_EQ(sim.contact_count(), 0u);
  const double t = sim.time;
  const Vec<3> expected = x0 + v0 * t + 0.5 * sim.gravity * t * t;
  EXPECT_LT((sim.clumps.position[0] - expected).norm(), 1e-12 * (expected - x0).norm());
  EXPECT_LT((sim.particles.position[3] - sim.clumps.position[0] - arm0).norm(), 1e-14);  // positions near 1 m
  EXPECT_LT(sim.clumps.angular_velocity[0].norm(), 1e-10);
}

// A dumbbell of two spheres of radius r touching on an axle along y rolls
// down a slope (gravity tilted by 20 degrees about y) as one sphere alone
// does: twice the mass, two contacts with the same springs and dashpots
// (the dashpot takes each member's own mass), the inertia about the axle
// 2 (2/5) m r^2 = (2/5) M r^2. The two runs do the same arithmetic up to
// the round-off of the clump's rotation matrix (1e-16): its centre of mass
// follows the sphere to 1e-9 r and 1e-9 of the speed over 0.1 s (12 mm,
// 13 000 steps; measured 2e-11 r and 3e-12), and both roll at 5/7 g sin 20 t, to the tangential
// spring's start-up oscillation (1 %, as in test_mesh_walls.cpp).
TEST(Clump, ADumbbellRollsDownASlopeAsOneOfItsSpheres) {
  const double r = 1e-3;
  const double g = 9.81;
  const double slope = 20.0 * std::numbers::pi / 180.0;
  const double m = kDensity * particle_volume<3>(r);
  ContactSpec spec{.normal_stiffness = m * g / (1e-4 * r), .restitution = 0.5, .friction = 0.5};
  auto make = [&](bool clump) {
    auto sim = single_material<3>(kDensity, spec);
    const double z = r - m * g * std::cos(slope) / spec.normal_stiffness;  // resting overlap
    if (clump) {
      add_clump<3>(sim, {Vec<3>(0, -r, 0), Vec<3>(0, r, 0)}, {r, r}, Vec<3>(0, 0, z), identity3());
    } else {
      sim.particles.add(Vec<3>(0, 0, z), r, kDensity, 0, false);
    }
    sim.walls.push_back(plane<3>(Vec<3>::Zero(), Vec<3>(0, 0, 1), "floor"));
    sim.gravity = Vec<3>(g * std::sin(slope), 0.0, -g * std::cos(slope));
    sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
    sim.prepare();
    return sim;
  };
  auto sphere = make(false);
  auto dumbbell = make(true);
  while (sphere.time < 0.1) {
    sphere.advance(100);
    dumbbell.advance(100);
  }
  const double v = 5.0 / 7.0 * g * std::sin(slope) * sphere.time;
  EXPECT_EQ(dumbbell.contact_count(), 2u);
  EXPECT_LT((dumbbell.clumps.position[0] - sphere.particles.position[0]).norm(), 1e-9 * r);
  EXPECT_LT((dumbbell.clumps.velocity[0] - sphere.particles.velocity[0]).norm(), 1e-9 * v);
  EXPECT_LT((dumbbell.clumps.angular_velocity[0] - sphere.particles.angular_velocity[0]).norm(),
            1e-9 * v / r);
  EXPECT_NEAR(sphere.particles.velocity[0].x(), v, 0.01 * v);
  EXPECT_GT(sphere.particles.position[0].x(), 0.01);  // 12 mm: 6 diameters
}

// Euler's free symmetric top: a dumbbell (I_3 about its axis, I_perp across
// it) spun about an axis 30 degrees off its own, without gravity or
// contacts. Its angular momentum L stays put; its axis turns about L at
// |L| / I_perp, on a cone of fixed angle. Over 1.5 turns of the precession
// (56 000 steps of w dt = 3e-4), the implicit midpoint's phase error is of
// order (w dt)^2 w t / 12 = 1e-7 rad: the axis within 1e-6 of the closed
// form (measured 7e-9); the energy to (w dt)^2 (1e-6; measured 2e-11). L is the drift's invariant: each
// step maps it to the angular velocity and back, three products of 3 x 3
// matrices, a few 1e-16 of it; over 56 000 steps they add up to 4e-11
// (measured): within 1e-9.
TEST(Clump, AFreeDumbbellPrecessesAsEulersSymmetricTop) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  add_clump<3>(sim, {Vec<3>(0, 0, -r), Vec<3>(0, 0, r)}, {r, r}, Vec<3>::Zero(), identity3());
  const double w = 100.0;
  const double tilt = 30.0 * std::numbers::pi / 180.0;
  sim.clumps.angular_velocity[0] = w * Vec<3>(std::sin(tilt), 0.0, std::cos(tilt));
  sim.clumps.place_members(sim.particles);
  const auto& c = sim.clumps;
  const double i_perp = c.inertia[0].maxCoeff();
  const AngVec<3> l0 = angular_momentum(sim);
  const double e0 = clump_kinetic_energy(sim);
  const Vec<3> axis0 = (sim.particles.position[1] - sim.particles.position[0]).normalized();
  sim.time_step = 3e-6;
  sim.prepare();
  const double turn = 2.0 * std::numbers::pi * i_perp / l0.norm();
  const auto steps = static_cast<std::uint64_t>(1.5 * turn / sim.time_step);
  sim.advance(steps);
  const Vec<3> axis = (sim.particles.position[1] - sim.particles.position[0]).normalized();
  const Eigen::AngleAxisd precession(l0.norm() / i_perp * sim.time, l0.normalized());
  EXPECT_LT((axis - precession * axis0).norm(), 1e-6);
  EXPECT_LT((angular_momentum(sim) - l0).norm(), 1e-9 * l0.norm());
  EXPECT_NEAR(clump_kinetic_energy(sim), e0, 1e-6 * e0);
  EXPECT_NEAR(sim.kinetic_energy(), e0, 1e-6 * e0);  // the members' sum: the same body
}

// An asymmetric clump (three unequal spheres in a bent row) spun near its
// intermediate axis tumbles, flipping over and back (Dzhanibekov's nut): a
// hard case for an integrator. Its angular momentum stays to round-off
// (1.2e-10 measured over 100 000 steps, as above: within 1e-9), its energy
// to (w dt)^2 (1e-5; measured 5e-10).
TEST(Clump, AnAsymmetricClumpTumblesKeepingItsMomentumAndEnergy) {
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  add_clump<3>(sim, {Vec<3>(-1.8e-3, 0, 0), Vec<3>(0, 0, 0), Vec<3>(1.5e-3, 1e-3, 0)}, {0.8e-3, 1e-3, 0.8e-3},
               Vec<3>::Zero(), identity3());
  auto& c = sim.clumps;
  // Nearly about the intermediate principal axis (the second column).
  const auto r = rotation_matrix(c.orientation[0]);
  c.angular_velocity[0] = 100.0 * (r.col(1) + 0.01 * r.col(0)).normalized();
  c.place_members(sim.particles);
  const AngVec<3> l0 = angular_momentum(sim);
  const double e0 = clump_kinetic_energy(sim);
  sim.time_step = 3e-6;
  sim.prepare();
  double flip = 1.0;  // the intermediate axis's lowest alignment with L
  for (int k = 0; k < 1000; ++k) {
    sim.advance(100);
    flip = std::min(flip, (rotation_matrix(c.orientation[0]).col(1)).dot(l0.normalized()));
  }
  EXPECT_LT(flip, -0.9);  // it turned over
  EXPECT_LT((angular_momentum(sim) - l0).norm(), 1e-9 * l0.norm());
  EXPECT_NEAR(clump_kinetic_energy(sim), e0, 1e-5 * e0);
}

// Two clumps meet off-centre, without friction or damping (restitution 1),
// in zero gravity: they bounce and spin apart. The forces are equal,
// opposite and along the line through the two members' centres, so the
// total momentum stays to round-off (1e-12), and the angular momentum about
// the origin too, a sum of terms x_c x M v_c as large as 5 r |p| that
// cancel, its round-off over 10 000 steps up to 1e-10 of that; the kinetic
// energy comes back after the contact to the spring's discrete error,
// (w_c dt)^2 with dt = pi sqrt(m / k) / 100 and w_c up to 2 sqrt(k / m) at
// an off-centre contact (1e-3; measured 1.6e-4 in 2D, 1e-9 in 3D).
template <int D>
void collide() {
  const double r = 1e-3;
  auto sim = single_material<D>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 1.0});
  Vec<D> along = Vec<D>::Zero();
  along[0] = 1.0;
  Vec<D> across = Vec<D>::Zero();
  across[1] = 1.0;
  auto q0 = ClumpShape<D>::identity_orientation();
  // Dumbbells along y, the second one higher by r: they meet member to member.
  add_clump<D>(sim, {Vec<D>(-r * across), Vec<D>(r * across)}, {r, r}, Vec<D>::Zero(), q0,
               Vec<D>(0.2 * along));
  add_clump<D>(sim, {Vec<D>(-r * across), Vec<D>(r * across)}, {r, r},
               Vec<D>(4.5 * r * along + 1.2 * r * across), q0, Vec<D>(-0.1 * along));
  const double m = kDensity * particle_volume<D>(r);
  sim.time_step = std::sqrt(m / 100.0) * std::numbers::pi / 100.0;
  const Vec<D> p0 = sim.clumps.mass[0] * sim.clumps.velocity[0] + sim.clumps.mass[1] * sim.clumps.velocity[1];
  const AngVec<D> l0 = angular_momentum(sim);
  const double e0 = clump_kinetic_energy(sim);
  sim.prepare();
  sim.advance(10000);
  EXPECT_EQ(sim.contact_count(), 0u);                     // apart again
  EXPECT_GT(sim.clumps.angular_velocity[0].norm(), 1.0);  // spun by the off-centre blow
  const Vec<D> p = sim.clumps.mass[0] * sim.clumps.velocity[0] + sim.clumps.mass[1] * sim.clumps.velocity[1];
  EXPECT_LT((p - p0).norm(), 1e-12 * p0.norm());
  EXPECT_LT((angular_momentum(sim) - l0).norm(), 1e-10 * (l0.norm() + p0.norm() * 5 * r));
  EXPECT_NEAR(clump_kinetic_energy(sim), e0, 1e-3 * e0);
}

// The energy budget counts a clump as one body: its kinetic energy
// 1/2 M v^2 + 1/2 w.L, each half kick's change split into the works of its
// kinds of load (gravity, contacts, damping) by their parts of its force
// and moment. An uneven clump of three overlapping spheres (radii 1, 0.5
// and 0.6 mm) dropped turned from 3 mm onto a floor, with friction 0.5, a
// dashpot and local damping 0.3, bounces, tumbles and settles in 0.1 s.
// The budget then closes: the kinetic energy is its start plus the works
// to 1e-10 of gravity's work (measured 4e-12: the implicit midpoint turn
// keeps an asymmetric clump's angular momentum exactly but its kinetic
// energy only to (w dt)^2 a step, which no work accounts for), gravity's
// work is the fall of the potential energy (sum of -m_i g.x_i over the
// members, which the shares make M g.x_c) to 1e-6 (the kicks' work against
// the drifts' move differs by about M g^2 dt^2 / 8 in all; measured
// 1.8e-7), and damping and the contacts took what gravity and the start's
// kinetic energy gave, less the springs' energy at rest (1e-9).
TEST(Clump, TheEnergyBudgetCountsAClumpAsOneBody) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity,
                                ContactSpec{.normal_stiffness = 100.0, .restitution = 0.3, .friction = 0.5});
  sim.walls.push_back(plane<3>(Vec<3>::Zero(), Vec<3>(0, 0, 1)));
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.7, Vec<3>(1.0, 2.0, 0.5).normalized()));
  add_clump<3>(sim, {Vec<3>(0, 0, 0), Vec<3>(1.2 * r, 0, 0), Vec<3>(0.3 * r, 0.9 * r, 0.2 * r)},
               {r, 0.5 * r, 0.6 * r}, Vec<3>(0, 0, 3 * r),
               Orientation<3>(turn.w(), turn.x(), turn.y(), turn.z()), Vec<3>(0.05, 0.0, 0.0));
  sim.gravity = Vec<3>(0, 0, -9.81);
  sim.damping.local = 0.3;
  sim.track_energy = true;
  sim.time_step = 0.1 * sim.critical_time_step();
  const double potential0 = sim.gravitational_energy();
  sim.prepare();
  sim.advance(static_cast<std::uint64_t>(0.1 / sim.time_step));
  const auto& e = sim.energy;
  const double fall = potential0 - sim.gravitational_energy();
  ASSERT_GT(fall, 0.0);
  EXPECT_GT(sim.contact_count(), 0u);
  EXPECT_LT(std::abs(sim.unaccounted_energy()), 1e-10 * e.gravity_work);
  EXPECT_NEAR(e.gravity_work / fall, 1.0, 1e-6);
  const double taken = e.damping_dissipation() + sim.contact_dissipation();
  EXPECT_NEAR(taken + sim.kinetic_energy() + sim.elastic_energy(), e.gravity_work + e.kinetic_start,
              1e-9 * e.gravity_work);
  EXPECT_GT(e.damping_dissipation(), 0.0);
  std::printf(
      "clump's energy budget: unaccounted %.2e, gravity's work / fall - 1 %.2e, damping %.3g and "
      "contacts %.3g of it\n",
      sim.unaccounted_energy() / e.gravity_work, e.gravity_work / fall - 1.0,
      e.damping_dissipation() / e.gravity_work, sim.contact_dissipation() / e.gravity_work);
}

TEST(Clump, TwoDumbbellsCollideKeepingMomentumAndEnergy2D) { collide<2>(); }
TEST(Clump, TwoDumbbellsCollideKeepingMomentumAndEnergy3D) { collide<3>(); }

// A [domain] removes a clump whole, by its centre of mass: three dumbbells
// of spheres of 1 mm, upright, fall freely side by side from centres at
// z = 3, 6 and 9 mm through the domain's floor at z = 0, with a loose
// sphere beside them at 6 mm. After t = 0.0416 s (8.49 mm of fall; a
// list lasts skin / 2 = 0.1 mm of fall) the first's centre is 5.5 mm below
// the floor, the second's and the sphere's 2.5 mm below and the third's
// 0.51 mm above, the centre of its lower member 0.49 mm below: the
// first two clumps and the sphere are gone with all their members, the
// third is kept whole, and removed_mass is the two clumps' and the
// sphere's masses (round-off: 1e-12).
TEST(Clump, ADomainRemovesAClumpWholeByItsCentreOfMass) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  const std::vector<Vec<3>> upright{Vec<3>(0, 0, -r), Vec<3>(0, 0, r)};
  sim.particles.add(Vec<3>(-3.0 * r, 0, 6.0 * r), r, kDensity, 0, false);
  for (int k = 0; k < 3; ++k)
    add_clump<3>(sim, upright, {r, r}, Vec<3>(3.0 * k * r, 0, 3.0 * (k + 1) * r), identity3());
  const double m_clump = sim.clumps.mass[0];
  const double m_sphere = 1.0 / sim.particles.inv_mass[0];
  sim.has_domain = true;
  sim.domain_lower = Vec<3>(-0.1, -0.1, 0.0);
  sim.domain_upper = Vec<3>(0.1, 0.1, 0.1);
  sim.gravity = Vec<3>(0, 0, -9.81);
  sim.time_step = 1e-5;
  sim.prepare();
  sim.advance(4160);
  ASSERT_EQ(sim.clumps.size(), 1u);
  EXPECT_NEAR(sim.clumps.position[0].z(), 9.0 * r - 0.5 * 9.81 * sim.time * sim.time, 1e-12);
  ASSERT_EQ(sim.particles.size(), 2u);
  // The lower member's centre is out of the domain: kept all the same.
  EXPECT_LT(std::min(sim.particles.position[0].z(), sim.particles.position[1].z()), -0.4 * r);
  EXPECT_EQ(sim.removed_count, 5u);
  EXPECT_NEAR(sim.removed_mass, 2.0 * m_clump + m_sphere, 1e-12 * m_clump);
  // The members keep their clump after the removal reordered the particles.
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(sim.clumps.clump_of[i], 0) << i;
  sim.advance(100);
  EXPECT_NEAR(std::abs(sim.particles.position[1].z() - sim.particles.position[0].z()), 2.0 * r, 1e-15);
}

// Periodic boundaries: the collision above moved 2 r down x in a box
// periodic along x over [0, 20 r), so that the two dumbbells meet across
// its ends, one at x = 18 r, the other at 2.5 r. Space is the same
// everywhere: each clump's velocity and spin must be those of the open run
// (to 1e-9: the runs differ by the round-off of positions 18 r from the
// origin, which the contact does not amplify), its centre the open run's
// moved by -2 r, to a whole period (1e-12 m). 3000 steps see them meet
// and part, before they could meet again the other way round.
TEST(Clump, TwoDumbbellsCollideAcrossAPeriodicBoundaryAsInOpenSpace) {
  const double r = 1e-3;
  auto run = [&](bool periodic) {
    auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 1.0});
    const Vec<3> shift(periodic ? 18.0 * r : 0.0, 0.0, 0.0);
    if (periodic) sim.periodic.set_axis(0, 0.0, 20.0 * r);
    const std::vector<Vec<3>> members{Vec<3>(0, -r, 0), Vec<3>(0, r, 0)};
    add_clump<3>(sim, members, {r, r}, shift, identity3(), Vec<3>(0.2, 0, 0));
    add_clump<3>(sim, members, {r, r},
                 Vec<3>(4.5 * r, 1.2 * r, 0) + shift - Vec<3>(periodic ? 20.0 * r : 0.0, 0, 0), identity3(),
                 Vec<3>(-0.1, 0, 0));
    sim.time_step = std::sqrt(kDensity * particle_volume<3>(r) / 100.0) * std::numbers::pi / 100.0;
    sim.prepare();
    sim.advance(3000);
    return sim;
  };
  const auto open = run(false);
  const auto across = run(true);
  EXPECT_EQ(open.contact_count(), 0u);
  EXPECT_GT(open.clumps.angular_velocity[0].norm(), 1.0);  // they met
  for (std::size_t c = 0; c < 2; ++c) {
    const double v = open.clumps.velocity[c].norm();
    EXPECT_LT((across.clumps.velocity[c] - open.clumps.velocity[c]).norm(), 1e-9 * v) << c;
    EXPECT_LT((across.clumps.angular_velocity[c] - open.clumps.angular_velocity[c]).norm(),
              1e-9 * open.clumps.angular_velocity[c].norm())
        << c;
    const Vec<3> moved = open.clumps.position[c] + Vec<3>(18.0 * r, 0, 0);
    EXPECT_LT(across.periodic.shortest(across.clumps.position[c] - moved).norm(), 1e-12) << c;
    EXPECT_LT(across.clumps.position[c].x(), 20.0 * r + 0.5 * across.skin) << c;  // put back at the builds
  }
  std::printf("collision across a periodic boundary: velocity %.2e, spin %.2e; list builds %zu (open %zu)\n",
              (across.clumps.velocity[0] - open.clumps.velocity[0]).norm() / open.clumps.velocity[0].norm(),
              (across.clumps.angular_velocity[0] - open.clumps.angular_velocity[0]).norm() /
                  open.clumps.angular_velocity[0].norm(),
              across.list_builds(), open.list_builds());
}

// A spinning peanut flies through a box periodic along all three axes, 20
// periods of 10 mm in 20 000 steps: it keeps x0 + v t to a whole period
// (1e-12 m), its spin, and its members 1 mm apart (nearest images, 1e-15 m);
// its members move continuously between the list builds, which put them
// back into the box one by one, so the lists are built as often as in open
// space (each time a member has moved half the skin), not every step.
TEST(Clump, APeanutFliesThroughAPeriodicBoxKeepingItsShape) {
  const double r = 1e-3;
  auto sim = single_material<3>(kDensity, ContactSpec{.normal_stiffness = 100.0, .restitution = 0.5});
  for (int k = 0; k < 3; ++k) sim.periodic.set_axis(k, 0.0, 0.01);
  const Vec<3> x0(0.005, 0.005, 0.005);
  const Vec<3> v(1.0, 0.6, -0.3);
  add_clump<3>(sim, {Vec<3>(-0.5 * r, 0, 0), Vec<3>(0.5 * r, 0, 0)}, {r, r}, x0, identity3(), v);
  sim.clumps.angular_velocity[0] = Vec<3>(0.0, 0.0, 30.0);  // about an axis of symmetry of its inertia
  sim.clumps.place_members(sim.particles);
  sim.time_step = 1e-5;
  sim.prepare();
  sim.advance(20'000);
  const double t = sim.time;
  EXPECT_LT(sim.periodic.shortest(sim.clumps.position[0] - (x0 + v * t)).norm(), 1e-12);
  EXPECT_LT((sim.clumps.angular_velocity[0] - Vec<3>(0.0, 0.0, 30.0)).norm(), 1e-9);
  const double gap = sim.periodic.shortest(sim.particles.position[1] - sim.particles.position[0]).norm();
  EXPECT_NEAR(gap, r, 1e-15);
  // Open space: a member moves about |v| dt + 30 x 0.5 mm x dt a step, so a
  // list lasts skin / 2 over that; allow twice as many builds.
  const double per_step = (v.norm() + 30.0 * 0.5 * r) * sim.time_step;
  const double builds = 20'000 * per_step / (0.5 * sim.skin);
  EXPECT_LT(static_cast<double>(sim.list_builds()), 2.0 * builds + 2.0);
  std::printf("peanut through a periodic box: list builds %zu (open space about %.0f)\n", sim.list_builds(),
              builds);
}

// examples/dem_cases/clump_pour.toml: 100 dumbbells and 100 trimers poured
// into a box of five frictional plane walls, settled until the unbalanced
// force ratio is below 1e-4. At rest the walls carry the clumps' weight
// (the floor nearly all, the sides the rest by friction): their vertical
// loads add up to it to the clumps' residual net force, at most about 1e-4
// of a contact force each, some 1e-4 of the weight in all (measured
// 2e-5): within 1e-3. No member got through a wall.
TEST(Clump, APouredBedOfClumpsRestsOnItsWalls) {
  const std::string dir = temp_dir("clump_pour");
  std::string probes;
  for (const char* w : {"west", "east", "south", "north"}) {
    probes += fmt::format(
        "\n[[probe]]\nname = \"{}_z\"\nquantity = \"wall_force\"\nwall = \"{}\"\ncomponent = \"z\"\n", w, w);
  }
  Scene<3> scene = scene_from_text<3>(
      dir, "pour.toml",
      scene_variant("examples/dem_cases/clump_pour.toml", {{"[[stage]]", probes + "\n[[stage]]"}}));
  double weight = 0.0;
  for (double m : scene.simulation.clumps.mass) weight += m * 9.81;
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<3>(scene, options).interrupted);
  const auto rows = read_probes(dir + "/out/probes.csv");
  const auto last = [&](const char* name) { return rows.at(name).back(); };
  EXPECT_LT(last("unbalanced"), 1e-4);  // settled, not out of time
  const double carried =
      -(last("floor_z") + last("west_z") + last("east_z") + last("south_z") + last("north_z"));
  std::printf("clump pour: weight %.6g N, carried by the walls %.6g N (%.2e)\n", weight, carried,
              carried / weight - 1.0);
  EXPECT_NEAR(carried, weight, 1e-3 * weight);
  const auto& p = scene.simulation.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec<3>& x = p.position[i];
    EXPECT_TRUE(x.z() > 0.0 && std::abs(x.x()) < 0.006 && std::abs(x.y()) < 0.006) << i;
  }
  // The snapshots give each particle its clump, to colour them by: the
  // first generator's 100 clumps of two, then 100 of three.
  const std::string text = darcydem::testing::file_contents(dir + "/out/particles_00000.vtu");
  const auto at = text.find("Name=\"clump\"");
  ASSERT_NE(at, std::string::npos);
  std::istringstream values(text.substr(text.find('>', at) + 1));
  std::vector<int> members(200, 0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    int c = -1;
    values >> c;
    ASSERT_TRUE(c >= 0 && c < 200) << i;
    ++members[static_cast<std::size_t>(c)];
  }
  for (std::size_t c = 0; c < 200; ++c) EXPECT_EQ(members[c], c < 100 ? 2 : 3) << c;
}

/// examples/dem_cases/clump_pour.toml in a box periodic along x and y:
/// the four side walls out, the period in their place; `more` changes too.
std::string periodic_pour(std::vector<std::pair<std::string, std::string>> more) {
  more.push_back({"[[wall]]\nname = \"floor\"",
                  "[periodic]\nx = [-0.006, 0.006]\ny = [-0.006, 0.006]\n\n[[wall]]\nname = \"floor\""});
  for (const char* w : {"west", "east", "south", "north"})
    more.push_back({fmt::format("[[wall]]\nname = \"{}\"", w), "[[side_wall_out]]"});
  std::string text = scene_variant("examples/dem_cases/clump_pour.toml", more);
  // Each side wall's remaining lines (point, normal, material) go with it.
  for (std::size_t at = text.find("[[side_wall_out]]"); at != std::string::npos;
       at = text.find("[[side_wall_out]]"))
    text.erase(at, text.find("\n\n", at) - at);
  return text;
}

// The same pour in a box periodic along x and y instead of four side walls
// (the generators' clouds span the period and wrap round it, clumps
// straddling its ends): the floor alone carries the weight, within 1e-3
// as above, and every member of a clump stays at its distances from the
// others (nearest images, 1e-15 m of positions of 10 mm) while clumps pass
// through the ends.
TEST(Clump, APouredBedOfClumpsInAPeriodicBoxRestsOnItsFloor) {
  const std::string dir = temp_dir("clump_pour_periodic");
  const std::string text = periodic_pour({});
  Scene<3> scene = scene_from_text<3>(dir, "pour.toml", text);
  ASSERT_EQ(scene.simulation.walls.size(), 1u);
  const auto& sim = scene.simulation;
  // The members' distances to each other in each clump.
  auto distances = [&] {
    std::vector<double> d;
    const auto& c = sim.clumps;
    for (std::size_t k = 0; k < c.size(); ++k) {
      for (std::uint32_t a = c.first[k]; a < c.first[k + 1]; ++a) {
        for (std::uint32_t b = a + 1; b < c.first[k + 1]; ++b) {
          const std::size_t i = sim.particles.index_of(c.member_id[a]);
          const std::size_t j = sim.particles.index_of(c.member_id[b]);
          d.push_back(sim.periodic.shortest(sim.particles.position[j] - sim.particles.position[i]).norm());
        }
      }
    }
    return d;
  };
  const std::vector<double> before = distances();
  double weight = 0.0;
  for (double m : sim.clumps.mass) weight += m * 9.81;
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<3>(scene, options).interrupted);
  const auto rows = read_probes(dir + "/out/probes.csv");
  EXPECT_LT(rows.at("unbalanced").back(), 1e-4);  // settled, not out of time
  const double carried = -rows.at("floor_z").back();
  std::printf("periodic clump pour: weight %.6g N, carried by the floor %.6g N (%.2e)\n", weight, carried,
              carried / weight - 1.0);
  EXPECT_NEAR(carried, weight, 1e-3 * weight);
  const std::vector<double> after = distances();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t k = 0; k < after.size(); ++k) EXPECT_NEAR(after[k], before[k], 1e-15) << k;
  // Clumps lie across the ends: centres within 1 mm of them, so members
  // (of radius 0.4 to 0.55 mm, 0.3 to 1.1 mm from the centre) on both sides.
  std::size_t straddling = 0;
  for (std::size_t k = 0; k < sim.clumps.size(); ++k) {
    const Vec<3>& x = sim.clumps.position[k];
    straddling += (std::abs(x.x()) > 0.005 || std::abs(x.y()) > 0.005) ? 1 : 0;
  }
  EXPECT_GT(straddling, 0u);
}

// OUT/particles_final.csv keeps the clumps (a `clump` column), so a bed
// poured once starts other scenes as clumps: the periodic pour stopped
// mid-fall at 0.03 s (clumps tumbling, some across the period's ends, each
// written whole about its centre of mass in the period) read back by a
// scene's csv generator: the same clumps in the same order, each with its
// members where they were (nearest images, 1e-15 m of positions of 10 mm:
// 17 digits), its mass (1e-12) and principal moments (1e-9: the same
// members, their tensor's eigenvalues to round-off) and its centre (1e-15 m).
TEST(Clump, ClumpsWrittenAtTheEndStartAnotherSceneAsClumps) {
  const std::string dir = temp_dir("clump_csv");
  const std::string text = periodic_pour({{"duration = 1.5", "duration = 0.03"}});
  Scene<3> first = scene_from_text<3>(dir, "pour.toml", text);
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<3>(first, options).interrupted);
  const std::string csv = darcydem::testing::file_contents(dir + "/out/particles_final.csv");
  ASSERT_NE(csv.find("x,y,z,radius,clump\n"), std::string::npos);
  Scene<3> second = scene_from_text<3>(dir, "again.toml", R"(
[simulation]
dimension = 3
time_step = "auto"
initial_overlap_tolerance = 0.5

[periodic]
x = [-0.006, 0.006]
y = [-0.006, 0.006]

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e3
restitution = 0.3

[[wall]]
name = "floor"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]
material = "sand"

[[particles]]
generator = "csv"
material = "sand"
file = "out/particles_final.csv"

[[stage]]
name = "rest"
duration = 0.001
gravity = [0.0, 0.0, -9.81]
)");
  const auto& a = first.simulation;
  const auto& b = second.simulation;
  ASSERT_EQ(b.clumps.size(), a.clumps.size());
  ASSERT_EQ(b.particles.size(), a.particles.size());
  std::size_t across = 0;
  for (std::size_t c = 0; c < a.clumps.size(); ++c) {
    EXPECT_NEAR(b.clumps.mass[c] / a.clumps.mass[c], 1.0, 1e-12) << c;
    EXPECT_LT((b.clumps.inertia[c] - a.clumps.inertia[c]).norm(), 1e-9 * a.clumps.inertia[c].norm()) << c;
    EXPECT_LT(b.periodic.shortest(b.clumps.position[c] - a.clumps.position[c]).norm(), 1e-15) << c;
    ASSERT_EQ(b.clumps.first[c + 1] - b.clumps.first[c], a.clumps.first[c + 1] - a.clumps.first[c]) << c;
    for (std::uint32_t k = a.clumps.first[c]; k < a.clumps.first[c + 1]; ++k) {
      const Vec<3>& xa = a.particles.position[a.clumps.member_index[k]];
      const Vec<3>& xb = b.particles.position[b.clumps.member_index[k]];
      EXPECT_LT(b.periodic.shortest(xb - xa).norm(), 1e-15) << c << " " << k;
    }
    across +=
        std::abs(a.clumps.position[c].x()) > 0.005 || std::abs(a.clumps.position[c].y()) > 0.005 ? 1 : 0;
  }
  EXPECT_GT(across, 0u);
}

// examples/fluid_cases/hydrostatic_bed.toml with its lattice cut to one
// layer of 2 x 2 spheres of 0.49 mm, each made a dumbbell along x of the
// given template, in still water drained at the top. They sink onto the
// floor, the pore pressure their fall raised drains away, and at rest the
// floor carries their submerged weight, (rho_s - rho_f) g V per clump,
// within 0.5 % (issue 3's tolerance for the bed of spheres): the pore water
// acts on each member, buoyancy and drag, and each clump sums them. The
// fluid's solid is the clumps' volume V, to 1e-12 (the grid overlaps' own
// accuracy). (A stack of them would not do: a column of spheres on spheres
// topples, its lean growing as exp(t sqrt(g / r)), with clumps or without.)
void clumps_rest_in_water(const std::string& name, const std::string& spheres, double volume) {
  const std::string dir = temp_dir(name);
  Scene<3> scene = scene_from_text<3>(
      dir, "bed.toml",
      scene_variant(
          "examples/fluid_cases/hydrostatic_bed.toml",
          {{"[[particles]]",
            "[[clump_template]]\nname = \"dumbbell\"\nspheres = " + spheres + "\n\n[[particles]]"},
           {"min = [0.0, 0.0, 0.0]\nmax = [0.006, 0.006, 0.008]",
            "min = [0.002, 0.002, 0.0]\nmax = [0.004, 0.004, 0.001]"},
           {"radius = 0.00049", "radius = 0.00049\nclump = \"dumbbell\"\norientation = \"aligned\""}}));
  scene.simulation.track_energy = true;
  RunOptions options;
  options.out_dir = dir + "/out";
  ASSERT_FALSE(run_scene<3>(scene, options).interrupted);
  const auto& sim = scene.simulation;
  ASSERT_EQ(sim.clumps.size(), 4u);
  // The energy budget closes with the water's work on the clumps, as for
  // loose grains (1e-9 of gravity's work; the turns' error of the tumble is
  // below it). The water's work is its buoyancy's, rho_f / rho_s of
  // gravity's on each member's share against it, plus its drag's and the
  // excess pressure's, which resist the fall: at most -rho_f / rho_s of
  // gravity's work (measured 0.383 and 0.381 against 0.377).
  const double ratio = scene.fluid->fluid.density / sim.materials[0].density;
  EXPECT_LT(sim.energy.field_work, -ratio * sim.energy.gravity_work);
  EXPECT_LT(std::abs(sim.unaccounted_energy()), 1e-9 * sim.energy.gravity_work);
  std::printf("%s: energy unaccounted %.2e of gravity's work, the water's %.3g of it\n", name.c_str(),
              sim.unaccounted_energy() / sim.energy.gravity_work,
              sim.energy.field_work / sim.energy.gravity_work);
  EXPECT_EQ(sim.contact_count(), 8u);  // each member on the floor
  // The scene's sand (2650 kg/m^3) in its water (1000).
  const double submerged = 4.0 * (sim.materials[0].density - scene.fluid->fluid.density) * 9.80665 * volume;
  const double floor = -sim.walls[0].force.z();
  std::printf("%s: floor %.6e N, submerged weight %.6e N (%+.2e); kinetic energy %.3g J\n", name.c_str(),
              floor, submerged, floor / submerged - 1.0, sim.kinetic_energy());
  EXPECT_NEAR(floor, submerged, 0.005 * submerged);
  double solid = 0.0;
  for (double v : scene.fluid->solid_volume()) solid += v;
  EXPECT_NEAR(solid / (4.0 * volume), 1.0, 1e-12);
  const double stress = submerged / (0.006 * 0.006);
  // Drained: the excess pressure of their fall (0.3 Pa, above the floor's
  // stress) is below 1e-3 of that stress by the end (measured 4e-4 at 0.1 s
  // and still falling: few grains in cells of 2 mm let the water through
  // slowly to the drained top, 8 mm up).
  for (double u : scene.fluid->pressure()) EXPECT_LT(std::abs(u), 1e-3 * stress);
}

// Two touching spheres of radius 0.245 mm (measured 5e-9).
TEST(Clump, ClumpsInStillWaterRestWithTheirSubmergedWeight) {
  clumps_rest_in_water("clump_bed", "[[-1.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, 1.0]]",
                       2.0 * particle_volume<3>(0.245e-3));
}

// Two spheres of radius a = 0.49 / 1.5 mm a apart: the union's volume, 14 %
// less than the members' (the lens counted once); each member's buoyancy
// and solid its share.
TEST(Clump, ClumpsOfOverlappingSpheresInStillWaterRestWithTheirSubmergedWeight) {
  const double a = 0.49e-3 / 1.5;
  clumps_rest_in_water("overlapping_clump_bed", "[[-0.5, 0.0, 0.0, 1.0], [0.5, 0.0, 0.0, 1.0]]",
                       two_balls(a, a).volume);
}

}  // namespace
}  // namespace darcydem
