// Verification of the pore fluid against closed forms and conservation laws
// (issue 3): Biot's undrained response, Darcy's law, the force balance of
// steady flow through a frozen packing, and conservation of fluid volume.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "darcydem/fluid/pore_fluid.hpp"
#include "darcydem/generation/generators.hpp"
#include "dem_setup.hpp"
#include "fluid_sums.hpp"

using namespace darcydem;

namespace {

constexpr double g = 9.80665;

/// Spheres of radii 0.4..0.5 mm (times `scale`) placed at random without
/// overlap (random sequential addition) in [0, 0.01]^2 x [0, 0.02]: a loose
/// packing, n about 0.77 on average and 0.6..0.9 from cell to cell; 1200
/// grains (about 5 per 2 mm cell) at scale 1, 9600 (38 per cell) at 0.5.
Packing<3> loose_random_packing(double scale = 1.0) {
  RadiusDistribution radii;
  radii.kind = RadiusDistribution::Kind::uniform;
  radii.min = 0.0004 * scale;
  radii.max = 0.0005 * scale;
  const auto count = static_cast<std::int64_t>(std::lround(1200.0 / (scale * scale * scale)));
  return random_packing<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.01, 0.02), count, radii, 11, 2000);
}

/// Equal spheres of 0.9 mm on a cubic lattice of 1 mm, in the same box:
/// every 2 mm cell holds 8 whole grains, so n = 1 - pi 0.9^3 / 6 = 0.618
/// in every cell.
Packing<3> regular_lattice_packing() {
  return lattice_packing<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.01, 0.02), 0.001, 0.00045);
}

/// The packing's spheres fixed in place, with a 5 x 5 x 10 grid of 2 mm
/// cells, inflow q at the bottom and the top drained; Kozeny-Carman with
/// the scene's default diameter, the packing's specific_surface_diameter.
PoreFluid<3> frozen_packing(ParticleData<3>& p, const Packing<3>& pk, DragLaw drag, PermeabilityModel model,
                            double q, PressureSolverKind solver = PressureSolverKind::cholesky,
                            CgPreconditioner preconditioner = CgPreconditioner::jacobi) {
  for (std::size_t i = 0; i < pk.position.size(); ++i) p.add(pk.position[i], pk.radius[i], 2650.0, 0, true);
  PoreFluid<3> f(solver, 1e-12, preconditioner);
  f.grid.origin = Vec<3>::Zero();
  f.grid.spacing = Vec<3>::Constant(0.002);
  f.grid.cells = {5, 5, 10};
  f.fluid = {1000.0, 1.0e-3, 2e9};
  f.drag = drag;
  f.permeability.model = model;
  f.permeability.intrinsic = Vec<3>::Constant(1e-10);
  f.permeability.diameter = specific_surface_diameter<3>(p.radius);
  f.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(q)};
  f.sides[5] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.initialize(p);
  // Nothing moves, so one implicit step of 1000 s is the steady state.
  f.update(p, 1000.0, 1000.0);
  return f;
}

PoreFluid<3> frozen_packing(ParticleData<3>& p, DragLaw drag, PermeabilityModel model, double q,
                            PressureSolverKind solver = PressureSolverKind::cholesky,
                            CgPreconditioner preconditioner = CgPreconditioner::jacobi) {
  return frozen_packing(p, loose_random_packing(), drag, model, q, solver, preconditioner);
}

/// Excess pressure on the bottom face: cell value plus the half-cell drop
/// that carries the imposed flux, summed times the face areas (N).
double bottom_thrust(const PoreFluid<3>& f, double q) {
  return darcydem::testing::floor_thrust(f, q, [](int, int) { return true; });
}

/// The fluid's force on the grains of a packing in steady upward flow q,
/// against the excess pressure's thrust on the floor.
struct ForceBalance {
  double seepage_miss = 0.0;  ///< (seepage force - drop x area) / (drop x area)
  double total_miss = 0.0;    ///< the same with buoyancy on both sides
  double sideways = 0.0;      ///< |horizontal force| / (drop x area + buoyancy)
};
ForceBalance force_balance(const Packing<3>& pk, DragLaw drag, PermeabilityModel model, double q,
                           DragCells cells = DragCells::centre, double kozeny_carman_diameter = 0.0) {
  ParticleData<3> p;
  auto f = frozen_packing(p, pk, drag, model, q);
  if (kozeny_carman_diameter > 0.0) {
    // Another d: the permeability again, and the steady state with it.
    f.permeability.diameter = kozeny_carman_diameter;
    f.initialize(p);
    f.update(p, 1000.0, 2000.0);
  }
  f.drag_cells = cells;
  const auto [total, solid] = darcydem::testing::fluid_force_on_grains(f, p, g);
  const double buoyancy = f.fluid.density * g * solid;
  const double thrust = bottom_thrust(f, q);
  const double expected = thrust + buoyancy;
  const ForceBalance b{(total.z() - buoyancy - thrust) / thrust, (total.z() - expected) / expected,
                       std::hypot(total.x(), total.y()) / expected};
  std::printf(
      "force balance: %zu grains, seepage force %.6e N against pressure drop x area %.6e N (%+.3f %%)\n",
      p.size(), total.z() - buoyancy, thrust, 100.0 * b.seepage_miss);
  return b;
}

/// Issue 3: the force on the grains is the drop times the area plus the
/// buoyancy within 1 %, the seepage part alone too, and no net sideways
/// force (no sideways flow) to the same relative accuracy.
void expect_force_balance(const Packing<3>& pk, DragLaw drag, PermeabilityModel model, double q) {
  const auto b = force_balance(pk, drag, model, q);
  EXPECT_LT(std::abs(b.total_miss), 0.01);
  EXPECT_LT(std::abs(b.seepage_miss), 0.01);
  EXPECT_LT(b.sideways, 0.01);
}

}  // namespace

TEST(PoreFluid, BiotUndrainedIncrement) {
  // Two cells sealed from each other (vanishing permeability) and from the
  // outside; a disc moves from cell 0 into cell 1 by a prescribed
  // displacement (zero velocity, so no fluid is carried). The Biot law
  // (Eq. 3) gives du = (K_f / n) dVs / V exactly in each cell.
  ParticleData<2> p;
  p.add(Vec<2>(0.95e-3, 0.5e-3), 0.2e-3, 2650.0, 0, true);
  p.add(Vec<2>(0.4e-3, 0.5e-3), 0.3e-3, 2650.0, 0, true);
  PoreFluid<2> f(PressureSolverKind::cholesky);
  f.grid.spacing = Vec<2>(1e-3, 1e-3);
  f.grid.cells = {2, 1};
  f.fluid = {1000.0, 1e-3, 1e7};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<2>::Constant(1e-40);
  f.initialize(p);
  const auto before = f.solid_volume();
  p.position[0].x() += 0.1e-3;
  f.update(p, 1e-6, 1e-6);
  const double v = f.grid.cell_volume();
  for (int c = 0; c < 2; ++c) {
    const double dvs = f.solid_volume()[c] - before[c];
    const double expected = f.fluid.bulk_modulus / f.porosity()[c] * dvs / v;
    EXPECT_NEAR(f.pressure()[c], expected, 1e-9 * std::abs(expected)) << "cell " << c;
  }
  EXPECT_GT(f.pressure()[1], 0.0);  // the grain moved into cell 1: compression
  EXPECT_LT(f.pressure()[0], 0.0);
}

TEST(PoreFluid, DarcyLawThroughUniformPermeability) {
  // Constant permeability: the steady pressure is exactly linear,
  // u(z) = q mu (H - z) / kappa, and what flows in at the bottom flows out at
  // the top. Tolerance 1e-9: only the direct solver's round-off.
  ParticleData<3> p;
  const double q = 1e-3;
  const auto f = frozen_packing(p, DragLaw::darcy, PermeabilityModel::constant, q);
  const double kappa = 1e-10;
  const double scale = q * f.fluid.viscosity * 0.02 / kappa;
  for (std::size_t c = 0; c < f.grid.size(); ++c) {
    const double z = f.grid.centre(f.grid.coords(c)).z();
    EXPECT_NEAR(f.pressure()[c], q * f.fluid.viscosity * (0.02 - z) / kappa, 1e-9 * scale);
  }
  const double area = 0.01 * 0.01;
  EXPECT_NEAR(f.side_inflow(4), q * area, 1e-12 * q * area);
  EXPECT_NEAR(f.side_inflow(5), -q * area, 1e-9 * q * area);
  // The sides' pressures (side_pressure) from the same line: the inlet
  // z = 0 at q mu H / kappa, the drained top at its 0, and a no-flow side
  // the mean of u over the height, q mu H / (2 kappa).
  EXPECT_NEAR(f.side_pressure(4), scale, 1e-9 * scale);
  EXPECT_NEAR(f.side_pressure(5), 0.0, 1e-12 * scale);
  EXPECT_NEAR(f.side_pressure(0), 0.5 * scale, 1e-9 * scale);
  EXPECT_NEAR(f.side_pressure(3), 0.5 * scale, 1e-9 * scale);
}

/// The steady flow through the frozen packing solved by CG on the grid's
/// stencil (GridOperator) with a preconditioner, against sparse Cholesky on
/// the stored matrix.
void expect_cg_agrees_with_cholesky(CgPreconditioner preconditioner) {
  ParticleData<3> p1;
  ParticleData<3> p2;
  const double q = 1e-4;
  const auto direct = frozen_packing(p1, DragLaw::darcy, PermeabilityModel::kozeny_carman, q);
  const auto iterative = frozen_packing(p2, DragLaw::darcy, PermeabilityModel::kozeny_carman, q,
                                        PressureSolverKind::cg, preconditioner);
  EXPECT_EQ(iterative.solver().describe(250),
            "cg (" + darcydem::to_string(preconditioner) + " preconditioner)");
  double largest = 0.0;
  double difference = 0.0;
  for (std::size_t c = 0; c < direct.grid.size(); ++c) {
    largest = std::max(largest, std::abs(direct.pressure()[c]));
    difference = std::max(difference, std::abs(direct.pressure()[c] - iterative.pressure()[c]));
  }
  ASSERT_GT(largest, 0.0);
  EXPECT_GT(iterative.last_solve().iterations, 1);
  // CG to a relative residual of 1e-12 on a matrix of condition number
  // about 10^3 (250 cells): the pressures agree to about 1e-9 of the largest.
  EXPECT_LT(difference, 1e-8 * largest);
}

TEST(PoreFluid, ConjugateGradientsOnTheStencilAgreeWithCholesky) {
  expect_cg_agrees_with_cholesky(CgPreconditioner::jacobi);
}

TEST(PoreFluid, MultigridConjugateGradientsAgreeWithCholesky) {
  // 250 cells: the grid and one coarse level of 45 cells.
  expect_cg_agrees_with_cholesky(CgPreconditioner::multigrid);
}

// The sum over grains of V_p grad u / (1 - n) equals the integral of
// grad u only on average over each cell: each grain takes the values of the
// cell that holds its centre, though its volume is shared among cells.

TEST(PoreFluid, ForceBalanceDarcyDrag) {
  // Constant k: measured -0.75 % with 5 grains per cell.
  expect_force_balance(loose_random_packing(), DragLaw::darcy, PermeabilityModel::constant, 1e-3);
}

TEST(PoreFluid, ForceBalanceDarcyDragWithKozenyCarman) {
  // With Kozeny-Carman each cell has its own k, and the drag of a grain
  // goes as 1/((1 - n) k), a convex function of the cell's solid: cells
  // holding more centres than their share of solid weigh too much. With 5
  // grains per cell the sum is +3.0 % over the balance; with 38 per cell
  // (the same box, grains of half the size) +0.34 %, within issue 3's 1 %.
  const auto coarse =
      force_balance(loose_random_packing(1.0), DragLaw::darcy, PermeabilityModel::kozeny_carman, 1e-3);
  EXPECT_GT(coarse.seepage_miss, 0.0);
  EXPECT_LT(coarse.seepage_miss, 0.05);
  expect_force_balance(loose_random_packing(0.5), DragLaw::darcy, PermeabilityModel::kozeny_carman, 1e-3);
}

TEST(PoreFluid, ForceBalanceErgunWithKozenyCarman) {
  // Ergun's viscous term and Kozeny-Carman share the constant 150, so they
  // balance for equal grains in cells of one porosity. What remains is
  // hand-derived: in each cell the grains take (1 - n) of the seepage force
  // from the gradient and n from the drag, and the drag is beta / beta_KC
  // times the balancing one, beta_KC = 150 mu (1-n)^2 / (n d^2) and beta
  // Ergun's with its inertial term (1.75 Re, 3e-4 here at q = 1e-5 m/s)
  // blended into Wen-Yu's (weight 1 - phi = 0.7 % at n = 0.618). Expected
  // n (beta / beta_KC - 1) = -0.11 %; to 1e-5: the lattice fills its cells
  // exactly, so only the solver's round-off remains.
  const double q = 1e-5;
  const auto b =
      force_balance(regular_lattice_packing(), DragLaw::ergun, PermeabilityModel::kozeny_carman, q);
  const FluidProperties water{1000.0, 1.0e-3, 2e9};
  const double d = 0.0009;
  const double n = 1.0 - std::numbers::pi * d * d * d / 6.0 / 1e-9;
  const double beta_kc = 150.0 * water.viscosity * (1.0 - n) * (1.0 - n) / (n * d * d);
  const double expected = n * (ergun_wen_yu_beta(n, d, q / n, water) / beta_kc - 1.0);
  std::printf("expected from the laws: %+.4f %%\n", 100.0 * expected);
  EXPECT_NEAR(b.seepage_miss, expected, 1e-5);
  // So also within issue 3's 1 %, with the buoyancy and sideways.
  EXPECT_LT(std::abs(b.total_miss), 0.01);
  EXPECT_LT(b.sideways, 0.01);
}

TEST(PoreFluid, ErgunWithKozenyCarmanOnGradedGrainsAndLooseCells) {
  // Graded grains (radii uniform in 0.2..0.25 mm), loose cells, 38 grains
  // per cell. Ergun takes each grain's own d, so the drag goes with
  // sum V_p / d^2 ~ sum d; the pressure drop goes with 1 / d_KC^2. The
  // scene's default d_KC, the specific-surface (Sauter) diameter sum d^3 /
  // sum d^2, is within 0.2 % of the one that balances them exactly,
  // sqrt(sum d^3 / sum d): the drag about 0.4 % above. The arithmetic mean
  // diameter (the default before session 22) is 0.6 % below it, and the
  // balance was off by -1.49 %, outside issue 3's 1 %. Other offsets: the
  // centres' +0.34 % at 38 per cell (ForceBalanceDarcyDragWithKozenyCarman)
  // and the cells above n = 0.8 blended into Wen-Yu. Measured -0.27 %;
  // bound: the 1 %.
  const auto b =
      force_balance(loose_random_packing(0.5), DragLaw::ergun, PermeabilityModel::kozeny_carman, 1e-5);
  EXPECT_LT(std::abs(b.seepage_miss), 0.01);
  EXPECT_LT(std::abs(b.total_miss), 0.01);
  // With 5 grains per cell the centres' +3 % dominates (+2.2 %, not
  // asserted); drag_cells = overlaps takes it away (the test below).
}

TEST(PoreFluid, ErgunOnAWideGradingMissesByWhatTheRunLogSays) {
  // A sand graded from 0.3 to 1.2 mm by mass (Cu about 2), made at
  // porosity 0.75. Ergun's viscous drag goes as V_p / d_p^2 grain by
  // grain, Kozeny-Carman's pressure drop as 1 / d^2, so with the default
  // d, the specific-surface diameter, the drag is (d_s / d_e)^2 - 1 above
  // what the pressure drop needs, d_e = ergun_balance_diameter (the run
  // log's note says so). The drag carries the share n of the seepage
  // force in each cell, so the seepage force is off by about n (d_s /
  // d_e)^2 - n, n the packing's mean porosity (the flow-weighted mean
  // differs; the inertial term and the Wen-Yu blend above n = 0.8 add a
  // little): allowed 15 % of that (measured +11.43 % against +12.46 %).
  // The drag spread over the overlapped cells takes away the centres'
  // sampling offset. With d = d_e instead the balance is back within
  // issue 3's 1 % (measured -0.78 %: each cell's grains have their own
  // d_e, and cells above n = 0.8 blend into Wen-Yu; not separated).
  const auto g = RadiusDistribution::grading({0.3e-3, 0.6e-3, 1.2e-3}, {0.0, 0.4, 1.0}, 3);
  const auto pk = random_packing_to_porosity<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.01, 0.02), 0.75, g, 5, 2000);
  const double d_s = specific_surface_diameter<3>(pk.radius);
  const double d_e = ergun_balance_diameter<3>(pk.radius);
  const double excess = d_s * d_s / (d_e * d_e) - 1.0;
  double solid = 0.0;
  for (double r : pk.radius) solid += particle_volume<3>(r);
  const double n = 1.0 - solid / 2e-6;
  const auto off =
      force_balance(pk, DragLaw::ergun, PermeabilityModel::kozeny_carman, 1e-5, DragCells::overlaps);
  const auto on =
      force_balance(pk, DragLaw::ergun, PermeabilityModel::kozeny_carman, 1e-5, DragCells::overlaps, d_e);
  std::printf(
      "wide grading: %zu grains, n %.4f, d_s %.4f mm, d_e %.4f mm: the drag %+.2f %%, expected miss %+.2f "
      "%%\n",
      pk.radius.size(), n, d_s * 1e3, d_e * 1e3, 100.0 * excess, 100.0 * n * excess);
  EXPECT_GT(excess, 0.04);  // a grading wide enough to matter
  EXPECT_NEAR(off.seepage_miss, n * excess, 0.15 * n * excess);
  EXPECT_LT(std::abs(on.seepage_miss), 0.01);
}

TEST(PoreFluid, DragSpreadOverTheOverlappedCellsBalancesExactly) {
  // drag_cells = overlaps: each grain takes the cells it overlaps, weighted
  // by the overlap volumes, each cell's mean gradient -mu qbar / kappa and
  // Darcy drag. Summed over the grains, each cell then gets V_s (-g) + n V
  // (-g) = -V g exactly, and the cells' V g telescope to the pressure on
  // the grid's faces: the seepage force is the drop times the area to
  // round-off (1e-9), whatever the grains per cell, the permeability field
  // or the packing's aliasing with the cells (with the centre's cell:
  // -0.75 %, +3.0 %, +0.34 %, and -1.06 % on the 0.95 mm lattice).
  const auto lattice = lattice_packing<3>(Vec<3>::Zero(), Vec<3>(0.01, 0.01, 0.02), 0.00095, 0.00045);
  for (const auto& [name, pk, model] :
       {std::tuple{"loose, constant k", loose_random_packing(1.0), PermeabilityModel::constant},
        std::tuple{"loose, Kozeny-Carman", loose_random_packing(1.0), PermeabilityModel::kozeny_carman},
        std::tuple{"finer, Kozeny-Carman", loose_random_packing(0.5), PermeabilityModel::kozeny_carman},
        std::tuple{"0.95 mm lattice, Kozeny-Carman", lattice, PermeabilityModel::kozeny_carman}}) {
    const auto b = force_balance(pk, DragLaw::darcy, model, 1e-3, DragCells::overlaps);
    EXPECT_LT(std::abs(b.seepage_miss), 1e-9) << name;
    EXPECT_LT(b.sideways, 0.01) << name;
  }
  // Ergun with Kozeny-Carman: exactly the centre's figure on the regular
  // lattice (every grain in one cell), and on the loose packing (5 grains
  // per cell) the offsets of ErgunWithKozenyCarmanOnGradedGrainsAndLooseCells
  // without the centres' +3 %: measured -0.12 % (-1.34 % with the
  // arithmetic mean diameter); bound: issue 3's 1 %.
  const auto regular = force_balance(regular_lattice_packing(), DragLaw::ergun,
                                     PermeabilityModel::kozeny_carman, 1e-5, DragCells::overlaps);
  EXPECT_NEAR(regular.seepage_miss,
              force_balance(regular_lattice_packing(), DragLaw::ergun, PermeabilityModel::kozeny_carman, 1e-5)
                  .seepage_miss,
              1e-12);
  const auto loose = force_balance(loose_random_packing(1.0), DragLaw::ergun,
                                   PermeabilityModel::kozeny_carman, 1e-5, DragCells::overlaps);
  EXPECT_LT(std::abs(loose.seepage_miss), 0.01);
}

TEST(PoreFluid, SpreadDragWeighsEachCellByTheGrainsOverlap) {
  // drag_cells = overlaps with the Darcy drag: the force on a grain goes
  // with its own velocity as -V_p beta_bar v, beta_bar the mean over its
  // cells of n^2 mu / ((1 - n) kappa) (n clamped as for the permeability)
  // weighted by its overlap volumes. Hand-derived from the cells' fields
  // and the grain's overlaps (for_each_overlap) for every grain of the
  // frozen loose packing that spans more than one cell, changing its
  // velocity by 1 mm/s along each axis in turn; to 1e-9.
  ParticleData<3> p;
  auto f = frozen_packing(p, loose_random_packing(), DragLaw::darcy, PermeabilityModel::kozeny_carman, 1e-3);
  f.drag_cells = DragCells::overlaps;
  std::vector<std::vector<std::pair<std::size_t, double>>> cells(p.size());
  f.for_each_overlap(p, [&](std::size_t c, std::size_t i, double v) { cells[i].emplace_back(c, v); });
  std::vector<Vec<3>> before(p.size()), after(p.size());
  f.particle_forces(p, Vec<3>(0, 0, -g), before);
  std::size_t spanning = 0;
  double worst = 0.0;
  for (int k = 0; k < 3; ++k) {
    for (auto& v : p.velocity) v[k] += 1e-3;
    f.particle_forces(p, Vec<3>(0, 0, -g), after);
    for (auto& v : p.velocity) v[k] -= 1e-3;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (cells[i].size() < 2) continue;
      spanning += k == 0 ? 1U : 0U;
      double volume = 0.0;
      double beta = 0.0;
      for (const auto& [c, v] : cells[i]) {
        const double n =
            std::clamp(f.porosity()[c], f.permeability.min_porosity, f.permeability.max_porosity);
        volume += v;
        beta += v * n * n * f.fluid.viscosity / ((1.0 - n) * f.permeability_field()[c][k]);
      }
      const double expected = -particle_volume<3>(p.radius[i]) * beta / volume * 1e-3;
      const double change = after[i][k] - before[i][k];
      worst = std::max(worst, std::abs(change - expected) / std::abs(expected));
    }
  }
  EXPECT_GT(spanning, 500U);
  EXPECT_LT(worst, 1e-9);
}

TEST(PoreFluid, DragSpreadOverTheOverlappedCellsBalancesExactlyIn2D) {
  // The same in 2D: discs of radii 0.4..0.5 mm at random in a 10 x 20 mm
  // box, 5 x 10 cells of 2 mm (about 2.4 discs per cell), Kozeny-Carman, the
  // Darcy drag spread over the overlapped cells. The seepage force (the
  // vertical force less the buoyancy) equals the excess pressure on the
  // floor (each bottom cell's value plus the half-cell drop that carries
  // the inflow) times the faces' widths, to round-off (1e-9).
  RadiusDistribution radii;
  radii.kind = RadiusDistribution::Kind::uniform;
  radii.min = 0.0004;
  radii.max = 0.0005;
  const auto pk = random_packing<2>(Vec<2>::Zero(), Vec<2>(0.01, 0.02), 120, radii, 5, 4000);
  ParticleData<2> p;
  double solid = 0.0;
  for (std::size_t i = 0; i < pk.position.size(); ++i) {
    p.add(pk.position[i], pk.radius[i], 2650.0, 0, true);
    solid += std::numbers::pi * pk.radius[i] * pk.radius[i];
  }
  const double q = 1e-3;
  PoreFluid<2> f(PressureSolverKind::cholesky);
  f.grid.spacing = Vec<2>::Constant(0.002);
  f.grid.cells = {5, 10};
  f.fluid = {1000.0, 1.0e-3, 2e9};
  f.drag = DragLaw::darcy;
  f.drag_cells = DragCells::overlaps;
  f.permeability.model = PermeabilityModel::kozeny_carman;
  f.permeability.diameter = specific_surface_diameter<2>(p.radius);
  f.sides[2] = {FluidBoundaryType::flux, TimeSeries::constant(q)};
  f.sides[3] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.initialize(p);
  f.update(p, 1000.0, 1000.0);
  std::vector<Vec<2>> force(p.size());
  f.particle_forces(p, Vec<2>(0.0, -g), force);
  double total = 0.0;
  for (const auto& x : force) total += x.y();
  double thrust = 0.0;
  for (int i = 0; i < 5; ++i) {
    const std::size_t c = f.grid.index({i, 0});
    thrust += (f.pressure()[c] + q * f.fluid.viscosity / f.permeability_field()[c][1] * 0.001) * 0.002;
  }
  const double seepage = total - f.fluid.density * g * solid;
  std::printf("2D, %zu discs: seepage force %.9e N against %.9e N\n", p.size(), seepage, thrust);
  ASSERT_GT(thrust, 0.0);
  EXPECT_NEAR(seepage, thrust, 1e-9 * thrust);
}

TEST(PoreFluid, UserPermeabilityWithErgunBreaksTheBalance) {
  // REFERENCE.md: a user-given k with Ergun's beta does not balance; this
  // is why the "darcy" drag law exists. Here k is 10x Kozeny-Carman's, so
  // Ergun's drag is far too strong: the total exceeds the balance by > 10 %.
  ParticleData<3> p;
  const double q = 1e-4;
  auto f = frozen_packing(p, DragLaw::ergun, PermeabilityModel::kozeny_carman, q);
  double mean_kappa = 0.0;
  for (const auto& k : f.permeability_field()) mean_kappa += k.z() / f.grid.size();
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<3>::Constant(10.0 * mean_kappa);
  f.initialize(p);
  f.update(p, 1000.0, 1000.0);
  std::vector<Vec<3>> force(p.size());
  f.particle_forces(p, Vec<3>::Zero(), force);
  double total = 0.0;
  for (const auto& x : force) total += x.z();
  EXPECT_GT(total, 1.1 * bottom_thrust(f, q));
}

TEST(PoreFluid, DrainedSideFollowsItsTimeSeries) {
  // An empty 1 x 4 column, bottom sealed, top drained at a pressure ramped
  // from 0 to 100 Pa over 1 s and held: with a conductance far above the
  // storage the column follows the side's value at once, u = p(t) in every
  // cell (1e-6 relative: the lag is about storage / conductance x the
  // column's 4 cells in series, ~1e-9 of the change).
  ParticleData<2> p;
  PoreFluid<2> f(PressureSolverKind::cholesky);
  f.grid.spacing = Vec<2>(1e-3, 1e-3);
  f.grid.cells = {1, 4};
  f.fluid = {1000.0, 1e-3, 2e9};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<2>::Constant(1e-6);
  f.sides[3] = {FluidBoundaryType::drained, TimeSeries{{0.0, 1.0}, {0.0, 100.0}, 0.5}};
  f.initialize(p);
  for (double t : {0.25, 0.5, 0.75, 1.0, 1.5, 3.0}) {
    f.update(p, 1e-3, t);
    const double expected = t <= 0.5 ? 0.0 : (t >= 1.5 ? 100.0 : 100.0 * (t - 0.5));
    for (double u : f.pressure()) EXPECT_NEAR(u, expected, 1e-6 * 100.0) << "t = " << t;
  }
}

TEST(PoreFluid, AnisotropicPermeabilityActsPerAxis) {
  // A 4 x 4 block without grains, inflow q on x_min with x_max drained: the
  // pressure drop is q mu L / kappa_x; the same with the flow along y uses
  // kappa_y (5x smaller here, so a 5x larger drop). Exact for uniform kappa.
  auto drop = [](int axis) {
    ParticleData<2> p;
    PoreFluid<2> f(PressureSolverKind::cholesky);
    f.grid.spacing = Vec<2>(1e-3, 1e-3);
    f.grid.cells = {4, 4};
    f.fluid = {1000.0, 1e-3, 2e9};
    f.permeability.model = PermeabilityModel::constant;
    f.permeability.intrinsic = Vec<2>(1e-9, 2e-10);
    f.sides[2 * axis] = {FluidBoundaryType::flux, TimeSeries::constant(1e-3)};
    f.sides[2 * axis + 1] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
    f.initialize(p);
    f.update(p, 1000.0, 1000.0);
    // Cell centre nearest the inlet is 3.5 cells from the outlet face.
    return f.pressure()[0];
  };
  const double mu = 1e-3, q = 1e-3, l = 3.5e-3;
  EXPECT_NEAR(drop(0), q * mu * l / 1e-9, 1e-9 * q * mu * l / 1e-9);
  EXPECT_NEAR(drop(1), q * mu * l / 2e-10, 1e-9 * q * mu * l / 2e-10);
}

namespace {

/// Two grains in one cell of side `side`, no flow: grain 0 moves at v, grain
/// 1 is still. The force on each is the drag on its slip relative to the
/// cell's mean solid velocity, compared with the scalar drag laws of
/// fluid_laws.hpp (the force path batches Re^0.687 and folds the
/// coefficients per cell).
void expect_drag_law(DragLaw drag, double side, const Vec<3>& v) {
  ParticleData<3> p;
  p.add(Vec<3>(0.0011, 0.0011, 0.0011), 0.001, 2650.0, 0, false);
  p.add(Vec<3>(side - 0.0011, side - 0.0011, side - 0.0011), 0.001, 2650.0, 0, false);
  p.velocity[0] = v;
  PoreFluid<3> f;
  f.grid.origin = Vec<3>::Zero();
  f.grid.spacing = Vec<3>::Constant(side);
  f.grid.cells = {1, 1, 1};
  f.fluid = {1000.0, 1.0e-3, 2e9};
  f.drag = drag;
  f.permeability.model = PermeabilityModel::kozeny_carman;
  f.permeability.diameter = 0.002;
  f.initialize(p);
  std::vector<Vec<3>> force(2);
  f.particle_forces(p, Vec<3>::Zero(), force);
  const double n = std::clamp(f.porosity()[0], f.permeability.min_porosity, f.permeability.max_porosity);
  const double vp = 4.0 / 3.0 * std::numbers::pi * 1e-9;
  for (int i = 0; i < 2; ++i) {
    const Vec<3> slip = f.solid_velocity()[0] - p.velocity[i];
    Vec<3> expected;
    if (drag == DragLaw::ergun) {
      expected = ergun_wen_yu_beta(n, 0.002, slip.norm(), f.fluid) / (1.0 - n) * vp * slip;
    } else {
      const double kappa = kozeny_carman(0.002, n);
      expected = n * n * f.fluid.viscosity / kappa / (1.0 - n) * vp * slip;
    }
    // Round-off only: the batch's pow is within 4 ulp of std::pow.
    EXPECT_LT((force[i] - expected).norm(), 1e-12 * expected.norm()) << "grain " << i << ", n = " << n;
  }
}

}  // namespace

TEST(PoreFluid, GrainDragFollowsTheDragLaws) {
  // n = 0.85 (Wen-Yu weighs 98 %): Re about 350 and, faster, above 1000
  // where C_d Re switches to 0.44 Re.
  expect_drag_law(DragLaw::ergun, 0.00382, Vec<3>(0.05, -0.03, 0.2));
  expect_drag_law(DragLaw::ergun, 0.00382, Vec<3>(0.3, -0.2, 1.2));
  // n about 0.62 (grains cut by the grid's sides): Ergun dominant.
  expect_drag_law(DragLaw::ergun, 0.0028, Vec<3>(0.05, -0.03, 0.2));
  // Creeping slip (Re about 1e-6): Wen-Yu's Re^0.687 near zero.
  expect_drag_law(DragLaw::ergun, 0.0028, Vec<3>(1e-9, 0.0, 2e-9));
  expect_drag_law(DragLaw::darcy, 0.0028, Vec<3>(0.05, -0.03, 0.2));
}

namespace {

/// A fluid over an empty grid of `cells` with the given spacing, its
/// pressure set to u at the cell centres.
template <int D, class U>
PoreFluid<D> with_pressure(const std::array<int, D>& cells, const Vec<D>& spacing, U&& u) {
  ParticleData<D> p;
  PoreFluid<D> f(PressureSolverKind::cholesky);
  f.grid.origin = Vec<D>::Zero();
  f.grid.spacing = spacing;
  f.grid.cells = cells;
  f.fluid = {1000.0, 1e-3, 2e9};
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<D>::Constant(1e-10);
  f.initialize(p);
  std::vector<double> values(f.grid.size());
  for (std::size_t c = 0; c < values.size(); ++c) {
    const auto cc = f.grid.coords(c);
    Vec<D> x;
    for (int k = 0; k < D; ++k) x[k] = (cc[k] + 0.5) * spacing[k];
    values[c] = u(x);
  }
  f.set_pressure(values);
  return f;
}

/// Points spread over the part of the grid where every stencil corner is
/// an interior face (the holding cell not on the grid's side along its
/// component's axis, and between cell centres along the others).
template <int D>
std::vector<Vec<D>> interior_points(const std::array<int, D>& cells, const Vec<D>& spacing) {
  std::vector<Vec<D>> points;
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    Vec<D> x;
    for (int k = 0; k < D; ++k) {
      // [1, cells - 1] cells along k (a single cell: its centre).
      x[k] = cells[k] == 1 ? 0.5 * spacing[k] : (1.0 + (cells[k] - 2) * u(rng)) * spacing[k];
    }
    points.push_back(x);
  }
  return points;
}

}  // namespace

TEST(PoreFluid, StaggeredGradientIsExactForAQuadraticPressure) {
  // For a quadratic u, the face differences (u_b - u_a)/h are the exact
  // derivative at the face, and each component of grad u is linear in
  // every coordinate, which the staggered interpolation (linear between a
  // cell's faces along the component's axis, between cell centres along
  // the others) reproduces exactly. Tolerance: round-off of differences
  // of pressures of order 1e3 Pa over 1e-3 m (1e-9 of the gradient).
  const std::array<int, 3> cells = {5, 4, 3};
  const Vec<3> h(1e-3, 1.5e-3, 2e-3);
  auto u = [](const Vec<3>& x) {
    return 3e8 * x[0] * x[0] + 2e8 * x[0] * x[1] - 1e8 * x[1] * x[2] + 4e8 * x[2] * x[2] + 5e5 * x[1];
  };
  auto grad = [](const Vec<3>& x) {
    return Vec<3>(6e8 * x[0] + 2e8 * x[1], 2e8 * x[0] - 1e8 * x[2] + 5e5, -1e8 * x[1] + 8e8 * x[2]);
  };
  const auto f = with_pressure<3>(cells, h, u);
  for (const auto& x : interior_points<3>(cells, h)) {
    const Vec<3> expected = grad(x);
    EXPECT_LT((f.gradient_at(x) - expected).norm(), 1e-9 * expected.norm()) << x.transpose();
  }
  // One cell wide along x (the paper's column): x-pairs of faces are not
  // side by side in memory for the y and z components; u without x.
  const std::array<int, 3> column = {1, 4, 5};
  auto v = [](const Vec<3>& x) { return 2e8 * x[1] * x[2] - 3e8 * x[2] * x[2] + 1e5 * x[1]; };
  const auto g = with_pressure<3>(column, h, v);
  for (const auto& x : interior_points<3>(column, h)) {
    const Vec<3> expected(0.0, 2e8 * x[2] + 1e5, 2e8 * x[1] - 6e8 * x[2]);
    EXPECT_LT((g.gradient_at(x) - expected).norm(), 1e-9 * expected.norm()) << x.transpose();
  }
  // 2D.
  const std::array<int, 2> plane = {6, 5};
  const Vec<2> h2(1e-3, 1.2e-3);
  auto w = [](const Vec<2>& x) { return 1e8 * x[0] * x[0] - 4e8 * x[0] * x[1] + 2e8 * x[1] * x[1]; };
  const auto e = with_pressure<2>(plane, h2, w);
  for (const auto& x : interior_points<2>(plane, h2)) {
    const Vec<2> expected(2e8 * x[0] - 4e8 * x[1], -4e8 * x[0] + 4e8 * x[1]);
    EXPECT_LT((e.gradient_at(x) - expected).norm(), 1e-9 * expected.norm()) << x.transpose();
  }
}

TEST(PoreFluid, SetPressureChecksItsSize) {
  auto f = with_pressure<2>({3, 3}, Vec<2>(1e-3, 1e-3), [](const Vec<2>&) { return 1.0; });
  EXPECT_THROW(f.set_pressure(std::vector<double>(8, 0.0)), std::invalid_argument);
}

namespace {

/// A 2 x 2 x 2 grid of 1 mm cells at the origin; water (mu = 1e-3 Pa s,
/// K_f = 1e7 Pa), Ergun/Wen-Yu drag, Kozeny-Carman for grains of `diameter`.
void set_up_cube_of_cells(PoreFluid<3>& f, double diameter) {
  f.grid.origin = Vec<3>::Zero();
  f.grid.spacing = Vec<3>::Constant(1e-3);
  f.grid.cells = {2, 2, 2};
  f.fluid = {1000.0, 1.0e-3, 1e7};
  f.drag = DragLaw::ergun;
  f.permeability.model = PermeabilityModel::kozeny_carman;
  f.permeability.diameter = diameter;
}

}  // namespace

TEST(PoreFluid, GrainsOutsideTheGridFeelNoFluid) {
  // A 2 x 2 x 2 grid of 1 mm cells and still fluid: a grain whose centre is
  // in the grid (a cell's lower face included) feels exactly its buoyancy,
  // rho_f g V_p upwards; one whose centre is outside (an upper face
  // included) feels nothing, and grains_outside counts those.
  ParticleData<3> p;
  const double r = 2e-4;
  const std::vector<Vec<3>> inside = {Vec<3>(5e-4, 5e-4, 5e-4), Vec<3>(0.0, 5e-4, 1.5e-3)};
  const std::vector<Vec<3>> outside = {Vec<3>(2e-3, 5e-4, 5e-4), Vec<3>(5e-4, 5e-4, -1e-4),
                                       Vec<3>(5e-4, 2.5e-3, 5e-4)};
  for (const auto& x : inside) p.add(x, r, 2650.0, 0, false);
  for (const auto& x : outside) p.add(x, r, 2650.0, 0, false);
  PoreFluid<3> f;
  set_up_cube_of_cells(f, 2 * r);
  f.initialize(p);
  EXPECT_EQ(f.grains_outside(p), outside.size());
  std::vector<Vec<3>> force(p.size());
  f.particle_forces(p, Vec<3>(0.0, 0.0, -g), force);
  const double buoyancy = 1000.0 * g * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  for (std::size_t i = 0; i < inside.size(); ++i) {
    // Only round-off: V_p is computed as (4/3) pi r^3 here too.
    EXPECT_NEAR(force[i].z(), buoyancy, 1e-12 * buoyancy) << "grain " << i;
    EXPECT_EQ(force[i].head<2>().norm(), 0.0) << "grain " << i;
  }
  for (std::size_t i = inside.size(); i < p.size(); ++i) EXPECT_EQ(force[i].norm(), 0.0) << "grain " << i;
}

TEST(PoreFluid, GrainsOutsideTheGridBelowTheWaterLevelAreInStillWater) {
  // The grid of the test above with a free water surface at z = 2.5 mm,
  // 0.5 mm above its top. A grain outside the grid and below the surface
  // feels its buoyancy and the drag of a sphere alone in still water,
  // Schiller and Naumann's 3 pi mu d v (1 + 0.15 Re^0.687), written out
  // here; one above the surface feels nothing; one inside the grid is as
  // before (still fluid: its buoyancy alone).
  ParticleData<3> p;
  const double r = 2e-4;
  const Vec<3> v(0.01, 0.0, -0.02);
  p.add(Vec<3>(5e-4, 5e-4, 5e-4), r, 2650.0, 0, false);    // in the grid
  p.add(Vec<3>(5e-4, 5e-4, 2.2e-3), r, 2650.0, 0, false);  // above the grid, in the water, moving
  p.add(Vec<3>(-1e-3, 5e-4, 1e-3), r, 2650.0, 0, false);   // beside the grid, in the water, at rest
  p.add(Vec<3>(5e-4, 5e-4, 2.6e-3), r, 2650.0, 0, false);  // above the water
  p.velocity[1] = v;
  PoreFluid<3> f;
  set_up_cube_of_cells(f, 2 * r);
  f.water_level = 2.5e-3;
  f.initialize(p);
  EXPECT_EQ(f.grains_outside(p), 3U);
  EXPECT_EQ(f.grains_in_free_water(p), 2U);
  std::vector<Vec<3>> force(p.size());
  f.particle_forces(p, Vec<3>(0.0, 0.0, -g), force);
  const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const Vec<3> buoyancy(0.0, 0.0, 1000.0 * g * vp);
  const double re = 1000.0 * 2.0 * r * v.norm() / 1.0e-3;  // 4.47
  const Vec<3> drag = -3.0 * std::numbers::pi * 1.0e-3 * 2.0 * r * (1.0 + 0.15 * std::pow(re, 0.687)) * v;
  // Round-off only: the same formulas in another order.
  EXPECT_LT((force[0] - buoyancy).norm(), 1e-12 * buoyancy.norm());
  EXPECT_LT((force[1] - (buoyancy + drag)).norm(), 1e-12 * (buoyancy + drag).norm());
  EXPECT_LT((force[2] - buoyancy).norm(), 1e-12 * buoyancy.norm());
  EXPECT_EQ(force[3].norm(), 0.0);
}

TEST(PoreFluid, WaterAboveTheGridRisesWithTheOutflowBelowIt) {
  // The 2 x 2 x 2 grid of 1 mm cells, permeability 1e-10 m^2, the top
  // drained, and the top cells' excess pressures set by hand to c (Pa),
  // different in each column. The Darcy flux up through the top face of a
  // column is then (kappa/mu) c / (h/2), and the free water above the grid
  // rises at that speed (continuity across the surface), interpolated
  // linearly between the columns' centres and held beyond the outer ones.
  // Each grain there feels its buoyancy and Schiller and Naumann's drag
  // 3 pi mu d |w - v| (1 + 0.15 Re^0.687) along w - v, written out here;
  // beside the grid the water is still.
  const double r = 2e-4;
  const double h = 1e-3;
  const double kappa = 1e-10;
  const double mu = 1e-3;
  ParticleData<3> p;
  const Vec<3> v(0.002, 0.0, -0.004);
  p.add(Vec<3>(0.5e-3, 0.5e-3, 2.2e-3), r, 2650.0, 0, false);   // above column (0, 0), moving
  p.add(Vec<3>(0.75e-3, 0.5e-3, 2.4e-3), r, 2650.0, 0, false);  // a quarter of the way to column (1, 0)
  p.add(Vec<3>(1.0e-3, 1.0e-3, 2.1e-3), r, 2650.0, 0, false);   // between all four columns
  p.add(Vec<3>(0.2e-3, 1.9e-3, 2.3e-3), r, 2650.0, 0, false);   // beyond the outer centres of column (0, 1)
  p.add(Vec<3>(-0.5e-3, 0.5e-3, 2.2e-3), r, 2650.0, 0, false);  // beside the grid, at its top's height
  p.velocity[0] = v;
  PoreFluid<3> f;
  set_up_cube_of_cells(f, 2 * r);
  f.permeability.model = PermeabilityModel::constant;
  f.permeability.intrinsic = Vec<3>::Constant(kappa);
  f.sides[5] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  f.water_level = 3e-3;
  f.initialize(p);
  // The top cells' pressures, by column (i, j); cell index i + 2 j + 4 k.
  const std::array<double, 4> c = {20.0, 60.0, 100.0, 40.0};
  std::vector<double> u(8, 0.0);
  for (int col = 0; col < 4; ++col) u[4 + col] = c[col];
  f.set_pressure(u);
  std::array<double, 4> q{};
  for (int col = 0; col < 4; ++col) q[col] = kappa / mu * c[col] / (0.5 * h);  // 4, 12, 20, 8 mm/s
  const std::array<double, 5> w = {
      q[0], 0.75 * q[0] + 0.25 * q[1], 0.25 * (q[0] + q[1] + q[2] + q[3]), q[2], 0.0,
  };
  std::vector<Vec<3>> force(p.size());
  f.particle_forces(p, Vec<3>(0.0, 0.0, -g), force);
  const double vp = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec<3> slip = Vec<3>(0.0, 0.0, w[i]) - p.velocity[i];
    const double re = 1000.0 * 2.0 * r * slip.norm() / mu;
    const Vec<3> expected = Vec<3>(0.0, 0.0, 1000.0 * g * vp) +
                            3.0 * std::numbers::pi * mu * 2.0 * r * (1.0 + 0.15 * std::pow(re, 0.687)) * slip;
    // Round-off only: the same formulas in another order, and the
    // interpolation's weights (exact binary fractions here).
    EXPECT_LT((force[i] - expected).norm(), 1e-12 * expected.norm()) << "grain " << i;
  }
}

namespace {

/// The settling velocity of a sphere of diameter d and density rho_s in
/// still water (1000 kg/m^3, 1e-3 Pa s), where Schiller and Naumann's drag
/// 3 pi mu d v (1 + 0.15 Re^0.687) carries its submerged weight: by
/// bisection.
double terminal_velocity(double d, double rho_s) {
  const double mu = 1.0e-3;
  const double weight = (rho_s - 1000.0) * std::numbers::pi * d * d * d / 6.0 * g;
  auto drag = [&](double v) {
    const double re = 1000.0 * d * v / mu;
    return 3.0 * std::numbers::pi * mu * d * v * (1.0 + 0.15 * std::pow(re, 0.687));
  };
  double lo = 0.0;
  double hi = 1.0;
  for (int i = 0; i < 200; ++i) (drag(0.5 * (lo + hi)) < weight ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

/// A simulation holding one sphere at (1, 1, 100) mm, at rest: 100 mm
/// above the 2 x 2 x 2 mm grid of set_up_cube_of_cells.
auto lone_sphere(double r, double rho_s) {
  ContactSpec spec;
  spec.normal_stiffness = 1e3;
  spec.restitution = 0.5;
  auto sim = darcydem::testing::single_material<3>(rho_s, spec);
  sim.particles.add(Vec<3>(1e-3, 1e-3, 0.1), r, rho_s, 0, false);
  return sim;
}

}  // namespace

TEST(PoreFluid, AGrainSinksInStillWaterAtItsTerminalVelocity) {
  // A sphere (d = 0.5 mm, 2650 kg/m^3) released from rest in still water
  // above the grid (water_level far above it). Its equation of motion,
  // m dv/dt = (rho_s - rho_f) V g - 3 pi mu d v (1 + 0.15 Re^0.687), starts
  // at the submerged acceleration (1 - rho_f/rho_s) g and ends at the
  // terminal velocity where the drag carries the submerged weight, found
  // here by bisection (v_t = 7.84 cm/s, Re = 39).
  const double r = 2.5e-4;
  const double d = 2 * r;
  const double rho_s = 2650.0;
  const double v_terminal = terminal_velocity(d, rho_s);

  auto sim = lone_sphere(r, rho_s);
  PoreFluid<3> fluid;
  set_up_cube_of_cells(fluid, d);
  fluid.water_level = 1.0;
  fluid.initialize(sim.particles);
  sim.force_field = &fluid;
  sim.gravity = Vec<3>(0.0, 0.0, -g);
  sim.time_step = 1e-5;
  sim.prepare();
  // Ten steps: v = (1 - rho_f/rho_s) g t (1 - O(t / tau)), tau = m v_t /
  // submerged weight = 12.8 ms: within t / tau = 8e-3 of it (bound 2e-2).
  for (int s = 0; s < 10; ++s) sim.step();
  const double v_early = (1.0 - 1000.0 / rho_s) * g * 10 * sim.time_step;
  const double v_10 = -sim.particles.velocity[0].z();
  EXPECT_NEAR(v_10, v_early, 2e-2 * v_early);
  // 0.2 s is 15.6 tau and the approach to v_t is at least as fast as
  // exp(-t / tau) (the drag grows faster than linearly with the speed):
  // 2e-7 of v_t is left. The time step adds nothing there: the step's
  // fixed point is the velocity at which the forces balance. Bound 1e-5.
  for (int s = 10; s < 20000; ++s) sim.step();
  const Vec<3> v = sim.particles.velocity[0];
  std::printf(
      "still water: v after 10 steps %.6g m/s against %.6g; after 0.2 s %.10g m/s against v_t = %.10g\n",
      v_10, v_early, -v.z(), v_terminal);
  EXPECT_NEAR(-v.z(), v_terminal, 1e-5 * v_terminal);
  EXPECT_EQ(v.head<2>().norm(), 0.0);
}

TEST(PoreFluid, TheWaterTakesTheWorkOfGravityFromAGrainSinkingAtItsTerminalVelocity) {
  // The sinking sphere of the test above with the energy budget tracked.
  // Without contacts or damping the budget closes: gravity's work plus the
  // water's (buoyancy and drag, the force field's) is the kinetic energy,
  // to round-off (bound 1e-12 of gravity's work). Once the sphere sinks at
  // v_t the water takes all that gravity gives: over 0.15-0.2 s (more than
  // 11.7 tau, 8e-6 of v_t left to gain, so the kinetic energy grows by
  // 1.3e-6 of gravity's work there) the water's work is -m g v_t (0.05 s),
  // v_t by bisection, independent of the simulation; bound 1e-5.
  const double r = 2.5e-4;
  const double rho_s = 2650.0;
  const double v_terminal = terminal_velocity(2 * r, rho_s);
  const double m = rho_s * 4.0 / 3.0 * std::numbers::pi * r * r * r;

  auto sim = lone_sphere(r, rho_s);
  PoreFluid<3> fluid;
  set_up_cube_of_cells(fluid, 2 * r);
  fluid.water_level = 1.0;
  fluid.initialize(sim.particles);
  sim.force_field = &fluid;
  sim.gravity = Vec<3>(0.0, 0.0, -g);
  sim.time_step = 1e-5;
  sim.track_energy = true;
  sim.prepare();
  sim.advance(15000);
  const EnergyBudget before = sim.energy;
  sim.advance(5000);
  const EnergyBudget& after = sim.energy;
  const double kinetic = sim.kinetic_energy();
  EXPECT_NEAR(after.gravity_work + after.field_work, kinetic, 1e-12 * after.gravity_work);
  const double expected = -m * g * v_terminal * 5000 * sim.time_step;
  const double water = after.field_work - before.field_work;
  std::printf("water's work over 0.15-0.2 s: %.10g J against -m g v_t dt = %.10g J\n", water, expected);
  EXPECT_NEAR(water, expected, 1e-5 * std::abs(expected));
  // No contact: what the split leaves to the contacts (the load less
  // gravity and the water) is round-off.
  EXPECT_NEAR(after.contact_work, 0.0, 1e-12 * after.gravity_work);
}

TEST(PoreFluid, AGrainAboveASeepingBedMovesAtTheOutflowLessItsSettlingVelocity) {
  // The sphere of the test above, released from rest in the water above
  // an empty grid through which water flows up at q = 10 cm/s (inflow on
  // the floor, top drained). Relative to the rising water it settles at
  // v_t = 7.84 cm/s, so it ends rising at q - v_t = 2.16 cm/s.
  const double r = 2.5e-4;
  const double d = 2 * r;
  const double rho_s = 2650.0;
  const double q = 0.1;
  const double v_expected = q - terminal_velocity(d, rho_s);
  auto sim = lone_sphere(r, rho_s);
  PoreFluid<3> fluid;
  set_up_cube_of_cells(fluid, d);
  fluid.sides[4] = {FluidBoundaryType::flux, TimeSeries::constant(q)};
  fluid.sides[5] = {FluidBoundaryType::drained, TimeSeries::constant(0.0)};
  fluid.water_level = 1.0;
  fluid.initialize(sim.particles);
  // Steady flow through the empty grid: a few implicit steps, each far
  // longer than the grid's diffusion time (h^2 mu / (kappa K_f) < 1e-6 s).
  for (int s = 0; s < 5; ++s) fluid.update(sim.particles, 1e-2, 1e-2 * (s + 1));
  const double area = 4e-6;
  ASSERT_NEAR(fluid.side_inflow(5), -q * area, 1e-9 * q * area);
  sim.force_field = &fluid;
  sim.gravity = Vec<3>(0.0, 0.0, -g);
  sim.time_step = 1e-5;
  sim.prepare();
  // 0.2 s: as in still water, more than 15 of the approach's time
  // constants (the slip, not the speed, is what the drag acts on), so
  // 2e-7 of the slip is left; bound 1e-5 of the slip v_t.
  for (int s = 0; s < 20000; ++s) sim.step();
  const Vec<3> v = sim.particles.velocity[0];
  std::printf("above an outflow of %.3g m/s: v = %.10g m/s against q - v_t = %.10g\n", q, v.z(), v_expected);
  EXPECT_NEAR(v.z(), v_expected, 1e-5 * (q - v_expected));
  EXPECT_EQ(v.head<2>().norm(), 0.0);
}
