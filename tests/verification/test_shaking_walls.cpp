// Walls that oscillate (YADE's HarmonicMotionEngine, a shaking table),
// against hand derivations. A grain on a floor shaken vertically,
// y_f = A (1 - cos(omega t)) (phase -90 degrees: the floor starts at rest),
// rides on it while the floor's acceleration A omega^2 cos(omega t) stays
// above -g: the floor carries m (g + a_f). With Gamma = A omega^2 / g > 1 it
// leaves the floor where cos(omega t) = -1/Gamma, at the floor's speed then,
// flies freely and lands where its parabola meets the floor's sine again.
// And examples/dem_cases/vibrated_bed.toml: a bed of discs shaken so flies
// as that grain does (the completely inelastic bouncing ball).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "dem_setup.hpp"
#include "scene_loading.hpp"

using namespace darcydem;
using darcydem::testing::particle_on_floor;

namespace {

constexpr double g = 9.81;
constexpr double r = 5e-4;
constexpr double frequency = 20.0;  // Hz
constexpr double omega = 2.0 * std::numbers::pi * frequency;

/// particle_on_floor (resting overlap 1e-4 r; restitution 0.5) with the
/// floor shaken vertically at Gamma, starting at rest.
template <int D>
Simulation<D> shaken_grain(double gamma) {
  ContactSpec spec;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  auto sim = particle_on_floor<D>(spec, r, 0.0, g);
  Wall<D>& floor = sim.walls[0];
  floor.oscillation.amplitude[D - 1] = gamma * g / (omega * omega);
  floor.oscillation.frequency = frequency;
  floor.oscillation.phase = -0.5 * std::numbers::pi;
  sim.prepare();
  return sim;
}

/// The floor's height at time t, m.
double floor_height(double amplitude, double t) { return amplitude * (1.0 - std::cos(omega * t)); }

/// Where a grain that left the floor at omega t = arccos(-g / (A omega^2))
/// at the floor's speed lands on it again: its parabola meets the floor's
/// sine, found by bisection between a twentieth of a period after the
/// lift-off and a whole period after it. Returns the time, s.
double landing_time(double amplitude) {
  const double t_left = std::acos(-g / (amplitude * omega * omega)) / omega;
  const double v = amplitude * omega * std::sin(omega * t_left);
  const double y0 = floor_height(amplitude, t_left);
  auto above = [&](double t) {
    const double s = t - t_left;
    return y0 + v * s - 0.5 * g * s * s - floor_height(amplitude, t);
  };
  double lo = t_left + 0.05 / frequency;
  double hi = t_left + 1.0 / frequency;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (above(mid) > 0.0 ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

TEST(ShakingWalls, TheWallIsWhereTheSinePutsItStepAfterStep) {
  // A box shaken along a slanted direction at 7 Hz from phase 30 degrees,
  // on top of a drift: after 10^5 steps of an awkward length it is at
  // x0 + v t + A (sin(omega t + phase) - sin(phase)). The sum of the steps'
  // moves telescopes, so only round-off is left: 1e-12 of the amplitude
  // per 1000 steps, 1e-10 here.
  Wall<2> w;
  w.shape = WallShape::box;
  w.point = Vec<2>(0.1, 0.2);
  w.pivot = w.point;
  w.motion = WallMotion::velocity;
  w.velocity = Vec<2>(0.01, 0.0);
  w.oscillation.amplitude = Vec<2>(3e-3, -4e-3);
  w.oscillation.frequency = 7.0;
  w.oscillation.phase = std::numbers::pi / 6.0;
  w.oscillation.start = 0.25;
  const double dt = 1.234567e-5;
  double t = 0.25;
  for (int s = 0; s < 100000; ++s) {
    w.advance(dt, t);
    t += dt;
  }
  const double angle = 2.0 * std::numbers::pi * 7.0 * (t - 0.25) + std::numbers::pi / 6.0;
  const Vec<2> expected =
      Vec<2>(0.1, 0.2) + (t - 0.25) * w.velocity + w.oscillation.amplitude * (std::sin(angle) - 0.5);
  EXPECT_NEAR((w.point - expected).norm(), 0.0, 1e-10 * 5e-3);
  EXPECT_NEAR((w.pivot - w.point).norm(), 0.0, 1e-15);
  // Its velocity over the last step: the drift plus the sine's mean slope
  // over the step, A (sin(end) - sin(start)) / dt (round-off of a
  // difference of 5e-3 m over 1.2e-5 s, and of the time summed 10^5
  // times: below 1e-10 m/s).
  const double before = angle - 2.0 * std::numbers::pi * 7.0 * dt;
  const Vec<2> slope = w.oscillation.amplitude * (std::sin(angle) - std::sin(before)) / dt;
  EXPECT_NEAR((w.translation_velocity() - w.velocity - slope).norm(), 0.0, 1e-10);
  EXPECT_NEAR((w.surface_velocity(Vec<2>(1.0, 1.0)) - w.translation_velocity()).norm(), 0.0, 0.0);
}

TEST(ShakingWalls, AGrainRidesAFloorShakenBelowOneG) {
  // Gamma = 0.5: the grain never leaves, and the floor carries
  // m (g + A omega^2 cos(omega t)), from 0.5 m g to 1.5 m g. The
  // contact's own dynamics (its natural frequency 280 times the shaking's)
  // and the dashpot's share, c times the overlap's rate, are below 1e-3 m g
  // (measured 4e-5) once the start's jolt (the acceleration's jump to
  // A omega^2) has died away, a tenth of a period in.
  for (const int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    auto run = [&]<int D>(Simulation<D> sim) {
      const double m = 1.0 / sim.particles.inv_mass[0];
      const double a = 0.5 * g / (omega * omega);
      double worst = 0.0;
      double lowest = 1e9;
      while (sim.time < 2.0 / frequency) {
        sim.advance(10);
        const double load = -sim.walls[0].force[D - 1];
        lowest = std::min(lowest, load);
        if (sim.time < 0.1 / frequency) continue;
        const double expected = m * (g + a * omega * omega * std::cos(omega * sim.time));
        worst = std::max(worst, std::abs(load - expected) / (m * g));
      }
      std::printf(
          "grain on a floor shaken at Gamma 0.5 (%dD): floor load within %.2e m g of m (g + a_f); "
          "lowest %.4f m g\n",
          D, worst, lowest / (m * g));
      EXPECT_LT(worst, 1e-3);
      EXPECT_GT(lowest, 0.45 * m * g);
    };
    if (dimension == 2) run(shaken_grain<2>(0.5));
    if (dimension == 3) run(shaken_grain<3>(0.5));
  }
}

TEST(ShakingWalls, AGrainLeavesAFloorShakenAtTwoGWhereItsPullPassesG) {
  // Gamma = 2: the floor's acceleration falls to -g at omega t = arccos(-1/2)
  // = 120 degrees; there the grain leaves it at the floor's speed
  // A omega sin(120 deg), rises v^2 / 2g above where it left, and lands where
  // y_L + v s - g s^2 / 2 meets the floor's height (found here by bisection).
  // The lift-off is taken at the first step with no contact force: the
  // spring unloads with the floor (its natural period 1/280 of the
  // shaking's: a lag of order 1/280 of a radian at most) and the dashpot
  // makes the force vanish a little early, so the phase is bound to
  // 1e-3 rad (measured 2e-5); the flight is free fall (exact in velocity
  // Verlet) from the resting overlap's height (5e-5 of the rise), so the
  // apex is bound to 1e-3 (measured 1.8e-4) and the landing to five time
  // steps (measured one: contact is found at the step's end). A surface
  // that did not move with the shaking would have the dashpot resist the
  // floor's whole speed, hundreds of m g: the grain would be thrown.
  for (const int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    auto run = [&]<int D>(Simulation<D> sim) {
      const double amplitude = 2.0 * g / (omega * omega);
      double left = -1.0;
      double y_left = 0.0;
      double apex = -1e9;
      double landed = -1.0;
      while (sim.time < 1.5 / frequency && landed < 0.0) {
        sim.advance(1);
        const bool touching = sim.walls[0].force.squaredNorm() > 0.0;
        const double y = sim.particles.position[0][D - 1];
        if (left < 0.0 && !touching && sim.time > 0.1 / frequency) {
          left = sim.time;
          y_left = y;
        }
        if (left > 0.0) {
          apex = std::max(apex, y - y_left);
          if (touching) landed = sim.time;
        }
      }
      const double phase = std::acos(-0.5);
      const double v = amplitude * omega * std::sin(phase);
      const double lo = landing_time(amplitude);
      std::printf(
          "grain on a floor shaken at Gamma 2 (%dD): leaves %.2e rad after arccos(-1/2), rises "
          "%.4e m (v^2/2g %.4e), lands %.2e s after the parabola meets the floor (step %.1e s)\n",
          D, omega * left - phase, apex, v * v / (2.0 * g), landed - lo, sim.time_step);
      EXPECT_NEAR(omega * left, phase, 1e-3);
      EXPECT_NEAR(apex, v * v / (2.0 * g), 1e-3 * v * v / (2.0 * g));
      EXPECT_NEAR(landed, lo, 5.0 * sim.time_step);
    };
    if (dimension == 2) run(shaken_grain<2>(2.0));
    if (dimension == 3) run(shaken_grain<3>(2.0));
  }
}

TEST(ShakingWalls, TheEnergyBudgetCountsTheShakingFloorsWork) {
  // The bouncing grain for two periods with the budget on: the floor's
  // work (its force times its move, step by step) feeds the grain's
  // kinetic and potential energy and what the contact takes; the budget
  // closes to round-off, 1e-9 of the work done. A floor whose work were
  // left out would leave the whole of it unaccounted.
  auto sim = shaken_grain<3>(2.0);
  sim.track_energy = true;
  sim.advance(static_cast<std::uint64_t>(2.0 / frequency / sim.time_step));
  const auto& e = sim.energy;
  const double unaccounted = sim.unaccounted_energy();
  std::printf(
      "shaken grain's energy budget: boundary work %.4e J, contact dissipation %.4e J, unaccounted "
      "%.2e J\n",
      e.boundary_work, sim.contact_dissipation(), unaccounted);
  EXPECT_GT(e.boundary_work, 0.0);
  EXPECT_GT(sim.contact_dissipation(), 0.0);
  EXPECT_LT(std::abs(unaccounted), 1e-9 * e.boundary_work);
}

TEST(ShakingWalls, TheVibratedBedExampleFliesAsAnInelasticBall) {
  // examples/dem_cases/vibrated_bed.toml: 80 discs settled on a floor that
  // then shakes at 20 Hz, Gamma = 2, from t = 0.3 s (the settling stage, to
  // a step of 4.3e-6 s). A bed that rode the floor as a rigid body, and
  // stuck to it on landing, would leave it at omega t = arccos(-1/2) and
  // land where the grain of the test above does (the completely inelastic
  // bouncing ball): 6.7534 rad, half a radian into the next cycle. The bed
  // is no rigid body: its grains rattle, and it leaves the floor over a
  // few probe intervals (0.025 rad each) as its contacts unload from the
  // bottom up, so its last touch before the flight is bound to within
  // 0.25 rad after arccos(-1/2) (measured 0.17); the flight itself is the
  // free fall of its centre of mass, so the landing is bound to 0.1 rad
  // (measured 0.04 early).
  const std::string text = darcydem::testing::scene_variant("examples/dem_cases/vibrated_bed.toml", {});
  const auto probes = darcydem::testing::run_scene_probes<2>("vibrated_bed", text);
  const auto& time = probes.at("time");
  const auto& load = probes.at("floor_load");
  const double start = 0.3;
  const double lift = std::acos(-0.5);
  // The first flight: the longest run of probes without a floor load in
  // the first cycle and a half.
  double best_from = 0.0;
  double best_to = 0.0;
  double from = -1.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    const double phase = omega * (time[k] - start);
    if (phase < 0.5 || phase > 3.0 * std::numbers::pi) continue;
    const bool touching = load[k] != 0.0;
    if (!touching && from < 0.0) from = phase;
    if (touching && from >= 0.0) {
      if (phase - from > best_to - best_from) {
        best_from = from;
        best_to = phase;
      }
      from = -1.0;
    }
  }
  // The ball's landing, as in the grain's test (A = 1.2425 mm: Gamma
  // 2.0000 at 20 Hz).
  const double lo = landing_time(0.0012425);
  std::printf(
      "vibrated bed: leaves the floor at %.3f rad (a rigid ball: %.3f), lands at %.3f rad (an inelastic "
      "ball: %.4f)\n",
      best_from, lift, best_to, omega * lo);
  EXPECT_GT(best_from, lift - 0.03);
  EXPECT_LT(best_from, lift + 0.25);
  EXPECT_NEAR(best_to, omega * lo, 0.1);
}
