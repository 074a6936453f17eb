// The energies a run reports (Simulation::elastic_energy, gravitational_energy
// and kinetic_energy, the probes of the same names), as YADE's energy
// tracker and PFC's strain energy report them: checked where their sum is
// conserved (a conservative motion) and against the hand-derived energies
// of a disc resting on a floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "dem_setup.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

namespace {

/// A grain at rest, without dashpots (restitution 1), set spinning at omega0
/// about an axis normal to gravity: on a floor (a wall contact, overlap
/// m g / k_n), or in the hollow between two fixed grains of its size, r
/// apart on either side of it (two grain contacts, R* = r / 2; placed where
/// their springs carry its weight). Friction 10 keeps the tangential springs
/// from sliding and the rolling resistance mu_r = 0.5 the rolling springs
/// from yielding: the largest rolling moment, omega0 sqrt(I k_r) (all the
/// spin's energy in the springs), is at most 0.21 of the limit mu_r R* F_n
/// (floor, omega0 = 0.2 rad/s) and 0.19 (hollow, 0.05 rad/s). Everything
/// then is conservative: the spin passes to the tangential and rolling
/// springs and to the grain's translation and back. Returns the largest
/// departure of the sum of the energies from its start, over 30 000 steps
/// (some 30 periods of the springs), relative to the spin's energy; sets
/// `stored_share` to the largest share of that energy the springs held.
template <int D>
double worst_energy_drift(bool in_hollow, double& stored_share) {
  ContactSpec spec;
  spec.restitution = 1.0;
  spec.friction = 10.0;
  spec.rolling_friction = 0.5;
  const double r = 1e-3;
  const double g = 9.81;
  auto sim = darcydem::testing::particle_on_floor<D>(spec, r, 0.0, g);
  const int axis = D == 3 && in_hollow ? 1 : 0;  // the spin's axis: normal to the three centres' plane
  if (in_hollow) {
    sim.walls.clear();
    const double k_n = sim.contact_table(0, 0).normal_stiffness;
    const double weight = 2500.0 * particle_volume<D>(r) * g;
    // The height h of the centre above the fixed ones' where the two
    // springs, each 2r - L long (L = sqrt(r^2 + h^2)), carry the weight:
    // 2 k_n (2r - L) h / L = m g, by bisection to round-off.
    double lo = 1.7 * r;
    double hi = std::sqrt(3.0) * r;
    for (int k = 0; k < 200; ++k) {
      const double h = 0.5 * (lo + hi);
      const double length = std::sqrt(r * r + h * h);
      (2.0 * k_n * (2.0 * r - length) * h / length > weight ? lo : hi) = h;
    }
    sim.particles.position[0][D - 1] = 0.5 * (lo + hi);
    for (const double side : {-1.0, 1.0}) {
      Vec<D> x = Vec<D>::Zero();
      x[0] = side * r;
      sim.particles.add(x, r, 2500.0, 0, true, Vec<D>::Zero());
    }
  }
  // 10x finer than the helper's step: velocity Verlet's energy fluctuates by
  // about (omega dt)^2 / 4 of the oscillating energy; the stiffest mode
  // (the contact point's tangential spring on the grain's mass and
  // inertia, omega^2 = 3.5 k_t / m in 3D, twice that with two contacts)
  // has omega dt = 0.0094 (0.013): 2.2e-5 (4.4e-5).
  sim.time_step *= 0.1;
  const double omega0 = in_hollow ? 0.05 : 0.2;  // rad/s
  sim.particles.angular_velocity[0][axis] = omega0;
  sim.prepare();
  auto energy = [&] { return sim.kinetic_energy() + sim.gravitational_energy() + sim.elastic_energy(); };
  const double spin = sim.kinetic_energy();
  const double at_rest = sim.elastic_energy();
  const double e0 = energy();
  double worst = 0.0;
  stored_share = 0.0;
  for (int s = 0; s < 30000; ++s) {
    sim.step();
    worst = std::max(worst, std::abs(energy() - e0) / spin);
    stored_share = std::max(stored_share, (sim.elastic_energy() - at_rest) / spin);
  }
  return worst;
}

}  // namespace

TEST(Energy, ASpinningGrainsSpringsStoreTheEnergyItsSpinLoses) {
  for (const int d : {2, 3}) {
    for (const bool in_hollow : {false, true}) {
      SCOPED_TRACE(std::to_string(d) + (in_hollow ? "D, in a hollow of two grains" : "D, on a floor"));
      double stored = 0.0;
      const double worst =
          d == 2 ? worst_energy_drift<2>(in_hollow, stored) : worst_energy_drift<3>(in_hollow, stored);
      // The springs take up most of the spin's energy at times (the test must
      // exercise them; measured: all of it, when the grain is still):
      // without the rolling spring's 1/2 k_r theta^2 in the elastic energy
      // the sum would miss that part (measured so: 0.68 of the spin's
      // energy on the floor, 0.25 in the hollow).
      EXPECT_GT(stored, 0.5);
      // Conserved within 1e-4 of the spin's energy: 2.3 to 4.5 times the
      // integrator's fluctuation estimated above (measured: floor 2.0e-5 in
      // 2D, 2.4e-5 in 3D; hollow 2.9e-5, 3.6e-5).
      EXPECT_LT(worst, 1e-4);
    }
  }
}

TEST(Energy, ProbesGiveARestingDiscsSpringAndHeight) {
  // One disc of r = 0.5 mm on a floor, settled by local damping. By hand:
  // m = rho pi r^2 (per metre), overlap d = m g / k_n, the spring's energy
  // (m g)^2 / (2 k_n), the potential -m g.x = m g (r - d).
  const char* scene_text = R"(
[simulation]
dimension = 2
time_step = "auto"

[[material]]
name = "sand"
density = 2650.0

[[contact]]
materials = ["sand", "sand"]
law = "linear"
normal_stiffness = 1e3
restitution = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "sand"

[[particles]]
generator = "column"
material = "sand"
base = [0.0, 0.0]
count = 1
radius = 0.0005

[output]
probe_interval = 0.01

[[probe]]
name = "kinetic"
quantity = "kinetic_energy"

[[probe]]
name = "elastic"
quantity = "elastic_energy"

[[probe]]
name = "potential"
quantity = "gravitational_energy"

[[stage]]
name = "settle"
duration = 0.2
gravity = [0.0, -9.81]
local_damping = 0.7
)";
  const auto probes = darcydem::testing::run_scene_probes<2>("energy_probes", scene_text);
  const double r = 5e-4;
  const double m = 2650.0 * std::numbers::pi * r * r;
  const double weight = m * 9.81;
  const double d = weight / 1e3;
  // The first row: the disc placed touching the floor, at rest.
  EXPECT_NEAR(probes.at("potential").front(), weight * r, 1e-9 * weight * r);
  EXPECT_EQ(probes.at("kinetic").front(), 0.0);
  // The last: settled (local damping 0.7 over 0.2 s, some 140 periods of
  // the contact's 1.4 ms: the rest of the first bounce is far below the
  // 1e-6 relative the probes are checked to; they are written to 10
  // significant digits).
  EXPECT_NEAR(probes.at("elastic").back(), weight * weight / (2.0 * 1e3),
              1e-6 * weight * weight / (2.0 * 1e3));
  EXPECT_NEAR(probes.at("potential").back(), weight * (r - d), 1e-9 * weight * r);
  EXPECT_LT(probes.at("kinetic").back(), 1e-9 * weight * weight / (2.0 * 1e3));
}
