// Satake's fabric tensor of the contacts (Simulation::contact_fabric, the
// probe `fabric`), as YADE's fabricTensor and PFC's fabric measurement give
// it: (1/N_c) sum of n (x) n over the contacts between grains. Checked
// against lattices and chains whose contact directions are known by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <type_traits>

#include "dem_setup.hpp"
#include "scene_loading.hpp"

using namespace darcydem;

namespace {

constexpr double r = 5e-4;
constexpr double delta = 1e-6;  // every lattice's overlap
constexpr double s = 2.0 * r - delta;

template <int D>
Simulation<D> one_material() {
  ContactSpec spec;
  spec.normal_stiffness = 1e5;
  return darcydem::testing::single_material<D>(2650.0, spec);
}

template <int D>
Vec<D> big() {
  return Vec<D>::Constant(1.0);
}

/// |a - b| over the components, largest.
template <int D>
double worst(const typename Simulation<D>::Moment& a, const typename Simulation<D>::Moment& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace

// A hexagonal lattice of 12 x 12 discs overlapping by delta, periodic: each
// disc touches 6, along 0, 60 and 120 degrees: (1/3)(diag(1, 0) +
// diag(1/4, 3/4) twice, the off-diagonal terms +-sqrt(3)/4 cancelling) =
// I / 2. An FCC lattice of 4 x 4 x 4 cubes, periodic: 12 neighbours along
// (+-1, +-1, 0) / sqrt(2) and the like: I / 3. Round-off: 1e-12.
TEST(Fabric, OfIsotropicLatticesIsTheUnitTensorOverD) {
  {
    auto sim = one_material<2>();
    const int n = 12;
    const double row = s * std::sqrt(3.0) / 2.0;
    for (int j = 0; j < n; ++j) {
      for (int i = 0; i < n; ++i)
        sim.particles.add(Vec<2>((i + 0.25 + 0.5 * (j % 2)) * s, (j + 0.3) * row), r, 2650.0, 0, false);
    }
    sim.periodic.set_axis(0, 0.0, n * s);
    sim.periodic.set_axis(1, 0.0, n * row);
    sim.time_step = 0.1 * sim.critical_time_step();
    sim.prepare();
    ASSERT_EQ(sim.contact_count(), static_cast<std::size_t>(3 * n * n));
    EXPECT_LT(worst<2>(sim.contact_fabric(-big<2>(), big<2>()), 0.5 * Simulation<2>::Moment::Identity()),
              1e-12);
  }
  {
    auto sim = one_material<3>();
    const int n = 4;
    const double a = s * std::sqrt(2.0);  // the cube's side: face diagonals s long
    const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        for (int k = 0; k < n; ++k) {
          for (const auto& b : basis)
            sim.particles.add(Vec<3>((i + b[0] + 0.1) * a, (j + b[1] + 0.1) * a, (k + b[2] + 0.1) * a), r,
                              2650.0, 0, false);
        }
      }
    }
    for (int axis = 0; axis < 3; ++axis) sim.periodic.set_axis(axis, 0.0, n * a);
    sim.time_step = 0.1 * sim.critical_time_step();
    sim.prepare();
    ASSERT_EQ(sim.contact_count(), static_cast<std::size_t>(6 * 4 * n * n * n));
    EXPECT_LT(worst<3>(sim.contact_fabric(-big<3>(), big<3>()), Simulation<3>::Moment::Identity() / 3.0),
              1e-12);
  }
}

// A chain of 5 grains along a unit direction u (2D at 30 degrees, 3D along
// (1, 2, 2)/3): every contact's normal is +-u, so the fabric is u u^T
// (1e-12). A box round the chain's first two grains selects its contacts
// touching them (the grains' own and the next one's): the same tensor.
TEST(Fabric, OfAChainIsItsDirectionsDyad) {
  auto check = [](auto sim, const auto& u) {
    constexpr int D = std::decay_t<decltype(u)>::RowsAtCompileTime;
    for (int k = 0; k < 5; ++k)
      sim.particles.add(Vec<D>(Vec<D>::Constant(0.01) + k * s * u), r, 2650.0, 0, false);
    sim.time_step = 0.1 * sim.critical_time_step();
    sim.prepare();
    ASSERT_EQ(sim.contact_count(), 4U);
    const typename Simulation<D>::Moment dyad = u * u.transpose();
    EXPECT_LT(worst<D>(sim.contact_fabric(-big<D>(), big<D>()), dyad), 1e-12);
    const Vec<D> lo = Vec<D>::Constant(0.01) - Vec<D>::Constant(0.1 * r);
    const Vec<D> hi = lo + (s * u).cwiseAbs() + Vec<D>::Constant(0.2 * r);
    EXPECT_LT(worst<D>(sim.contact_fabric(lo, hi), dyad), 1e-12);
  };
  const double t = std::numbers::pi / 6.0;
  check(one_material<2>(), Vec<2>(std::cos(t), std::sin(t)));
  check(one_material<3>(), Vec<3>(1.0 / 3.0, 2.0 / 3.0, 2.0 / 3.0));
}

// A horizontal chain of 4 discs (3 contacts) and, apart from it, a vertical
// one of 3 (2 contacts) standing on a floor and pressed by a side wall: a box
// round both gives diag(3/5, 2/5) (the walls' contacts left out); a box
// round the vertical chain alone diag(0, 1); a box holding no grain NaN.
TEST(Fabric, CountsTheContactsOfTheGrainsInTheBoxButNotTheWalls) {
  auto sim = one_material<2>();
  for (int k = 0; k < 4; ++k) sim.particles.add(Vec<2>(0.01 + k * s, 0.01), r, 2650.0, 0, false);
  const double x_v = 0.02;
  for (int k = 0; k < 3; ++k) sim.particles.add(Vec<2>(x_v, r - delta + k * s), r, 2650.0, 0, false);
  sim.walls.push_back(darcydem::testing::plane<2>(Vec<2>(0.0, 0.0), Vec<2>(0.0, 1.0)));
  sim.walls.push_back(darcydem::testing::plane<2>(Vec<2>(x_v + r - delta, 0.0), Vec<2>(-1.0, 0.0)));
  sim.time_step = 0.1 * sim.critical_time_step();
  sim.prepare();
  ASSERT_EQ(sim.contact_count(), 3U + 2U + 1U + 3U);  // the floor's 1, the side wall's 3
  Simulation<2>::Moment both = Simulation<2>::Moment::Zero();
  both(0, 0) = 3.0 / 5.0;
  both(1, 1) = 2.0 / 5.0;
  EXPECT_LT(worst<2>(sim.contact_fabric(Vec<2>(0.0, 0.0), Vec<2>(0.03, 0.03)), both), 1e-12);
  Simulation<2>::Moment vertical = Simulation<2>::Moment::Zero();
  vertical(1, 1) = 1.0;
  EXPECT_LT(worst<2>(sim.contact_fabric(Vec<2>(0.015, 0.0), Vec<2>(0.03, 0.005)), vertical), 1e-12);
  EXPECT_TRUE(sim.contact_fabric(Vec<2>(0.05, 0.05), Vec<2>(0.06, 0.06)).array().isNaN().all());
}

// The probe through the runner: 3 discs of a column settled on a floor
// (kGood of the scene-error tests): the two contacts between them are
// vertical, so fabric yy = 1 and xx = xy = 0 (1e-12; written to 10 digits);
// before they touch (the first row: the generator places them 10 um
// apart, gap = 1e-5) NaN.
TEST(Fabric, ProbeFollowsTheSettlingColumn) {
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
normal_stiffness = 1e5
restitution = 0.5
friction = 0.5

[[wall]]
name = "floor"
point = [0.0, 0.0]
normal = [0.0, 1.0]
material = "sand"

[[particles]]
generator = "column"
material = "sand"
base = [0.0, 0.0]
count = 3
radius = 0.0005
gap = 1e-5

[output]
probe_interval = 0.01

[[probe]]
name = "fxx"
quantity = "fabric"
min = [-0.001, 0.0]
max = [0.001, 0.01]
component = "xx"

[[probe]]
name = "fyy"
quantity = "fabric"
min = [-0.001, 0.0]
max = [0.001, 0.01]
component = "yy"

[[probe]]
name = "fxy"
quantity = "fabric"
min = [-0.001, 0.0]
max = [0.001, 0.01]
component = "xy"

[[stage]]
name = "settle"
duration = 0.1
gravity = [0.0, -9.81]
local_damping = 0.5
)";
  const auto probes = darcydem::testing::run_scene_probes<2>("fabric_probe", scene_text);
  EXPECT_TRUE(std::isnan(probes.at("fyy").front()));
  EXPECT_NEAR(probes.at("fyy").back(), 1.0, 1e-12);
  EXPECT_NEAR(probes.at("fxx").back(), 0.0, 1e-12);
  EXPECT_NEAR(probes.at("fxy").back(), 0.0, 1e-12);
}
