// Bonds that carry a moment (YADE's cohesive moment law, PFC's parallel
// bond): the relative rotation of two bonded grains bends the bond, M_b =
// -k_b theta_b, and in 3D twists it, M_tw = -k_tw theta_tw, with
// k = ratio x k_n x R*^2. Checked against statics and dynamics derived by
// hand: a cantilever of grains sagging under its weight (each joint turned
// by the moment of the weight beyond it, and sheared by that weight), its
// root bond breaking in bending when gravity doubles, and a sphere twisting
// back and forth on its bond (a torsion pendulum) or spinning free once the
// twist passes the strength.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "../common/vtk_text.hpp"
#include "darcydem/simulation/runner.hpp"
#include "dem_setup.hpp"
#include "run_output.hpp"
#include "scene_loading.hpp"

namespace darcydem {
namespace {

constexpr double radius = 1e-3;     // m
constexpr double density = 2500.0;  // kg/m^3
constexpr double g = 9.81;          // m/s^2

template <int D>
double grain_mass() {
  return density * particle_volume<D>(radius);
}

/// A horizontal cantilever: a fixed grain at the origin and `count` free
/// grains along +x, neighbours overlapping by 1e-9 r (so that make_bonds
/// bonds them), gravity off. Bending ratio 1: k_b = k_n R*^2 = k_n r^2 / 4.
/// k_n is set so that the root joint turns by `root_turn` rad under the
/// weight (its moment m g r count^2, below).
template <int D>
Simulation<D> cantilever(int count, double root_turn, double bending_strength) {
  const double weight = grain_mass<D>() * g;
  const double k_b = weight * radius * count * count / root_turn;
  ContactSpec spec;
  spec.normal_stiffness = 4.0 * k_b / (radius * radius);
  spec.restitution = 0.5;
  spec.friction = 0.5;
  spec.bond_tensile_strength = 1e3 * count * weight;  // never reached here
  spec.bond_shear_strength = 1e3 * count * weight;
  spec.bond_bending_stiffness_ratio = 1.0;
  spec.bond_bending_strength = bending_strength;
  auto sim = testing::single_material<D>(density, spec);
  for (int k = 0; k <= count; ++k) {
    Vec<D> x = Vec<D>::Zero();
    x[0] = k * 2.0 * radius * (1.0 - 0.5e-9);
    sim.particles.add(x, radius, density, 0, k == 0, Vec<D>::Zero());
  }
  sim.time_step = 0.05 * std::sqrt(grain_mass<D>() / spec.normal_stiffness);
  return sim;
}

/// The sag of grain k (1..count) at rest, by hand (small deflections): joint
/// k (the bond between grains k-1 and k, at x = (2k - 1) r) carries the
/// weight beyond it, V_k = (count - k + 1) m g, in shear, and its moment
/// about the joint, M_k = m g r sum_{j>=k} (2(j - k) + 1) = m g r (count-k+1)^2.
/// The joint turns by theta_k = M_k / k_b and slips by delta_k = V_k / k_t, so
/// grain k turns by phi_k = phi_{k-1} + theta_k and sinks by
/// w_k = w_{k-1} + r phi_{k-1} + r phi_k + delta_k (its centre is r beyond
/// the joint, grain k-1's r before it).
std::vector<double> cantilever_sag(int count, double weight, double k_n) {
  const double k_b = k_n * radius * radius / 4.0;
  const double k_t = k_n;  // tangential_stiffness_ratio 1
  std::vector<double> w(static_cast<std::size_t>(count) + 1, 0.0);
  double phi = 0.0;
  for (int k = 1; k <= count; ++k) {
    const double beyond = count - k + 1;
    const double theta = weight * radius * beyond * beyond / k_b;
    const double phi_k = phi + theta;
    w[k] = w[k - 1] + radius * (phi + phi_k) + beyond * weight / k_t;
    phi = phi_k;
  }
  return w;
}

/// Viscous damping at twice the critical rate of the cantilever's slowest
/// mode, estimated from its tip sag (omega^2 ~ g / w_tip): every mode then
/// decays at least as exp(-omega t).
double settling_rate(double tip_sag) { return 2.0 * std::sqrt(g / tip_sag); }

// The root joint turns by 1e-5 rad: the geometric (second-order) errors of
// the small-deflection sag are about phi_tip^2 ~ 1e-9 of it.
//
// With `skin` tiny (a few nm, against a tip sag of about 0.4 um) the lists
// are rebuilt hundreds of times while it settles: the bonds' bending must
// be carried over at every build, or the joints would come to rest turned
// further each time their spring started afresh.
template <int D>
void cantilever_sags_as_its_joints_bend(double skin) {
  const int count = 10;
  auto sim = cantilever<D>(count, 1e-5, 1.0);
  sim.skin = skin;
  sim.prepare();
  ASSERT_EQ(sim.make_bonds(), static_cast<std::size_t>(count));
  const auto sag = cantilever_sag(count, grain_mass<D>() * g, sim.contact_table(0, 0).normal_stiffness);
  sim.gravity[D - 1] = -g;
  sim.damping.viscous = settling_rate(sag[count]);
  // 40 e-foldings of the slowest mode.
  const auto steps = static_cast<std::uint64_t>(40.0 / (0.5 * sim.damping.viscous * sim.time_step));
  sim.advance(steps);
  EXPECT_EQ(sim.bond_count(), static_cast<std::size_t>(count));
  EXPECT_EQ(sim.broken_bonds, 0U);
  if (skin > 0.0) {
    EXPECT_GT(sim.list_builds(), 100U);
  }
  // The bending makes the sag: without it (a pin) the cantilever would
  // fold; the joints' shear alone is count m g / k_t at the tip.
  EXPECT_GT(sag[count], 100.0 * count * grain_mass<D>() * g / sim.contact_table(0, 0).normal_stiffness);
  for (int k = 1; k <= count; ++k) {
    // Bound 1e-6 of each sag: the geometric errors are ~1e-9 and the
    // damped motion has decayed by e^-40.
    EXPECT_NEAR(-sim.particles.position[k][D - 1], sag[k], 1e-6 * sag[k]) << "grain " << k;
  }
  if constexpr (D == 3) {
    // Loaded in the x-z plane: nothing turns it out of that plane.
    for (int k = 1; k <= count; ++k) EXPECT_LT(std::abs(sim.particles.position[k][1]), 1e-6 * sag[1]);
  }
}

TEST(BondMoments, CantileverOfDiscsSagsAsItsJointsBendAndShear) {
  cantilever_sags_as_its_joints_bend<2>(0.0);
}
TEST(BondMoments, CantileverOfSpheresSagsAsItsJointsBendAndShear) {
  cantilever_sags_as_its_joints_bend<3>(0.0);
}
TEST(BondMoments, CantileverOfDiscsKeepsItsBendingThroughListBuilds) {
  cantilever_sags_as_its_joints_bend<2>(5e-9);
}
TEST(BondMoments, CantileverOfSpheresKeepsItsBendingThroughListBuilds) {
  cantilever_sags_as_its_joints_bend<3>(5e-9);
}

// Three grains beyond the fixed one: the joints' moments at rest are
// m g r x (9, 4, 1). Strength 13.5 m g r: the root holds at g (a release
// that overshoots by less than half); at 2 g the root's moment, 18, passes
// it, the next joint's, 8, stays well below: the root bond alone breaks and
// the rest of the cantilever falls with its two bonds.
template <int D>
void root_bond_breaks_in_bending() {
  const int count = 3;
  const double weight = grain_mass<D>() * g;
  auto sim = cantilever<D>(count, 1e-5, 13.5 * weight * radius);
  sim.prepare();
  ASSERT_EQ(sim.make_bonds(), 3U);
  const auto sag = cantilever_sag(count, weight, sim.contact_table(0, 0).normal_stiffness);
  sim.gravity[D - 1] = -g;
  sim.damping.viscous = settling_rate(sag[count]);
  const auto steps = static_cast<std::uint64_t>(40.0 / (0.5 * sim.damping.viscous * sim.time_step));
  sim.advance(steps);
  ASSERT_EQ(sim.bond_count(), 3U);
  ASSERT_EQ(sim.broken_bonds, 0U);
  EXPECT_NEAR(-sim.particles.position[count][D - 1], sag[count], 1e-6 * sag[count]);

  sim.gravity[D - 1] = -2.0 * g;
  sim.advance(steps);
  EXPECT_EQ(sim.broken_bonds, 1U);
  EXPECT_EQ(sim.bond_count(), 2U);
  // No longer held: the cantilever, free to turn about its root's ordinary
  // contact, has sunk far below the sag its bonds would hold it at under
  // 2 g, twice the one at g (the heavy damping slows its swing).
  for (int k = 1; k <= count; ++k) {
    EXPECT_LT(sim.particles.position[k][D - 1], -20.0 * sag[k]) << "grain " << k;
  }
  // The two bonds left hold the three grains together, a diameter apart.
  for (int k = 2; k <= count; ++k) {
    const double gap = (sim.particles.position[k] - sim.particles.position[k - 1]).norm() - 2.0 * radius;
    EXPECT_LT(std::abs(gap), 1e-3 * radius) << "bond " << k;
  }
}

TEST(BondMoments, RootBondOfADiscCantileverBreaksInBending) { root_bond_breaks_in_bending<2>(); }
TEST(BondMoments, RootBondOfASphereCantileverBreaksInBending) { root_bond_breaks_in_bending<3>(); }

/// A sphere bonded to a fixed one along x, spun about x (the bond's normal)
/// at omega0: a torsion pendulum on k_tw = k_n R*^2 (ratio 1, R* = r/2), of
/// frequency Omega = sqrt(k_tw / I), I = 0.4 m r^2. A spin about the normal
/// moves neither contact point: neither the shear nor the bending spring
/// takes part. No damping.
struct TorsionPendulum {
  Simulation<3> sim;
  double omega0;
  double frequency;
  double peak_moment;  ///< k_tw omega0 / Omega = omega0 sqrt(k_tw I)
};

TorsionPendulum torsion_pendulum(double strength_over_peak, int steps_per_half_period) {
  const double m = grain_mass<3>();
  const double k_n = 1e4;
  const double k_tw = k_n * radius * radius / 4.0;
  const double inertia = 0.4 * m * radius * radius;
  const double frequency = std::sqrt(k_tw / inertia);
  const double omega0 = 10.0;  // rad/s: peak twist omega0 / Omega ~ 1e-2 rad
  const double peak = omega0 * std::sqrt(k_tw * inertia);
  ContactSpec spec;
  spec.normal_stiffness = k_n;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  spec.bond_tensile_strength = 1.0;  // N, never reached
  spec.bond_shear_strength = 1.0;
  spec.bond_twisting_stiffness_ratio = 1.0;
  spec.bond_twisting_strength = strength_over_peak * peak;
  auto sim = testing::single_material<3>(density, spec);
  sim.particles.add(Vec<3>::Zero(), radius, density, 0, true, Vec<3>::Zero());
  sim.particles.add(Vec<3>(2.0 * radius * (1.0 - 0.5e-9), 0.0, 0.0), radius, density, 0, false,
                    Vec<3>::Zero());
  sim.particles.angular_velocity[1] = Vec<3>(omega0, 0.0, 0.0);
  sim.time_step = std::numbers::pi / frequency / steps_per_half_period;
  return {std::move(sim), omega0, frequency, peak};
}

// Strength 1.02 x the peak twist moment: the bond holds, and half a period
// later the spin has reversed, omega0 cos(Omega t) = -omega0. Bound 1e-5:
// velocity Verlet's phase error over half a period, (Omega dt)^2 pi / 24 ~
// 1e-7 with 2000 steps, and the normal spring's residue from the 1e-9 r
// initial overlap (no coupling to the spin).
TEST(BondMoments, SphereTwistsOnItsBondAsATorsionPendulum) {
  auto p = torsion_pendulum(1.02, 2000);
  p.sim.prepare();
  ASSERT_EQ(p.sim.make_bonds(), 1U);
  p.sim.advance(2000);
  EXPECT_NEAR(p.sim.particles.angular_velocity[1][0], -p.omega0, 1e-5 * p.omega0);
  EXPECT_LT(p.sim.particles.angular_velocity[1].tail<2>().norm(), 1e-9 * p.omega0);
  // The sphere stays put but for the normal spring's oscillation from the
  // initial overlap d0 = 1e-9 r: speed at most d0 sqrt(k_n / m).
  EXPECT_LT(p.sim.particles.velocity[1].norm(), 2.0 * 1e-9 * radius * std::sqrt(1e4 / grain_mass<3>()));
  p.sim.advance(2000);  // a whole period, through the opposite twist
  EXPECT_NEAR(p.sim.particles.angular_velocity[1][0], p.omega0, 1e-5 * p.omega0);
  EXPECT_EQ(p.sim.bond_count(), 1U);
  EXPECT_EQ(p.sim.broken_bonds, 0U);
  // Energy 1/2 I omega^2 + 1/2 k_tw theta^2 is conserved: the bond's share
  // (elastic_energy) and the spin's add up to 1/2 I omega0^2 (bound: the
  // step's shadow-energy error, (Omega dt)^2 / 8 ~ 3e-7).
  p.sim.advance(1000);  // a quarter period on: all in the twist
  const double inertia = 0.4 * grain_mass<3>() * radius * radius;
  const double spin = p.sim.particles.angular_velocity[1][0];
  const double total = 0.5 * inertia * spin * spin + p.sim.elastic_energy();
  EXPECT_NEAR(total, 0.5 * inertia * p.omega0 * p.omega0, 1e-5 * 0.5 * inertia * p.omega0 * p.omega0);
  EXPECT_LT(std::abs(spin), 1e-2 * p.omega0);
}

// Strength 0.98 x the peak: the bond breaks on the way, where the twist
// moment passes the strength S; the sphere then spins free at the rate left,
// sqrt(omega0^2 - S^2 / (k_tw I)) = omega0 sqrt(1 - 0.98^2) (energy). Bound
// 0.5 %: the break comes at the first step past S, up to one step of twist
// late, which with 20000 steps per half period shifts the rate by ~0.1 %.
TEST(BondMoments, SphereSpinsFreeOnceItsTwistPassesTheBondsStrength) {
  auto p = torsion_pendulum(0.98, 20000);
  p.sim.prepare();
  ASSERT_EQ(p.sim.make_bonds(), 1U);
  p.sim.advance(20000);
  EXPECT_EQ(p.sim.broken_bonds, 1U);
  EXPECT_EQ(p.sim.bond_count(), 0U);
  const double left = p.omega0 * std::sqrt(1.0 - 0.98 * 0.98);
  EXPECT_NEAR(p.sim.particles.angular_velocity[1][0], left, 5e-3 * left);
}

// examples/dem_cases/bonded_cantilever.toml, as a user runs it: stage "sag"
// bonds the ten discs to the fixed one and to each other and lets gravity
// bend them; the tip then sits at the small-deflection sag derived by hand
// (cantilever_sag, with the example's k_n = 1e7 N/m, m = 7.854e-3 kg/m).
// Stage "overload" (1.5 g) breaks the root bond alone.
TEST(BondMoments, BondedCantileverExampleSagsAndBreaksAtItsRootWhenOverloaded) {
  const std::string dir = testing::temp_dir("bonded_cantilever");
  const RunSummary summary = testing::run_example<2>("examples/dem_cases/bonded_cantilever.toml", dir);
  ASSERT_FALSE(summary.interrupted);
  ASSERT_EQ(summary.stages_completed.size(), 2U);
  const auto probes = testing::read_probes(dir + "/probes.csv");
  const auto& t = probes.at("time");
  const auto& y = probes.at("tip_y");
  const auto& bonds = probes.at("bonds");
  const auto& broken = probes.at("broken");
  const double m = 2500.0 * std::numbers::pi * 1e-6;   // kg per metre
  const auto sag = cantilever_sag(10, m * 9.81, 1e7);  // tip: 1.7501e-4 m
  // The tip turns by phi_tip = 0.0119 rad here: the small-deflection sag is
  // off by second-order terms of about phi_tip^2 = 1.4e-4 of it; bound
  // 3e-4 (the run gives 6e-5).
  std::size_t sag_end = 0;
  while (sag_end + 1 < t.size() && t[sag_end + 1] < 0.3 - 1e-9) ++sag_end;
  EXPECT_NEAR(y[sag_end], -sag[10], 3e-4 * sag[10]) << "t = " << t[sag_end];
  for (std::size_t row = 1; row <= sag_end; ++row) {
    EXPECT_EQ(bonds[row], 10.0) << "t = " << t[row];
    EXPECT_EQ(broken[row], 0.0) << "t = " << t[row];
  }
  EXPECT_EQ(bonds.back(), 9.0);
  EXPECT_EQ(broken.back(), 1.0);
  EXPECT_LT(y.back(), -5.0 * sag[10]);  // swinging down about its root
  const std::string json = testing::file_contents(dir + "/run.json");
  EXPECT_NE(json.find("\"bonds\": {\"intact\": 9, \"broken\": 1}"), std::string::npos) << json;
  // The contact network at the end of stage "sag" (snapshot 1): the ten
  // bonds, joint k bending with the moment of the weight beyond it,
  // m g r (11 - k)^2; bound 1e-3 (the sag shortens the lever arms by about
  // phi^2 / 2 < 1e-4).
  const std::string vtu = testing::file_contents(dir + "/contacts_00001.vtu");
  const auto marked = testing::vtk_array(vtu, "bonded");
  const auto bending = testing::vtk_array(vtu, "bending_moment");
  ASSERT_EQ(marked.size(), 10U);
  ASSERT_EQ(bending.size(), 10U);
  for (std::size_t c = 0; c < 10; ++c) {
    EXPECT_EQ(marked[c], 1.0);
    const double beyond = static_cast<double>(10 - c);
    const double moment = m * 9.81 * 1e-3 * beyond * beyond;
    EXPECT_NEAR(bending[c], moment, 1e-3 * moment) << "joint " << c + 1;
  }
}

}  // namespace
}  // namespace darcydem
