// Drains ([[fluid.source]] with drain = true): a source holding a pressure
// that only takes water out (a relief well, a toe drain; MODFLOW's drain).
// Against the closed form of a column seeped upwards with a drain at mid
// height, shut and open; and, as the inflow rises and falls, the
// complementarity that defines a drain at every step: shut, the water at
// it stands at or below its pressure; open, it gives no water.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "darcydem/fluid/pore_fluid.hpp"

using namespace darcydem;

namespace {

// A column of N cells h high, one wide; no grains (porosity 1); constant
// permeability; inflow q (m/s) at the floor, the top drained at u = 0.
constexpr double h = 0.01;       // m
constexpr int cells = 20;        // along the column
constexpr double kappa = 1e-13;  // m^2
constexpr double mu = 1e-3;      // Pa s
constexpr double bulk = 1e8;     // Pa
constexpr double height = cells * h;
constexpr int drain_cell = 9;                       // its centre 95 mm up
constexpr double drain_y = (drain_cell + 0.5) * h;  // m
constexpr double resistance = mu / kappa;           // Pa s / m^2: u drop per metre per m/s

enum class Kind { point, bore, screen };

template <int D>
PoreFluid<D> column(const TimeSeries& inflow, double drain_pressure, Kind kind,
                    PressureSolverKind solver = PressureSolverKind::cg) {
  PoreFluid<D> f(solver, 1e-13);
  f.grid.spacing = Vec<D>::Constant(h);
  f.grid.cells.fill(1);
  f.grid.cells[D - 1] = cells;
  f.fluid = {1000.0, mu, bulk};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<D>::Constant(kappa);
  f.sides[2 * (D - 1)] = {FluidBoundaryType::flux, inflow};
  f.sides[2 * (D - 1) + 1] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  FluidSource<D> s;
  s.name = "drain";
  s.position = Vec<D>::Constant(0.5 * h);
  s.position[D - 1] = drain_y;
  s.type = FluidSourceType::pressure;
  s.value = TimeSeries::constant(drain_pressure);
  s.drain = true;
  if (kind != Kind::point) s.radius = h / 20.0;
  if constexpr (D == 3) {
    if (kind == Kind::screen) s.screen = {drain_y - 1.5 * h, drain_y + 1.5 * h};  // 3 cells
  }
  f.sources.push_back(s);
  ParticleData<D> none;
  f.initialize(none, {});
  return f;
}

}  // namespace

TEST(FluidDrains, ADrainBelowTheWaterTakesWhatComesUpAndOneAboveItStaysShut) {
  // Steady (steps of 1e4 s; the column's slowest mode decays at pi^2 c /
  // (4 H^2) = 0.68 1/s, c = kappa K_f / (mu n) with n = 0.9 (the porosity's
  // cap), so 5 implicit steps leave (1 + 6800)^-5 of the start), q = 1e-5 m/s: shut, the pressure is the
  // plain seepage's, u = q mu / kappa (H - y), at the drain, 105 mm below the top, 10.5 kPa. A drain held at
  // 15 kPa, above that, stays shut and gives nothing. Held at 4 kPa it opens: its cell is at 4 kPa, below it
  // all of q still rises to it, u = p_d + q mu / kappa (y_d - y); above it the plain seepage from p_d to 0, u
  // = p_d (H - y) / (H - y_d), which carries (kappa / mu) p_d / (H - y_d) of q; the drain takes the rest.
  // Exact for this scheme (the pressure is linear in each part): bounds 1e-9 of the pressure scale and of q,
  // solved by Cholesky, to round-off (CG's relative residual of 1e-13 leaves 1.6e-9 on this stiff column).
  const double q = 1e-5;
  const double scale = q * resistance * height;
  ParticleData<2> none;
  for (const double p_d : {15e3, 4e3}) {
    PoreFluid<2> f = column<2>(TimeSeries::constant(q), p_d, Kind::point, PressureSolverKind::cholesky);
    for (int s = 1; s <= 5; ++s) f.update(none, 1e4, 1e4 * s, {});
    const bool open = p_d < q * resistance * (height - drain_y);
    EXPECT_EQ(f.drain_open(0), open) << p_d;
    double worst = 0.0;
    for (int c = 0; c < cells; ++c) {
      const double y = (c + 0.5) * h;
      double expected = q * resistance * (height - y);
      if (open)
        expected =
            y <= drain_y ? p_d + q * resistance * (drain_y - y) : p_d * (height - y) / (height - drain_y);
      worst = std::max(worst, std::abs(f.pressure()[static_cast<std::size_t>(c)] - expected));
    }
    const double taken = open ? -(q - p_d / (resistance * (height - drain_y))) * h : 0.0;
    std::printf("drain held at %.0f Pa: %s, takes %.6e m^2/s (closed form %.6e), the field within %.2e Pa\n",
                p_d, open ? "open" : "shut", f.source_inflow(0), taken, worst);
    EXPECT_LT(worst, 1e-9 * scale);
    EXPECT_NEAR(f.source_inflow(0), taken, 1e-9 * q * h);
  }
}

TEST(FluidDrains, ADrainOpensAsTheWaterRisesAboveItAndShutsAsItFalls) {
  // The inflow rises from 0 to 2e-5 m/s over 10 s and falls back to 0 by
  // 20 s, in steps of 0.1 s: the drain opens when the water at it passes
  // its pressure and shuts when it falls below. At every step the drain
  // gives no water (its inflow <= 0), and shut, the water at it (its cell,
  // or its bore: a screened drain's bore floats, joining its cells) stands
  // at most at its pressure; open, a drain held in its cell has its cell at
  // that pressure. Bounds: 1e-9 of the pressure scale and of the flow (the
  // solves to 1e-13). The water balance at every step. A drain held in
  // its cell, one with a bore (a radius), and a screened one across three
  // cells of a 3D column.
  TimeSeries inflow;
  inflow.times = {0.0, 10.0, 20.0};
  inflow.values = {0.0, 2e-5, 0.0};
  const double p_d = 8e3;  // Pa: the water reaches it at q = 7.6e-6 m/s
  const double scale = 2e-5 * resistance * height;
  for (const Kind kind : {Kind::point, Kind::bore, Kind::screen}) {
    PoreFluid<2> f2 = column<2>(inflow, p_d, kind);
    PoreFluid<3> f3 = column<3>(inflow, p_d, kind);
    int opened = 0;
    int shut = 0;
    bool was_open = false;
    for (int s = 1; s <= 200; ++s) {
      const double t = 0.1 * s;
      double q = 0.0;
      double at_drain = 0.0;
      bool open = false;
      double imbalance = 0.0;
      double gross = 0.0;
      if (kind == Kind::screen) {
        ParticleData<3> none;
        f3.update(none, 0.1, t, {});
        q = f3.source_inflow(0);
        at_drain = f3.well_pressure(0);
        open = f3.drain_open(0);
        imbalance = f3.last_balance().imbalance();
        gross = f3.last_balance().gross;
      } else {
        ParticleData<2> none;
        f2.update(none, 0.1, t, {});
        q = f2.source_inflow(0);
        at_drain = kind == Kind::point ? f2.pressure()[drain_cell] : f2.well_pressure(0);
        open = f2.drain_open(0);
        imbalance = f2.last_balance().imbalance();
        gross = f2.last_balance().gross;
      }
      ASSERT_LT(std::abs(imbalance), 1e-10 * gross) << "t = " << t;
      EXPECT_LE(q, 1e-9 * 2e-5 * h) << "t = " << t;  // never gives water
      if (open) {
        EXPECT_NEAR(at_drain, p_d, 1e-9 * scale) << "t = " << t;
      } else {
        EXPECT_EQ(q, 0.0) << "t = " << t;
        EXPECT_LE(at_drain, p_d + 1e-9 * scale) << "t = " << t;
      }
      opened += open && !was_open;
      shut += !open && was_open;
      was_open = open;
    }
    std::printf("drain (%s): opened %d time(s), shut %d\n",
                kind == Kind::point  ? "held in its cell"
                : kind == Kind::bore ? "with a bore"
                                     : "screened, 3D",
                opened, shut);
    EXPECT_EQ(opened, 1);
    EXPECT_EQ(shut, 1);
  }
}
