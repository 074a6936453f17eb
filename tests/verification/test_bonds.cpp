// Contact bonds (PFC's linear contact bond): a bonded pair carries tension
// k_n x gap and a tangential force without the Coulomb limit, until either
// exceeds the bond's strength. Checked against statics derived by hand: a
// hanging chain (each bond carries the weight below it), a grain held in
// shear between two fixed ones (two tangential springs in parallel), and
// free fall once the top bond has broken.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

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
constexpr int chain = 10;           // free grains below the fixed one

template <int D>
double grain_mass() {
  return density * particle_volume<D>(radius);
}

/// A vertical chain: a fixed grain at the origin and `chain` free grains
/// below it along the last axis, neighbours overlapping by 1e-9 r (so that
/// make_bonds bonds them), no gravity yet. k_n makes the top bond's static
/// stretch under the chain's weight 1e-4 r, well inside the skin (0.2 r).
template <int D>
Simulation<D> hanging_chain(double tensile_strength) {
  const double weight = chain * grain_mass<D>() * g;
  ContactSpec spec;
  spec.normal_stiffness = weight / (1e-4 * radius);
  spec.restitution = 0.5;
  spec.friction = 0.5;
  spec.bond_tensile_strength = tensile_strength;
  spec.bond_shear_strength = tensile_strength;
  auto sim = testing::single_material<D>(density, spec);
  for (int k = 0; k <= chain; ++k) {
    Vec<D> x = Vec<D>::Zero();
    x[D - 1] = -k * 2.0 * radius * (1.0 - 0.5e-9);
    sim.particles.add(x, radius, density, 0, k == 0, Vec<D>::Zero());
  }
  sim.time_step = 0.1 * std::sqrt(grain_mass<D>() / spec.normal_stiffness);
  return sim;
}

/// The stretch of the bond above grain k (1..chain) at rest: it carries the
/// weight of grains k..chain, (chain - k + 1) m g, on the spring k_n.
template <int D>
double static_gap(const Simulation<D>& sim, int k) {
  return (chain - k + 1) * grain_mass<D>() * g / sim.contact_table(0, 0).normal_stiffness;
}

template <int D>
double gap(const Simulation<D>& sim, int k) {
  return (sim.particles.position[k - 1] - sim.particles.position[k]).norm() - 2.0 * radius;
}

// Strength three times the top bond's static load (a released chain
// overshoots to at most twice it): the chain, released unstretched under
// gravity with viscous damping, comes to rest with every bond stretched by
// the weight it carries over k_n.
template <int D>
void chain_hangs_from_its_bonds() {
  auto sim = hanging_chain<D>(3.0 * chain * grain_mass<D>() * g);
  sim.prepare();
  ASSERT_EQ(sim.make_bonds(), static_cast<std::size_t>(chain));
  sim.gravity[D - 1] = -g;
  // About twice the critical rate of the stiffest mode, so every mode decays
  // within a few thousand steps.
  sim.damping.viscous = 4.0 * std::sqrt(sim.contact_table(0, 0).normal_stiffness / grain_mass<D>());
  sim.advance(40000);
  EXPECT_EQ(sim.bond_count(), static_cast<std::size_t>(chain));
  EXPECT_EQ(sim.broken_bonds, 0U);
  for (int k = 1; k <= chain; ++k) {
    // Every bond is in tension (the grains apart): an unbonded contact
    // would carry none. Bound 1e-6 of the stretch (measured 4e-9 to 7e-9):
    // what is left of the damped motion after 40 000 steps, far below it.
    EXPECT_GT(gap(sim, k), 0.0);
    EXPECT_NEAR(gap(sim, k), static_gap(sim, k), 1e-6 * static_gap(sim, k)) << "bond above grain " << k;
  }
  // The contacts as the stress probes and contacts.vtu see them: each bond
  // listed, apart as it is, its normal force the pull of the weight below
  // (negative: tension), within the same bound.
  std::size_t bonded = 0;
  for (const auto& c : sim.contact_forces()) {
    if (!c.bonded) continue;
    ++bonded;
    const auto k = static_cast<int>(c.second);
    ASSERT_EQ(c.first + 1, c.second);
    const double pull = (chain - k + 1) * grain_mass<D>() * g;
    EXPECT_NEAR(-c.force.dot(c.normal), -pull, 1e-6 * pull) << "bond above grain " << k;
    EXPECT_LT(c.overlap, 0.0);
  }
  EXPECT_EQ(bonded, static_cast<std::size_t>(chain));
}

TEST(Bonds, ChainOfDiscsHangsFromItsBondsStretchedByTheWeightBelow) { chain_hangs_from_its_bonds<2>(); }
TEST(Bonds, ChainOfSpheresHangsFromItsBondsStretchedByTheWeightBelow) { chain_hangs_from_its_bonds<3>(); }

// Strength 0.95 of the top bond's load and above every other bond's (at most
// 0.9 of it): put at rest in its stretched equilibrium, the chain loses its
// top bond at the first force evaluation and nothing else after; the rest then falls
// freely, its centre of mass as z0 - g t^2 / 2 (internal forces cancel),
// bonds intact.
template <int D>
void top_bond_breaks_and_the_rest_falls() {
  const double m = grain_mass<D>();
  auto sim = hanging_chain<D>(0.95 * chain * m * g);
  sim.prepare();
  ASSERT_EQ(sim.make_bonds(), static_cast<std::size_t>(chain));
  // Into the stretched equilibrium (a move of 1e-4 r at most, well inside
  // the half skin, so the lists and bonds stand), then the forces there.
  double drop = 0.0;
  for (int k = 1; k <= chain; ++k) {
    drop += static_gap(sim, k);
    sim.particles.position[k][D - 1] = -k * 2.0 * radius - drop;
  }
  sim.gravity[D - 1] = -g;
  // The evaluation of the forces there breaks the top bond at once.
  sim.prepare();
  ASSERT_EQ(sim.broken_bonds, 1U);
  ASSERT_EQ(sim.bond_count(), static_cast<std::size_t>(chain - 1));
  double z0 = 0.0;
  for (int k = 1; k <= chain; ++k) z0 += sim.particles.position[k][D - 1];
  z0 /= chain;
  const int steps = 20000;
  sim.advance(steps);
  const double t = steps * sim.time_step;
  EXPECT_EQ(sim.broken_bonds, 1U);
  EXPECT_EQ(sim.bond_count(), static_cast<std::size_t>(chain - 1));
  double z = 0.0;
  for (int k = 1; k <= chain; ++k) z += sim.particles.position[k][D - 1];
  z /= chain;
  // Velocity Verlet is exact for a constant acceleration; what remains is
  // round-off of the internal forces' sum (1e-12 m over the 2 cm fall).
  EXPECT_NEAR(z, z0 - 0.5 * g * t * t, 1e-12);
  EXPECT_GT(0.5 * g * t * t, 10.0 * radius);  // it has fallen clear of the fixed grain
  EXPECT_EQ(sim.particles.position[0], Vec<D>::Zero());
}

TEST(Bonds, TopBondOfDiscsBreaksAboveItsStrengthAndTheRestFallsFreely) {
  top_bond_breaks_and_the_rest_falls<2>();
}
TEST(Bonds, TopBondOfSpheresBreaksAboveItsStrengthAndTheRestFallsFreely) {
  top_bond_breaks_and_the_rest_falls<3>();
}

/// Grain 1 between fixed grains 0 and 2 along x, all three touching and
/// bonded, friction 0.3; a force `load` across the row (along the last axis)
/// on grain 1, no gravity. By symmetry the two bonds share the load in
/// shear, their torques on grain 1 cancel, and it comes to rest deflected by
/// load / (2 k_t). An unbonded pair with no normal force would carry no
/// tangential force at all (Coulomb's limit mu F_n = 0).
template <int D>
Simulation<D> sheared_grain(double load, double shear_strength) {
  ContactSpec spec;
  spec.normal_stiffness = 1e4;
  spec.tangential_stiffness_ratio = 0.5;
  spec.restitution = 0.5;
  spec.friction = 0.3;
  spec.bond_tensile_strength = shear_strength;
  spec.bond_shear_strength = shear_strength;
  auto sim = testing::single_material<D>(density, spec);
  for (int k = 0; k < 3; ++k) {
    Vec<D> x = Vec<D>::Zero();
    x[0] = (k - 1) * 2.0 * radius * (1.0 - 0.5e-9);
    sim.particles.add(x, radius, density, 0, k != 1, Vec<D>::Zero());
  }
  sim.particles.external_force.assign(3, Vec<D>::Zero());
  sim.particles.external_force[1][D - 1] = -load;
  sim.time_step = 0.05 * std::sqrt(grain_mass<D>() / spec.normal_stiffness);
  sim.prepare();
  EXPECT_EQ(sim.make_bonds(), 2U);
  // Viscous damping near the critical rate of the shear mode.
  sim.damping.viscous = 2.0 * std::sqrt(2.0 * 0.5 * spec.normal_stiffness / grain_mass<D>());
  return sim;
}

template <int D>
void bonds_hold_a_grain_in_shear() {
  const double strength = 1e-3;  // N
  auto sim = sheared_grain<D>(1.9 * strength, strength);
  sim.advance(100000);
  EXPECT_EQ(sim.bond_count(), 2U);
  const double kt = 0.5 * 1e4;
  const double deflection = 1.9 * strength / (2.0 * kt);  // 1.9e-7 m = 1.9e-4 r
  // Bound 1e-6 of the deflection: the tilt of the bonds changes the shares
  // by (deflection / 2r)^2 ~ 1e-8 (their stretch and the rotated tangent),
  // and the damped motion has decayed far below that.
  EXPECT_NEAR(-sim.particles.position[1][D - 1], deflection, 1e-6 * deflection);
  EXPECT_NEAR(sim.particles.position[1][0], 0.0, 1e-6 * deflection);
  // No spin: the two bonds' torques cancel (bound: round-off of the rate).
  EXPECT_LT(sim.particles.angular_velocity[1].norm(), 1e-9);
}

TEST(Bonds, TwoBondsHoldADiscInShearBeyondItsFriction) { bonds_hold_a_grain_in_shear<2>(); }
TEST(Bonds, TwoBondsHoldASphereInShearBeyondItsFriction) { bonds_hold_a_grain_in_shear<3>(); }

template <int D>
void bonds_break_in_shear() {
  const double strength = 1e-3;  // N
  auto sim = sheared_grain<D>(2.1 * strength, strength);
  sim.advance(100000);
  // Each bond's share (1.05 x its strength at rest) passes its strength on
  // the way: both break, and the grain, free across the row, leaves at the
  // terminal speed of the load against the viscous damping, F / (beta m).
  // Bound 1e-9: the approach to it decays as exp(-beta t), beta t > 100.
  EXPECT_EQ(sim.bond_count(), 0U);
  EXPECT_EQ(sim.broken_bonds, 2U);
  EXPECT_LT(sim.particles.position[1][D - 1], -0.25 * radius);  // apart from both fixed grains
  const double terminal = 2.1 * strength / (sim.damping.viscous * grain_mass<D>());
  EXPECT_NEAR(sim.particles.velocity[1][D - 1], -terminal, 1e-9 * terminal);
  EXPECT_GT(sim.damping.viscous * sim.time, 100.0);
}

TEST(Bonds, BondsOfADiscBreakInShearAboveTheirStrength) { bonds_break_in_shear<2>(); }
TEST(Bonds, BondsOfASphereBreakInShearAboveTheirStrength) { bonds_break_in_shear<3>(); }

// examples/dem_cases/cemented_chain.toml, as a user runs it: stage "hang"
// bonds the ten discs below the fixed one (the generator's discs touch to
// round-off; bond_gap 1e-9 m) and settles them; every bond then carries the
// weight below it, so the lowest disc has sunk by 55 m g / k_n. Stage
// "overload" triples gravity: the top bond's load (2.31 N/m) passes its
// strength (2 N/m), the others' (at most 9 x 3 m g = 2.08 N/m in
// equilibrium) would too, but the chain below falls freely once the top
// bond has gone, which unloads them: one bond breaks.
TEST(Bonds, CementedChainExampleSinksByTheBondsStretchAndDropsWhenOverloaded) {
  const std::string dir = testing::temp_dir("bonds_chain");
  const RunSummary summary = testing::run_example<2>("examples/dem_cases/cemented_chain.toml", dir);
  ASSERT_FALSE(summary.interrupted);
  ASSERT_EQ(summary.stages_completed.size(), 2U);
  const auto probes = testing::read_probes(dir + "/probes.csv");
  const auto& t = probes.at("time");
  const auto& y = probes.at("bottom_y");
  const auto& bonds = probes.at("bonds");
  const auto& broken = probes.at("broken");
  const double m = 2500.0 * std::numbers::pi * 1e-6;  // kg per metre
  const double sink = 55.0 * m * 9.81 / 1e4;          // 4.2376e-4 m
  // The last row of stage "hang" (0.3 s); bound 1e-6 of the sink (10 digits
  // in probes.csv; the damped motion has decayed far below it).
  std::size_t hang_end = 0;
  while (hang_end + 1 < t.size() && t[hang_end + 1] < 0.3 - 1e-9) ++hang_end;
  EXPECT_NEAR(y[hang_end], -0.021 - sink, 1e-6 * sink) << "t = " << t[hang_end];
  for (std::size_t row = 1; row <= hang_end; ++row) {
    EXPECT_EQ(bonds[row], 10.0) << "t = " << t[row];
    EXPECT_EQ(broken[row], 0.0) << "t = " << t[row];
  }
  EXPECT_EQ(bonds.back(), 9.0);
  EXPECT_EQ(broken.back(), 1.0);
  EXPECT_LT(y.back(), y[hang_end] - 0.01);  // it has fallen
  // The contact network at the end of stage "hang" (snapshot 1): the ten
  // bonds marked, each pulling with the weight below it, (11 - k) m g.
  const std::string vtu = testing::file_contents(dir + "/contacts_00001.vtu");
  const auto marked = testing::vtk_array(vtu, "bonded");
  const auto normal = testing::vtk_array(vtu, "normal_force");
  ASSERT_EQ(marked.size(), 10U);
  ASSERT_EQ(normal.size(), 10U);
  for (std::size_t c = 0; c < 10; ++c) {
    EXPECT_EQ(marked[c], 1.0);
    const double pull = static_cast<double>(10 - c) * m * 9.81;
    EXPECT_NEAR(normal[c], -pull, 1e-6 * pull) << "contact " << c;
  }
  const std::string json = testing::file_contents(dir + "/run.json");
  EXPECT_NE(json.find("\"bonds\": {\"intact\": 9, \"broken\": 1}"), std::string::npos) << json;
}

}  // namespace
}  // namespace darcydem
