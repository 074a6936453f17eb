// Periodic boundaries (Simulation::periodic): a compressed lattice that
// fills the period has the statics of an infinite one, a collision across a
// periodic boundary is the same collision as inside the domain, an elastic
// gas in a periodic box keeps its momentum and energy, and results stay
// bitwise the same for any thread count.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <vector>

#include "darcydem/generation/generators.hpp"
#include "darcydem/output/probes.hpp"
#include "dem_setup.hpp"

namespace darcydem {
namespace {

/// Pairs of the list that touch through a periodic boundary (their centres
/// are more than half a period apart along some axis).
template <int D>
std::size_t contacts_across_boundaries(const Simulation<D>& sim) {
  const auto& p = sim.particles;
  const auto& L = sim.pair_list();
  std::size_t count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::uint32_t k = L.row_offset[i]; k < L.row_offset[i + 1]; ++k) {
      const std::uint32_t j = L.neighbour[k];
      const Vec<D> raw = p.position[j] - p.position[i];
      const Vec<D> d = sim.periodic.shortest(raw);
      if (d.norm() >= p.radius[i] + p.radius[j]) continue;
      bool across = false;
      for (int a = 0; a < D; ++a) {
        across = across || (sim.periodic.periodic[a] && std::abs(raw[a]) > 0.5 * sim.periodic.length[a]);
      }
      count += across ? 1 : 0;
    }
  }
  return count;
}

/// A square (2D) or cubic (3D) lattice of n^D grains of radius r at spacing
/// s = 2 r - delta, filling a period of n s along every axis from an odd
/// offset, the first layer a third of a spacing in (so the last one's
/// grains reach across the boundary): as a piece of an infinite lattice
/// every grain touches its 2D neighbours with the force k_n delta, which
/// cancel. Love and Weber's stress over the period is then
/// sigma_kk = (N D contacts x s x k_n delta along their axes) / (N s^D) /
/// D = k_n delta / s^(D-1), shear zero. Round-off: the overlap delta =
/// 1e-6 m is found from positions of up to 0.05 m, whose last bits (1e-17
/// m) are 1e-11 of delta (measured: forces cancel to 1.4e-11 of k_n delta);
/// 1e-9 bounds it with a margin of 100.
template <int D>
void check_compressed_lattice(int n) {
  ContactSpec spec;
  spec.normal_stiffness = 1e4;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  auto sim = testing::single_material<D>(2650.0, spec);
  const double r = 5e-4;
  const double delta = 1e-6;
  const double s = 2.0 * r - delta;
  const double lower = -0.0123;
  for (int k = 0; k < D; ++k) sim.periodic.set_axis(k, lower, lower + n * s);
  std::int64_t total = 1;
  for (int k = 0; k < D; ++k) total *= n;
  for (std::int64_t c = 0; c < total; ++c) {
    Vec<D> x;
    std::int64_t rest = c;
    for (int k = 0; k < D; ++k) {
      x[k] = lower + (static_cast<double>(rest % n) + 1.0 / 3.0) * s;
      rest /= n;
    }
    sim.particles.add(x, r, 2650.0, 0, false);
  }
  const double m = 2650.0 * particle_volume<D>(r);
  sim.time_step = 0.1 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  const auto N = static_cast<std::size_t>(total);
  ASSERT_GT(N, sim.sort_threshold) << "the grains must be reordered along the cells";
  ASSERT_GT(sim.pair_list().block_count(), 1) << "pairs across force blocks must be exercised";

  EXPECT_EQ(sim.contact_count(), D * N) << "every grain has 2D neighbours, across the boundaries too";
  EXPECT_GT(contacts_across_boundaries(sim), 0U);
  const double kd = spec.normal_stiffness * delta;
  double worst_force = 0.0;
  for (std::size_t i = 0; i < N; ++i) worst_force = std::max(worst_force, sim.particles.force[i].norm());
  EXPECT_LT(worst_force, 1e-9 * kd) << "the neighbours' forces cancel on every grain";
  // Over the period, and over a box of the same size across its ends (the
  // grains beyond an end counted at their images in the box), and over one
  // of a few lattice periods across them: every box of whole lattice
  // periods holds the same stress.
  const double expected = kd / std::pow(s, D - 1);
  const Vec<D> straddling = Vec<D>::Constant(lower + (n / 2 + 0.37) * s);
  const std::array<std::pair<Vec<D>, Vec<D>>, 3> boxes = {
      std::pair{Vec<D>::Constant(lower), Vec<D>::Constant(lower + n * s)},
      std::pair{straddling, Vec<D>(straddling + Vec<D>::Constant(n * s))},
      std::pair{Vec<D>::Constant(lower + (n - 2.5) * s), Vec<D>::Constant(lower + (n + 1.5) * s)}};
  double worst_stress = 0.0;
  for (const auto& [lo, hi] : boxes) {
    const auto sigma = sim.contact_stress(lo, hi);
    worst_stress = std::max(worst_stress, std::abs(sigma(0, 0) / expected - 1.0));
    for (int a = 0; a < D; ++a) {
      EXPECT_NEAR(sigma(a, a), expected, 1e-9 * expected) << "axis " << a << ", box from " << lo[0];
      for (int b = 0; b < D; ++b) {
        if (b != a) {
          EXPECT_NEAR(sigma(a, b), 0.0, 1e-9 * expected);
        }
      }
    }
  }

  // In equilibrium nothing moves: a grain whose neighbour across a boundary
  // were missed would be pushed by k_n delta and move by about delta within
  // a contact period (the run lasts 30 of them).
  const std::vector<Vec<D>> start = [&] {
    std::vector<Vec<D>> x(N);
    for (std::size_t i = 0; i < N; ++i) x[sim.particles.id[i]] = sim.particles.position[i];
    return x;
  }();
  sim.advance(300);
  double worst_move = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    const Vec<D> moved = sim.periodic.shortest(sim.particles.position[i] - start[sim.particles.id[i]]);
    worst_move = std::max(worst_move, moved.norm());
  }
  EXPECT_LT(worst_move, 1e-6 * delta);
  std::printf(
      "%dD lattice: %zu contacts across boundaries; largest force %.3e of k delta; stress %.3e of k "
      "delta / s^(D-1) off; largest move %.3e of delta\n",
      D, contacts_across_boundaries(sim), worst_force / kd, worst_stress, worst_move / delta);
}

TEST(Periodic, CompressedSquareLatticeHasTheStaticsOfAnInfiniteOne) { check_compressed_lattice<2>(70); }
TEST(Periodic, CompressedCubicLatticeHasTheStaticsOfAnInfiniteOne) { check_compressed_lattice<3>(17); }

/// Two spheres meeting head-on along x at +-v, with a surface gap g, either
/// in the middle of the period or with their contact point on the periodic
/// boundary. Returns their velocities along x afterwards.
std::array<double, 2> head_on_collision(bool across, double restitution) {
  ContactSpec spec;
  spec.normal_stiffness = 1e4;
  spec.restitution = restitution;
  spec.friction = 0.3;
  auto sim = testing::single_material<3>(2650.0, spec);
  const double r = 5e-4;
  const double g = 0.5 * r;
  const double L = 10.0 * r;
  const double lower = 0.0371;
  for (int k = 0; k < 3; ++k) sim.periodic.set_axis(k, lower, lower + L);
  const double v = 0.05;
  const Vec<3> centre = Vec<3>::Constant(lower + 0.5 * L);
  Vec<3> a = centre;
  Vec<3> b = centre;
  if (across) {
    a.x() = lower + L - (r + 0.5 * g);
    b.x() = lower + (r + 0.5 * g);
  } else {
    a.x() -= r + 0.5 * g;
    b.x() += r + 0.5 * g;
  }
  sim.particles.add(a, r, 2650.0, 0, false, Vec<3>(v, 0, 0));
  sim.particles.add(b, r, 2650.0, 0, false, Vec<3>(-v, 0, 0));
  const double m = 2650.0 * particle_volume<3>(r);
  const double contact_time = std::numbers::pi * std::sqrt(0.5 * m / spec.normal_stiffness);
  sim.time_step = 0.01 * std::sqrt(m / spec.normal_stiffness);
  sim.prepare();
  // Until they have met and parted (and before they could meet again).
  const double duration = 0.5 * g / v + 2.0 * contact_time;
  sim.advance(static_cast<std::uint64_t>(duration / sim.time_step));
  EXPECT_EQ(sim.contact_count(), 0U);
  const std::size_t ia = sim.particles.id[0] == 0 ? 0 : 1;
  return {sim.particles.velocity[ia].x(), sim.particles.velocity[1 - ia].x()};
}

// Across the boundary the pair sees the same separation as inside, so the
// collision is the same one: velocities agree to round-off (positions near
// the boundary differ in their last bits, 1e-12 of v bounds that). The
// rebound speed is e v (the damping is calibrated to e; 0.5 % as in the
// normal-impact case, for the time discretisation) and momentum is kept.
TEST(Periodic, CollisionAcrossTheBoundaryIsTheSameCollisionAsInside) {
  const double v = 0.05;
  for (double e : {1.0, 0.5}) {
    const auto inside = head_on_collision(false, e);
    const auto across = head_on_collision(true, e);
    EXPECT_NEAR(across[0], inside[0], 1e-12 * v) << "e = " << e;
    EXPECT_NEAR(across[1], inside[1], 1e-12 * v) << "e = " << e;
    EXPECT_NEAR(across[0], -e * v, 0.005 * e * v) << "e = " << e;
    EXPECT_NEAR(across[0] + across[1], 0.0, 1e-15) << "momentum, e = " << e;
    std::printf("e = %.1f: rebound %.9f of v across, %.9f inside\n", e, -across[0] / v, -inside[0] / v);
  }
}

// An elastic gas of discs (restitution 1, frictionless) drifting through a
// box periodic along both axes: no wall takes momentum, so the total
// momentum stays what it was to round-off (1e-12 of sum m |v|), and the
// energy (kinetic + springs) to 1e-6 as in the closed-box energy test (the
// same step, 0.002 sqrt(m / k_n), whose Verlet error that bound covers).
// Grains must cross the boundaries and collide across them.
TEST(Periodic, ElasticGasKeepsItsMomentumAndEnergy) {
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  spec.restitution = 1.0;
  auto sim = testing::single_material<2>(2650.0, spec);
  const double L = 0.01;
  sim.periodic.set_axis(0, 0.0, L);
  sim.periodic.set_axis(1, -0.5 * L, 0.5 * L);
  RadiusDistribution d;
  d.kind = RadiusDistribution::Kind::uniform;
  d.min = 4e-4;
  d.max = 6e-4;
  const auto pk = random_packing<2>(Vec<2>(0.0, -0.5 * L), Vec<2>(L, 0.5 * L), 40, d, 3, 1000);
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> thermal(-0.15, 0.15);
  for (std::size_t k = 0; k < pk.position.size(); ++k) {
    const Vec<2> v(0.3 + thermal(rng), 0.2 + thermal(rng));
    sim.particles.add(pk.position[k], pk.radius[k], 2650.0, 0, false, v);
  }
  const double m_min = 2650.0 * particle_volume<2>(d.min);
  sim.time_step = 0.002 * std::sqrt(m_min / spec.normal_stiffness);
  sim.prepare();
  auto momentum = [&] {
    Vec<2> sum = Vec<2>::Zero();
    for (std::size_t i = 0; i < sim.particles.size(); ++i)
      sum += sim.particles.velocity[i] / sim.particles.inv_mass[i];
    return sum;
  };
  double scale = 0.0;
  for (std::size_t i = 0; i < sim.particles.size(); ++i) {
    scale += sim.particles.velocity[i].norm() / sim.particles.inv_mass[i];
  }
  const Vec<2> p0 = momentum();
  auto energy = [&] { return sim.kinetic_energy() + sim.elastic_energy(); };
  const double e0 = energy();
  double worst_energy = 0.0;
  double worst_momentum = 0.0;
  std::size_t across = 0;
  std::size_t crossings = 0;
  std::vector<Vec<2>> last(sim.particles.position);
  const std::uint64_t steps = 120000;  // about 0.055 s: 1.6 periods at the drift speed
  for (std::uint64_t s = 0; s < steps; s += 100) {
    sim.advance(100);
    worst_energy = std::max(worst_energy, std::abs(energy() - e0) / e0);
    worst_momentum = std::max(worst_momentum, (momentum() - p0).norm() / scale);
    across += contacts_across_boundaries(sim);
    for (std::size_t i = 0; i < sim.particles.size(); ++i) {
      const Vec<2> jump = sim.particles.position[i] - last[i];
      crossings += (std::abs(jump.x()) > 0.5 * L || std::abs(jump.y()) > 0.5 * L) ? 1 : 0;
      last[i] = sim.particles.position[i];
    }
  }
  EXPECT_GT(crossings, 40U) << "grains must cross the periodic boundaries";
  EXPECT_GT(across, 10U) << "grains must collide across the periodic boundaries";
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_LT(worst_energy, 1e-6);
  std::printf("elastic gas: %zu boundary crossings, %zu contacts across seen; momentum %.3e, energy %.3e\n",
              crossings, across, worst_momentum, worst_energy);
}

/// A dense 3D settling periodic along x and y (a floor, no side walls):
/// 3000 spheres, two force blocks, reordered at every list build.
Simulation<3> periodic_settling() {
  ContactSpec spec;
  spec.normal_stiffness = 1e3;
  spec.restitution = 0.5;
  spec.friction = 0.5;
  auto sim = testing::single_material<3>(2650.0, spec);
  RadiusDistribution d;
  d.kind = RadiusDistribution::Kind::uniform;
  d.min = 4e-4;
  d.max = 6e-4;
  const auto pk = random_packing<3>(Vec<3>(0, 0, 0), Vec<3>(0.015, 0.015, 0.045), 3000, d, 7, 1000);
  for (std::size_t k = 0; k < pk.position.size(); ++k)
    sim.particles.add(pk.position[k], pk.radius[k], 2650.0, 0, false);
  sim.walls.push_back(testing::plane<3>(Vec<3>(0, 0, 0), Vec<3>(0, 0, 1)));
  sim.periodic.set_axis(0, 0.0, 0.015);
  sim.periodic.set_axis(1, 0.0, 0.015);
  sim.gravity = Vec<3>(0, 0, -500.0);  // strong, so the bed forms within the test
  sim.damping.local = 0.3;
  sim.time_step = 0.2 * sim.critical_time_step();
  sim.sort_threshold = 1000;
  return sim;
}

// As Reproducibility.BitwiseIdenticalForAnyThreadCount, with contacts
// across the periodic boundaries: 1 thread with single steps against 2
// threads with advance().
TEST(Periodic, BitwiseIdenticalForAnyThreadCount) {
  const auto a = testing::run_on_threads(periodic_settling, 1, true, 3000);
  const auto b = testing::run_on_threads(periodic_settling, 2, false, 3000);
  ASSERT_GT(a.contact_count(), 1000U) << "the packing must be in contact";
  ASSERT_GT(contacts_across_boundaries(a), 20U)
      << "contacts across the periodic boundaries must be exercised";
  ASSERT_GT(a.pair_list().cross_count(), 0U) << "pairs across force blocks must be exercised";
  std::printf("periodic settling: %zu contacts, %zu across the boundaries\n", a.contact_count(),
              contacts_across_boundaries(a));
  for (std::size_t i = 0; i < a.particles.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      ASSERT_EQ(a.particles.position[i][k], b.particles.position[i][k]) << "particle " << i;
      ASSERT_EQ(a.particles.angular_velocity[i][k], b.particles.angular_velocity[i][k]) << "particle " << i;
    }
    for (int k = 0; k < 2; ++k) {
      EXPECT_GE(a.particles.position[i][k], -0.5 * a.skin) << "within the period (and the skin's drift)";
      EXPECT_LT(a.particles.position[i][k], 0.015 + 0.5 * a.skin);
    }
  }
}

}  // namespace
}  // namespace darcydem

namespace darcydem {
namespace {

// Box probes across the ends of a period along x, [0, 10 mm): a box from 8
// to 12 mm holds the grains at 9 mm and at 1 mm (whose image is at 11 mm),
// not the one at 5 mm; their mean x is that of the images in the box,
// (9 + 11) / 2 mm. Exact: whole periods added to millimetres.
TEST(Periodic, BoxProbesCountTheImagesInTheBox) {
  ContactSpec spec;
  spec.normal_stiffness = 1e3;
  auto sim = testing::single_material<2>(2650.0, spec);
  for (double x : {0.001, 0.005, 0.009}) sim.particles.add(Vec<2>(x, 0.002), 0.0004, 2650.0, 0, false);
  sim.periodic.set_axis(0, 0.0, 0.01);
  sim.time_step = 0.1 * sim.critical_time_step();
  sim.prepare();
  ProbeSpec probe;
  probe.quantity = ProbeQuantity::particles_in_box;
  probe.box_min = {0.008, 0.0};
  probe.box_max = {0.012, 0.004};
  EXPECT_EQ(evaluate_probe(probe, sim), 2.0);
  probe.quantity = ProbeQuantity::mean_particle_position;
  probe.component = 0;
  EXPECT_NEAR(evaluate_probe(probe, sim), 0.010, 1e-15);
}

}  // namespace
}  // namespace darcydem
