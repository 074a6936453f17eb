// The critical time step against the stability of the integrator.
//
// A grain resting on a floor with undamped linear contacts has three
// oscillations: the normal spring on the mass (omega^2 = k_n/m), the
// sticking tangential spring, which also turns the grain (the contact point
// has the mass m/(1 + 1/alpha) with I = alpha m r^2, omega^2 =
// k_t (1 + 1/alpha)/m), and the rolling spring on the inertia (omega^2 =
// k_r/I with k_r = 2.25 k_n mu_r^2 r^2). Velocity Verlet, like leapfrog, is
// stable for dt omega < 2 and unstable above, where the amplitude grows by
// about 1.9 per step at dt omega = 2.1.
// Simulation::critical_time_step() is 1/omega of the fastest of them, half
// the stability limit of a grain on a wall, the same margin for every mode.
// Each case checks that closed form to round-off and that the simulation is
// stable at 0.95 x 2/omega and blows up at 1.05 x 2/omega, which shows that
// omega is the real frequency of the mode in the integrator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "dem_setup.hpp"

namespace darcydem {
namespace {

constexpr double kRadius = 1e-3;
constexpr double kGravity = 9.81;

enum class Mode { normal, tangential, rolling };

template <int D>
Simulation<D> grain_on_floor(Mode mode) {
  ContactSpec spec;  // restitution 1: no dashpots
  spec.tangential_stiffness_ratio = 0.8;
  if (mode == Mode::tangential) spec.friction = 10.0;  // sticks at any amplitude reached when stable
  if (mode == Mode::rolling) spec.rolling_friction = 1.5;
  // Kicked at 1e-6 m/s (normal or tangential) or 1e-4 rad/s (rolling): far
  // from any Coulomb or rolling limit while stable.
  auto sim = testing::particle_on_floor<D>(spec, kRadius, mode == Mode::tangential ? 1e-6 : 0.0, kGravity);
  if (mode == Mode::normal) sim.particles.velocity[0][D - 1] = -1e-6;
  if (mode == Mode::rolling) sim.particles.angular_velocity[0][0] = 1e-4;  // about x: rolling, no twist
  return sim;
}

template <int D>
double omega(const Simulation<D>& sim, Mode mode) {
  const double m = 1.0 / sim.particles.inv_mass[0];
  const PairParameters& pp = sim.contact_table(0, 0);
  const double alpha = inertia_factor<D>;
  switch (mode) {
    case Mode::normal:
      return std::sqrt(pp.normal_stiffness / m);
    case Mode::tangential:
      return std::sqrt(pp.tangential_ratio * pp.normal_stiffness * (1.0 + 1.0 / alpha) / m);
    case Mode::rolling:
      return std::sqrt(2.25 * pp.rolling_friction * pp.rolling_friction * pp.normal_stiffness / (alpha * m));
  }
  return 0.0;
}

// Largest kinetic energy over 400 steps of dt, relative to the start's.
template <int D>
double energy_growth(Simulation<D> sim, double dt) {
  sim.time_step = dt;
  sim.prepare();
  const double start = sim.kinetic_energy();
  double largest = start;
  for (int s = 0; s < 400; ++s) {
    sim.step();
    const double e = sim.kinetic_energy();
    if (!std::isfinite(e)) return e;
    largest = std::max(largest, e);
  }
  return largest / start;
}

template <int D>
void check_mode(Mode mode) {
  auto sim = grain_on_floor<D>(mode);
  const double w = omega(sim, mode);
  // The fastest mode here is the one kicked: 0.8 x 3.5 (spheres) or 0.8 x 3
  // (discs) > 1, 2.25 x 1.5^2 / alpha > 1.
  EXPECT_NEAR(sim.critical_time_step() * w, 1.0, 1e-12);
  // Stable: leapfrog's energy at dt omega = 1.9 swings to at most
  // 1/(1 - (dt omega/2)^2) = 10 times its mean (measured 1.0-1.4).
  // Unstable: grows ~1.9 per step until the Coulomb or rolling limit or the
  // loss of contact caps it (measured 4e6-1e10 times the start's).
  EXPECT_LT(energy_growth(sim, 0.95 * 2.0 / w), 20.0);
  const double unstable = energy_growth(sim, 1.05 * 2.0 / w);
  EXPECT_TRUE(!std::isfinite(unstable) || unstable > 1e4) << unstable;
}

TEST(CriticalStep, NormalSpringOfASphereOnAWall) { check_mode<3>(Mode::normal); }
TEST(CriticalStep, NormalSpringOfADiscOnAWall) { check_mode<2>(Mode::normal); }
TEST(CriticalStep, TangentialSpringTurnsTheSphere) { check_mode<3>(Mode::tangential); }
TEST(CriticalStep, TangentialSpringTurnsTheDisc) { check_mode<2>(Mode::tangential); }
TEST(CriticalStep, RollingSpringOfASphere) { check_mode<3>(Mode::rolling); }
TEST(CriticalStep, RollingSpringOfADisc) { check_mode<2>(Mode::rolling); }

// Friction and rolling resistance together: the turning stiffnesses add, an
// upper bound on the coupled mode's omega^2, so twice the critical step is
// still stable (at most 1/(1 - 0.95^2) ~ 10 swing at dt omega <= 1.9).
TEST(CriticalStep, FrictionAndRollingTogetherStayStable) {
  ContactSpec spec;
  spec.friction = 10.0;
  spec.rolling_friction = 1.0;
  auto sim = testing::particle_on_floor<3>(spec, kRadius, 1e-6, kGravity);
  sim.particles.angular_velocity[0][0] = 1e-4;
  EXPECT_LT(energy_growth(sim, 0.95 * 2.0 * sim.critical_time_step()), 20.0);
}

}  // namespace
}  // namespace darcydem
