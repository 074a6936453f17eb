// The grains' fluid forces held between fluid steps (`[fluid] hold_forces`,
// the coupling interval of PFC's and CFDEM's fluid coupling): every DEM step
// of an interval applies, grain by grain, the force computed at the
// interval's first step, also when the simulation reorders its grains in
// between; without it the force follows each grain from step to step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "darcydem/contact/contact_laws.hpp"
#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/generation/generators.hpp"
#include "darcydem/simulation/simulation.hpp"

using namespace darcydem;

namespace {

constexpr int kInterval = 50;  // DEM steps per fluid step

/// 400 spheres (radii 0.4..0.5 mm) at random in a 10 x 10 x 20 mm box,
/// moving at 0.5 m/s in random directions, no walls, in a pore fluid with
/// an inflow of 1 mm/s at the bottom of a 5 x 5 x 10 grid of 2 mm cells,
/// the top drained. The grains are reordered at every list build
/// (sort_threshold 0), and they move across the list's cells, so the
/// order changes during the run.
struct Case {
  Simulation<3> sim;
  PoreFluid<3> fluid{PressureSolverKind::cg, 1e-12, CgPreconditioner::jacobi};
};

std::unique_ptr<Case> make_case(bool hold) {
  auto c = std::make_unique<Case>();
  Simulation<3>& sim = c->sim;
  Material grain{"grain", 2650.0, 0.0, 0.0};
  sim.materials.push_back(grain);
  ContactSpec spec;
  spec.normal_stiffness = 1000.0;
  spec.friction = 0.5;
  spec.restitution = 0.5;
  sim.contact_table = ContactTable(1);
  sim.contact_table.set(0, 0, make_pair_parameters(grain, grain, spec));
  RadiusDistribution radii;
  radii.kind = RadiusDistribution::Kind::uniform;
  radii.min = 0.0004;
  radii.max = 0.0005;
  const auto pk = random_packing<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.01, 0.02), 400, radii, 5, 2000);
  std::mt19937 rng(3);
  std::normal_distribution<double> z;
  for (std::size_t i = 0; i < pk.position.size(); ++i) {
    sim.particles.add(pk.position[i], pk.radius[i], 2650.0, 0, false);
    Vec<3> v(z(rng), z(rng), z(rng));
    sim.particles.velocity.back() = 0.5 * v.normalized();
  }
  sim.gravity = Vec<3>(0.0, 0.0, -9.80665);
  sim.sort_threshold = 0;
  sim.time_step = 2e-6;
  PoreFluid<3>& f = c->fluid;
  f.grid.origin = Vec<3>::Zero();
  f.grid.spacing = Vec<3>::Constant(0.002);
  f.grid.cells = {5, 5, 10};
  f.fluid = {1000.0, 1.0e-3, 1e7};
  f.drag = DragLaw::ergun;
  f.permeability.model = PermeabilityModel::kozeny_carman;
  f.permeability.diameter = 0.0009;
  f.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(1e-3)};
  f.sides[5] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.steps_per_update = kInterval;
  f.hold_forces = hold;
  f.initialize(sim.particles);
  sim.force_field = &f;
  sim.prepare();
  return c;
}

/// The field forces of the last step, by particle id.
std::vector<Vec<3>> by_id(const Simulation<3>& sim) {
  std::vector<Vec<3>> out(sim.particles.size());
  for (std::size_t i = 0; i < sim.particles.size(); ++i) out[sim.particles.id[i]] = sim.field_forces()[i];
  return out;
}

/// Runs `intervals` coupling intervals as the runner does (a fluid step
/// after every kInterval DEM steps); per DEM step, calls
/// seen(step in interval, field forces by id, whether the grains were
/// reordered since the step before).
template <class F>
void run(Case& c, int intervals, F&& seen) {
  std::vector<std::uint32_t> order = c.sim.particles.id;
  for (int k = 0; k < intervals * kInterval; ++k) {
    c.sim.step();
    const bool reordered = c.sim.particles.id != order;
    order = c.sim.particles.id;
    seen(k % kInterval, by_id(c.sim), reordered);
    if (c.sim.steps % kInterval == 0)
      c.fluid.update(c.sim.particles, kInterval * c.sim.time_step, c.sim.time);
  }
}

}  // namespace

TEST(HeldForces, EveryStepOfAnIntervalAppliesTheForceOfItsFirstStep) {
  auto c = make_case(true);
  std::vector<Vec<3>> first;
  int reorders_within = 0;
  int compared = 0;
  int renewed = 0;
  run(*c, 8, [&](int step, const std::vector<Vec<3>>& force, bool reordered) {
    if (step == 0) {
      // After each fluid step the forces are computed anew.
      if (!first.empty() && force != first) ++renewed;
      first = force;
      return;
    }
    if (reordered) ++reorders_within;
    // The same numbers, not close ones: the forces are applied again, not
    // recomputed.
    for (std::size_t id = 0; id < force.size(); ++id) {
      ASSERT_EQ(force[id], first[id]) << "grain " << id << ", step " << step << " of the interval";
    }
    ++compared;
  });
  EXPECT_EQ(compared, 8 * (kInterval - 1));
  EXPECT_EQ(renewed, 7);
  // The grains were reordered within intervals, so the forces had to move
  // with them (otherwise this test would not check that).
  EXPECT_GT(reorders_within, 0);
  // And a force computed now, at the grains' current positions and
  // velocities, differs from the held one: holding is not a no-op here.
  std::vector<Vec<3>> now(c->sim.particles.size());
  c->fluid.particle_forces(c->sim.particles, c->sim.gravity, now);
  double largest_change = 0.0;
  double largest = 0.0;
  for (std::size_t i = 0; i < now.size(); ++i) {
    largest_change = std::max(largest_change, (now[i] - c->sim.field_forces()[i]).norm());
    largest = std::max(largest, now[i].norm());
  }
  EXPECT_GT(largest_change, 1e-6 * largest);
}

TEST(HeldForces, WithoutHoldingTheForceFollowsEachGrain) {
  // The default: recomputed every DEM step from the last fluid step's
  // fields at the grain's current position and velocity, so within an
  // interval the forces change from step to step.
  auto c = make_case(false);
  std::vector<Vec<3>> before;
  int changed = 0;
  run(*c, 2, [&](int step, const std::vector<Vec<3>>& force, bool /*reordered*/) {
    if (step > 0 && force != before) ++changed;
    before = force;
  });
  EXPECT_EQ(changed, 2 * (kInterval - 1));
}
