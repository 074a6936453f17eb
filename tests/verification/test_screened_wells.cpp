// Screened wells ([[fluid.source]] with a `screen`, 3D): a well that draws
// from every cell its screen passes through, each joined to one bore
// pressure by its own well index. Against the 2D well, which
// test_fluid_sources.cpp checks against Theis and Thiem: a screen through
// the whole height of a layered aquifer between no-flow top and bottom is
// that well in every layer. And the superposition that finds the bore's
// pressure for a given inflow, against the same well holding that pressure.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "darcydem/fluid/pore_fluid.hpp"

using namespace darcydem;

namespace {

// Cells h x h across, hz along the wells; n x n of them across; no grains
// (porosity 1), constant isotropic permeability.
constexpr double h = 0.01;       // m
constexpr double hz = 0.02;      // m
constexpr int n = 41;            // cells along x and y (odd: a middle cell)
constexpr double kappa = 1e-10;  // m^2
constexpr double mu = 1e-3;      // Pa s
constexpr double bulk = 1e5;     // Pa
constexpr double r_w = h / 50.0;
constexpr double middle = 0.5 * n * h;

struct Well {
  FluidSourceType type;
  double value;  // m^3/s or Pa
  double x;      // m: where it crosses the first axis across its own
  std::array<double, 2> screen;
};

/// An aquifer of `layers` cells hz wide along `axis` (z: horizontal
/// layers and vertical wells; x: a drain along x), n x n of h across it:
/// its sides across the axis drained at u = 0, its two ends along the axis
/// no-flow.
PoreFluid<3> aquifer(int layers, const std::vector<Well>& wells, PressureSolverKind solver, int axis = 2) {
  PoreFluid<3> f(solver, 1e-13);
  f.grid.spacing = Vec<3>::Constant(h);
  f.grid.spacing[axis] = hz;
  f.grid.cells = {n, n, n};
  f.grid.cells[axis] = layers;
  f.fluid = {1000.0, mu, bulk};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<3>::Constant(kappa);
  for (int side = 0; side < 6; ++side) {
    f.sides[side] = side / 2 == axis ? FluidBoundary{}
                                     : FluidBoundary{FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  }
  int k = 0;
  for (const Well& w : wells) {
    FluidSource<3> s;
    s.name = "well" + std::to_string(k++);
    s.position = Vec<3>::Constant(middle);
    s.position[axis == 0 ? 1 : 0] = w.x;
    s.position[axis] = 0.5 * (w.screen[0] + w.screen[1]);
    s.type = w.type;
    s.value = TimeSeries::constant(w.value);
    s.radius = r_w;
    s.screen = w.screen;
    s.screen_axis = axis;
    f.sources.push_back(s);
  }
  ParticleData<3> none;
  f.initialize(none, {});
  return f;
}

PoreFluid<2> plane(FluidSourceType type, double value, PressureSolverKind solver) {
  PoreFluid<2> f(solver, 1e-13);
  f.grid.spacing = Vec<2>(h, h);
  f.grid.cells = {n, n};
  f.fluid = {1000.0, mu, bulk};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<2>::Constant(kappa);
  for (auto& side : f.sides) side = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.sources.push_back({"well", Vec<2>(middle, middle), type, TimeSeries::constant(value), r_w});
  ParticleData<2> none;
  f.initialize(none, {});
  return f;
}

/// What each cell of screened well i took from its bore, m^3/s.
std::vector<double> cell_inflows(const PoreFluid<3>& f, std::size_t i) {
  std::vector<double> out;
  for (const auto& [cell, index] : f.screen_well_indices(i))
    out.push_back(index * (f.well_pressure(i) - f.pressure()[cell]));
  return out;
}

// Steps: transient ones of 1 ms, then steady ones of 100 s (the grid's
// diffusion time L^2 mu / (kappa K_f) is 17 s).
const std::vector<double> steps = {1e-3, 1e-3, 1e-3, 1e-3, 1e-3, 100.0, 100.0, 100.0, 100.0, 100.0};

}  // namespace

TEST(ScreenedWells, AScreenThroughTheWholeAquiferIsThePlanesWellInEveryLayer) {
  // Between a no-flow top and bottom, a screen through every layer draws
  // alike from each: the flow is horizontal, each layer's equations are
  // the 2D grid's times its height hz (storage, conductances, and each
  // cell's well index, Peaceman's 2D index times the screen's length in
  // it). So every layer's pressures are the 2D well's, given Q / H per
  // metre or holding the same bore pressure, at every step, the transient
  // too; each cell takes hz / H of the well's inflow. Bounds 1e-9 of the
  // scale: the solves are to 1e-13, the bore's pressure found by
  // superposition to the same. Both solvers.
  // The same along x, a drain between no-flow ends: the plane across it
  // is (y, z).
  const int layers = 4;
  const double height = layers * hz;
  const double q = -3e-7;  // m^3/s: pumped out
  for (const auto& [solver, axis] :
       {std::pair{PressureSolverKind::cg, 2}, std::pair{PressureSolverKind::cholesky, 2},
        std::pair{PressureSolverKind::cg, 0}}) {
    for (const auto type : {FluidSourceType::inflow, FluidSourceType::pressure}) {
      const double value = type == FluidSourceType::inflow ? q : -2.0;  // m^3/s or Pa at the bore
      PoreFluid<3> f = aquifer(layers, {{type, value, middle, {0.0, height}}}, solver, axis);
      PoreFluid<2> g = plane(type, type == FluidSourceType::inflow ? q / height : value, solver);
      ASSERT_EQ(f.screen_well_indices(0).size(), static_cast<std::size_t>(layers));
      EXPECT_NEAR(f.equivalent_radius(0), g.equivalent_radius(0), 1e-15);
      EXPECT_NEAR(f.well_index(0), g.well_index(0) * height, 1e-12 * f.well_index(0));
      ParticleData<3> none3;
      ParticleData<2> none2;
      double time = 0.0;
      for (const double dt : steps) {
        time += dt;
        f.update(none3, dt, time, {});
        g.update(none2, dt, time, {});
        ASSERT_LT(std::abs(f.last_balance().imbalance()), 1e-10 * f.last_balance().gross) << "t = " << time;
        const double scale = std::abs(g.well_pressure(0));
        double apart = 0.0;
        for (int k = 0; k < layers; ++k) {
          for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
              const std::array<int, 3> at = axis == 2 ? std::array{i, j, k} : std::array{k, i, j};
              apart = std::max(apart,
                               std::abs(f.pressure()[f.grid.index(at)] - g.pressure()[g.grid.index({i, j})]));
            }
          }
        }
        EXPECT_LT(apart, 1e-9 * scale) << "t = " << time;
        EXPECT_NEAR(f.well_pressure(0), g.well_pressure(0), 1e-9 * scale) << "t = " << time;
        EXPECT_NEAR(f.source_inflow(0), g.source_inflow(0) * height, 1e-9 * std::abs(f.source_inflow(0)));
        for (const double c : cell_inflows(f, 0))
          EXPECT_NEAR(c, f.source_inflow(0) * hz / height, 1e-9 * std::abs(q));
      }
      std::printf("%s, along %c, %s: bore %.6f Pa (2D %.6f), inflow %.6e m^3/s (2D x H %.6e)\n",
                  to_string(solver).c_str(), "xyz"[axis],
                  type == FluidSourceType::inflow ? "given inflow" : "held bore", f.well_pressure(0),
                  g.well_pressure(0), f.source_inflow(0), g.source_inflow(0) * height);
    }
  }
}

TEST(ScreenedWells, AGivenInflowPutsTheBoreWhereHoldingItTakesThatInflow) {
  // Two partially penetrating wells, screens ending inside cells (a quarter
  // and a half of a cell), one pumping and one injecting: each given
  // inflow puts its bore at some pressure at steady state; holding those
  // pressures, the wells must take those inflows, and the fields be the
  // same (linearity and uniqueness; the superposition's 2 x 2 system for
  // the bores' pressures couples the wells). Bounds 1e-9 as above. Both
  // solvers; the water balance at every step, and each well's cells' shares
  // adding up to its inflow.
  const int layers = 8;
  const std::array<double, 2> screen_a{0.035, 0.125};  // cells 1 (1/4) to 6 (1/4)
  const std::array<double, 2> screen_b{0.02, 0.09};    // cells 1 to 4 (1/2)
  const double xa = middle - 8 * h;
  const double xb = middle + 8 * h;
  const double qa = -4e-7;
  const double qb = 1e-7;
  for (const auto solver : {PressureSolverKind::cg, PressureSolverKind::cholesky}) {
    PoreFluid<3> given = aquifer(
        layers, {{FluidSourceType::inflow, qa, xa, screen_a}, {FluidSourceType::inflow, qb, xb, screen_b}},
        solver);
    ASSERT_EQ(given.screen_well_indices(0).size(), 6U);
    ASSERT_EQ(given.screen_well_indices(1).size(), 4U);
    ParticleData<3> none;
    double time = 0.0;
    for (const double dt : steps) {
      time += dt;
      given.update(none, dt, time, {});
      ASSERT_LT(std::abs(given.last_balance().imbalance()), 1e-10 * given.last_balance().gross)
          << "t = " << time;
      for (std::size_t w = 0; w < 2; ++w) {
        double sum = 0.0;
        for (const double c : cell_inflows(given, w)) sum += c;
        EXPECT_NEAR(sum, w == 0 ? qa : qb, 1e-9 * std::abs(qa)) << "well " << w << ", t = " << time;
      }
    }
    const double pa = given.well_pressure(0);
    const double pb = given.well_pressure(1);
    PoreFluid<3> held = aquifer(
        layers,
        {{FluidSourceType::pressure, pa, xa, screen_a}, {FluidSourceType::pressure, pb, xb, screen_b}},
        solver);
    time = 0.0;
    for (const double dt : steps) {
      time += dt;
      held.update(none, dt, time, {});
    }
    double apart = 0.0;
    for (std::size_t c = 0; c < given.pressure().size(); ++c)
      apart = std::max(apart, std::abs(held.pressure()[c] - given.pressure()[c]));
    std::printf(
        "%s: bores %.6f and %.6f Pa; held there the wells take %.9e and %.9e m^3/s (given %.3e, %.3e); "
        "fields %.2e Pa apart\n",
        to_string(solver).c_str(), pa, pb, held.source_inflow(0), held.source_inflow(1), qa, qb, apart);
    EXPECT_NEAR(held.source_inflow(0), qa, 1e-9 * std::abs(qa));
    EXPECT_NEAR(held.source_inflow(1), qb, 1e-9 * std::abs(qa));
    EXPECT_LT(apart, 1e-9 * std::abs(pa));
    EXPECT_NEAR(held.well_pressure(0), pa, 1e-12 * std::abs(pa));
    // A partially penetrating well draws most, per metre of screen, at the
    // ends of its screen, where the water comes from above and below as
    // well as from the side (Muskat's uniform-potential well): the pumping
    // well's end cells take more per metre than its middle ones.
    const auto shares = cell_inflows(given, 0);
    const auto nodes = given.screen_well_indices(0);
    std::vector<double> per_metre;
    for (std::size_t c = 0; c < shares.size(); ++c) per_metre.push_back(shares[c] / nodes[c].second);
    // (Per unit of well index, which is proportional to the length: the
    // drawdown p_c - p_w.) Pumping: the shares are negative; the ends draw
    // more, so they are the most negative.
    EXPECT_LT(per_metre.front(), per_metre[2]);
    EXPECT_LT(per_metre.back(), per_metre[3]);
  }
}
