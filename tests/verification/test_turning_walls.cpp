// Plane and box walls that turn about a rotation centre (PFC's wall spin,
// YADE's RotationEngine), against hand derivations: a tilting table lets a
// grain that cannot roll slide once its tilt reaches atan(mu); a turntable
// carries a grain round at its own rate while the friction can hold it,
// omega^2 r < mu g, and flings it outwards above that; a turning paddle
// throws a free grain at (1 + e) times the speed of its face, and the
// energy budget counts the paddle's work as the moment on it times the
// angle it turned. And examples/dem_cases/tilting_table.toml: a bonded
// block slides at atan(mu), and the table carries its weight.
#include <gtest/gtest.h>

#include <algorithm>
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

/// The tilt at which a grain on a table turning at omega about a
/// horizontal line through the origin starts to slide: the table is the
/// floor of particle_on_floor (resting overlap 1e-3 r here), the grain L
/// from the line. Its rolling resistance (mu_r = 2 mu) keeps it from
/// rolling, so it slides once tan(theta) = mu. Returns the tilt, rad,
/// estimated from the time its slip down the table reaches `slip`:
/// past the onset theta_s, the downhill pull is
/// g (sin theta - mu cos theta) = g sqrt(1 + mu^2) sin(theta - theta_s),
/// so the slip is g sqrt(1 + mu^2) omega tau^3 / 6 after a time tau.
template <int D>
double sliding_tilt(double mu, double omega, double arm, double slip) {
  ContactSpec spec;
  spec.friction = mu;
  spec.rolling_friction = 2.0 * mu;
  spec.restitution = 0.5;
  auto sim = particle_on_floor<D>(spec, r, 0.0, g);
  // Ten times softer than particle_on_floor's (overlap 1e-3 r), dt as it
  // scales: about 1.5e5 steps to the onset.
  const double m = 2500.0 * particle_volume<D>(r);
  spec.normal_stiffness = m * g / (1e-3 * r);
  sim.contact_table.set(0, 0, make_pair_parameters(sim.materials[0], sim.materials[0], spec));
  sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
  sim.particles.position[0][0] = arm;
  sim.particles.position[0][D - 1] = r - 1e-3 * r;
  Wall<D>& table = sim.walls[0];
  table.pivot = Vec<D>::Zero();
  table.spin = omega;
  // 3D: about -y, so that x goes up as in 2D (counter-clockwise about z).
  if constexpr (D == 3) table.axis = Vec<3>(0.0, -1.0, 0.0);
  sim.prepare();
  const double onset = std::atan(mu);
  double found = std::nan("");
  while (sim.time < (onset + 0.1) / omega) {
    sim.advance(10);
    const double theta = omega * sim.time;
    // The table's own axes now: along it (up the slope from the line), and
    // its normal; the wall's must be the rotation's to round-off.
    Vec<D> along = Vec<D>::Zero();
    Vec<D> up = Vec<D>::Zero();
    along[0] = std::cos(theta);
    along[D - 1] = std::sin(theta);
    up[0] = -std::sin(theta);
    up[D - 1] = std::cos(theta);
    EXPECT_NEAR((table.normal - up).norm(), 0.0, 1e-10);
    // Its slip down the table from where it sat: the spring's deflection
    // before it slides is m g sin(theta) / k_t < 1e-3 r (0.5 um).
    const double down = arm - sim.particles.position[0].dot(along);
    if (down > slip) {
      const double tau = std::cbrt(6.0 * slip / (g * std::sqrt(1.0 + mu * mu) * omega));
      found = theta - omega * tau;
      break;
    }
  }
  return found;
}

}  // namespace

TEST(TurningWalls, ATiltingTableLetsAGrainSlideAtTheFrictionAngle) {
  // A grain 5 mm from the line the table turns about, at 0.2 rad/s: the
  // carrying round is slow (omega^2 L = 2e-5 g). The estimate's error: the
  // pull's growth is taken as linear in the tilt (sin, 1e-6 over the
  // 0.01 rad the 20 um slip takes), the spring's give before the onset
  // (0.5 um of the 20, 1e-4 rad in the estimate) and the step's: 1e-3 rad
  // (0.06 degrees) covers them. A table that did not turn, or turned the
  // grain with it the wrong way, leaves it at rest or slides it at once.
  for (const double mu : {0.3, 0.6}) {
    SCOPED_TRACE(mu);
    const double expected = std::atan(mu);
    const double t2 = sliding_tilt<2>(mu, 0.2, 5e-3, 2e-5);
    const double t3 = sliding_tilt<3>(mu, 0.2, 5e-3, 2e-5);
    std::printf("tilting table, mu %.1f: slides at %.5f rad (2D), %.5f (3D); atan(mu) = %.5f\n", mu, t2, t3,
                expected);
    EXPECT_NEAR(t2, expected, 1e-3);
    EXPECT_NEAR(t3, expected, 1e-3);
  }
}

namespace {

struct Carried {
  double rate = 0.0;    ///< rad/s, the grain's mean angular speed about the table's axis
  double radius = 0.0;  ///< m, from the axis at the end
  double drift = 0.0;   ///< m, the change of that distance from t1 to the end
  double time_step = 0.0;
};

/// A grain on a horizontal table (3D) turning about the vertical axis
/// through the origin at omega from t = 0, placed at rest at r0 from the
/// axis; its rolling resistance mu_r = 2 mu keeps it from rolling. Its mean
/// angular speed about the axis from t1 to t2.
Carried turntable(double mu, double omega, double r0, double t1, double t2) {
  ContactSpec spec;
  spec.friction = mu;
  spec.rolling_friction = 2.0 * mu;
  spec.restitution = 0.5;
  auto sim = particle_on_floor<3>(spec, r, 0.0, g);
  const double m = 2500.0 * particle_volume<3>(r);
  spec.normal_stiffness = m * g / (1e-3 * r);
  sim.contact_table.set(0, 0, make_pair_parameters(sim.materials[0], sim.materials[0], spec));
  sim.time_step = 0.05 * std::sqrt(m / spec.normal_stiffness);
  sim.particles.position[0] = Vec<3>(r0, 0.0, r - 1e-3 * r);
  Wall<3>& table = sim.walls[0];
  table.pivot = Vec<3>::Zero();
  table.spin = omega;
  table.axis = Vec<3>(0.0, 0.0, 1.0);
  sim.prepare();
  double turned = 0.0;
  double angle = 0.0;
  double start = 0.0;
  double start_radius = 0.0;
  while (sim.time < t2) {
    sim.advance(10);
    const Vec<3>& x = sim.particles.position[0];
    const double a = std::atan2(x.y(), x.x());
    double step = a - angle;
    step -= 2.0 * std::numbers::pi * std::round(step / (2.0 * std::numbers::pi));
    angle = a;
    turned += step;
    if (start == 0.0 && sim.time >= t1) {
      start = turned;
      start_radius = std::hypot(x.x(), x.y());
    }
  }
  // The table stays a table: turning about its own normal moves none of it.
  EXPECT_NEAR((table.normal - Vec<3>(0.0, 0.0, 1.0)).norm(), 0.0, 1e-12);
  const Vec<3>& x = sim.particles.position[0];
  const double radius = std::hypot(x.x(), x.y());
  return {(turned - start) / (t2 - t1), radius, radius - start_radius, sim.time_step};
}

}  // namespace

TEST(TurningWalls, ATurntableCarriesAGrainRoundWhileItsFrictionCanHoldIt) {
  // At 5 mm from the axis, mu = 0.5: omega^2 r0 = 0.2 g needs 0.4 of the
  // friction the contact has. The grain slides until it moves with the
  // table (omega r0 / (mu g) = 0.02 s), then goes round at omega: the
  // contact's tangential spring, which keeps its direction unless the
  // grain slips, lags it by (omega / omega_t)^2 = 2e-5 of omega, and its
  // ringing, about 1e-5 rad, is 1e-4 of the turn it is measured over
  // (0.1 to 0.4 s, about one turn): 1e-3. A table whose turn did not move
  // its surface would leave the grain where it is.
  const double r0 = 5e-3;
  const double mu = 0.5;
  const double omega = std::sqrt(0.2 * g / r0);
  const Carried held = turntable(mu, omega, r0, 0.1, 0.4);
  // At 0.8 g, past mu g, nothing holds it: it slides outwards (and off).
  const double fast = std::sqrt(0.8 * g / r0);
  const Carried flung = turntable(mu, fast, r0, 0.1, 0.2);
  std::printf(
      "turntable at %.6f rad/s: the grain goes round at %.6f rad/s, %.6f mm from the axis (r0 %.1f mm, "
      "%.4e mm more than at 0.1 s; omega^2 r dt / 2 x 0.3 s = %.4e mm); at %.3f rad/s it is %.3f mm out "
      "after "
      "0.2 s\n",
      omega, held.rate, held.radius * 1e3, r0 * 1e3, held.drift * 1e3,
      omega * omega * held.radius * 0.5 * held.time_step * 0.3 * 1e3, fast, flung.radius * 1e3);
  EXPECT_NEAR(held.rate, omega, 1e-3 * omega);
  // While it caught up it slid (omega r0)^2 / (2 mu g) = 0.2 r0, across
  // the radius mostly; held, it stays where it is on the table: the
  // spring's give, m omega^2 r0 / k_t = 1e-3 r0 0.2 ... 2e-4 r0 at most.
  EXPECT_NEAR(held.radius, r0, 0.2 * r0);
  // Held, it would stay where it is on the table, but the contact's
  // springs grow with the relative velocity at the half step, which lags
  // the grain's turn by omega dt / 2: an apparent slip outwards at
  // omega^2 r dt / 2, which the spring's damping turns into a creep
  // inwards at that speed (1.1e-5 m/s here; first order in the step, as
  // in PFC, whose force-displacement law takes the same velocity).
  // Measured to 1e-3 of it; 2 %, the radius's change over the window
  // being 7e-4 of it.
  const double creep = -omega * omega * held.radius * 0.5 * held.time_step * 0.3;
  EXPECT_NEAR(held.drift, creep, 0.02 * std::abs(creep));
  EXPECT_GT(flung.radius, 2.0 * r0);
}

TEST(TurningWalls, ATurningPaddleThrowsAGrainAtItsFacesSpeedAndTheBudgetCountsItsWork) {
  // A 2D paddle, 25 mm by 1 mm, turning counter-clockwise about its end at
  // the origin at omega; a free disc, no gravity, 20 mm out and 0.5 r
  // above its face (more than the skin: the paddle's turn must bring it
  // into the contact list). The face under the disc moves along its
  // normal at omega s, s the contact's distance along the paddle from the
  // centre: L cos(theta) + y sin(theta), theta the paddle's tilt when it
  // hits (about 0.5 r / L), y the disc's height; 7e-4 more than L. Elastic
  // and frictionless, the disc leaves at (1 + e) omega s along that
  // normal, to the turn while they touch (omega t_c = 1e-4). The budget counts the paddle's work as the
  // moment of the disc's push about the rotation centre times the angle turned: with e = 1, the disc's
  // kinetic energy; with e = 0.5, that and the contact's loss.
  const double arm = 2e-2;
  const double omega = 2.0;
  const double speed = omega * arm;
  const double m = 2650.0 * particle_volume<2>(r);
  for (const double e : {1.0, 0.5}) {
    SCOPED_TRACE(e);
    ContactSpec spec;
    spec.normal_stiffness = m * speed * speed / (1e-3 * r * 1e-3 * r);
    spec.restitution = e;
    auto sim = darcydem::testing::single_material<2>(2650.0, spec);
    Wall<2> paddle;
    paddle.name = "paddle";
    paddle.shape = WallShape::box;
    paddle.point = Vec<2>(12.5e-3, 0.0);
    paddle.half = Vec<2>(12.5e-3, 0.5e-3);
    paddle.pivot = Vec<2>::Zero();
    paddle.spin = omega;
    sim.walls.push_back(paddle);
    sim.particles.add(Vec<2>(arm, 0.5e-3 + 1.5 * r), r, 2650.0, 0, false);
    sim.time_step = 0.01 * std::sqrt(m / spec.normal_stiffness);
    sim.track_energy = true;
    sim.prepare();
    // It is hit after about 0.5 r / (omega L) and is clear 3 r later.
    while (sim.time < 4.0 * r / speed) sim.advance(100);
    // The tilt at which the face, h/2 above the paddle's line, comes to r
    // from the disc's centre (L, y): y cos(theta) - L sin(theta) = h/2 + r.
    const double y = 0.5e-3 + 1.5 * r;
    const double tilt = std::acos((0.5e-3 + r) / std::hypot(y, arm)) - std::atan2(arm, y);
    const double s = arm * std::cos(tilt) + y * std::sin(tilt);
    const Vec<2> v = sim.particles.velocity[0];
    const double ke = 0.5 * m * v.squaredNorm();
    std::printf(
        "paddle (e %.1f): hit at a tilt of %.5f rad, the disc leaves at %.6f m/s ((1 + e) omega s = %.6f), "
        "at %.2e rad from the paddle's normal; boundary work %.6e J/m, kinetic %.6e, dissipated %.6e\n",
        e, tilt, v.norm(), (1.0 + e) * omega * s, std::atan2(-v.x(), v.y()) - tilt, sim.energy.boundary_work,
        ke, sim.contact_dissipation());
    // The dashpot (e = 0.5) meets the leapfrog's first-order error, omega
    // dt = 0.01 x its share, as for the cylinder's (test_energy_budget):
    // 5e-3 there.
    EXPECT_NEAR(v.norm(), (1.0 + e) * omega * s, (e == 1.0 ? 3e-4 : 5e-3) * (1.0 + e) * speed);
    // Along the normal it was hit with, to the turn while they touch.
    EXPECT_NEAR(std::atan2(-v.x(), v.y()), tilt, 1e-3);
    const double given = 0.5 * m * (1.0 + e) * (1.0 + e) * speed * speed;
    // Without the moment's work the budget would miss all of it.
    EXPECT_NEAR(sim.energy.boundary_work, ke + sim.contact_dissipation(), 1e-4 * given);
    if (e == 1.0) {
      EXPECT_NEAR(sim.contact_dissipation(), 0.0, 1e-4 * given);
    }
    // The paddle turned on at its own rate: 2 rad/s for the run's time.
    const double angle = omega * sim.time;
    EXPECT_NEAR(sim.walls[0].axes(1, 0), std::sin(angle), 1e-10);
    EXPECT_NEAR(sim.walls[0].point.x(), 12.5e-3 * std::cos(angle), 1e-10 * 12.5e-3);
  }
}

TEST(TurningWalls, TheTiltingTableExampleSlidesItsBlockAtTheInterfacesFrictionAngle) {
  // examples/dem_cases/tilting_table.toml: a rigid block of 15 bonded discs
  // on a table turning at 0.1 rad/s about its left end from t = 0.05 s,
  // friction 0.4 between them.
  const std::string text = darcydem::testing::scene_variant("examples/dem_cases/tilting_table.toml", {});
  const auto probes = darcydem::testing::run_scene_probes<2>("tilting_table", text);
  const auto& time = probes.at("time");
  const auto& x0 = probes.at("x0");
  const auto& y0 = probes.at("y0");
  const auto& torque = probes.at("torque");
  const double omega = 0.1;
  const double start = 0.05;  // the settling stage, to a step (8e-6 s)
  const double mu = 0.4;
  // While it holds, the table carries the block's weight on the vertical
  // through its centre of mass, which turns with the table from (19, 3) mm:
  // the moment about the pivot is -M g (19 cos - 3 sin) mm. Off by the
  // contacts' give under the weight (2.4e-7 m of the 19 mm) and the
  // block's own turn (omega^2 x 19 mm = 2e-5 g): 2e-4.
  const double mass = 15.0 * 2650.0 * std::numbers::pi * 1e-6;
  double worst = 0.0;
  double onset = std::nan("");
  double s_held = 0.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    const double tilt = std::max(0.0, omega * (time[k] - start));
    if (time[k] < 0.04) continue;  // settling
    const double expected = -mass * g * (19e-3 * std::cos(tilt) - 3e-3 * std::sin(tilt));
    // The table's start jolts the block (its surface under it starts at
    // 2 mm/s), which rings for about 0.05 s, its contacts' damping: from
    // 0.1 s on.
    if (tilt < 0.35 && (time[k] < start || time[k] > start + 0.1)) {
      worst = std::max(worst, std::abs(torque[k] / expected - 1.0));
      EXPECT_NEAR(torque[k], expected, 2e-4 * std::abs(expected)) << "at a tilt of " << tilt;
    }
    // The first disc's place along the table, from the pivot; its slip
    // down it past the onset as in sliding_tilt (a rigid block slides as a
    // grain does).
    const double s = x0[k] * std::cos(tilt) + y0[k] * std::sin(tilt);
    if (time[k] < start) s_held = s;
    if (s_held - s > 2e-5) {
      const double tau = std::cbrt(6.0 * 2e-5 / (g * std::sqrt(1.0 + mu * mu) * omega));
      onset = tilt - omega * tau;
      break;
    }
  }
  std::printf(
      "tilting table example: the block slides at a tilt of %.5f rad (atan(mu) = %.5f); the "
      "table's moment within %.1e of -M g x_cm before\n",
      onset, std::atan(mu), worst);
  // As for the grain (sliding_tilt), and the probes' interval (1e-3 s,
  // 1e-4 rad): 1e-3 rad.
  EXPECT_NEAR(onset, std::atan(mu), 1e-3);
}
