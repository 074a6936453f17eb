// The multigrid preconditioner (fluid/grid_multigrid.hpp): its coarse
// operator against P^T A P written out densely, the symmetry and
// positivity that conjugate gradients need, the solution against a dense
// solve, and the property it is there for: an iteration count that barely
// grows with the grid, where Jacobi's doubles when the grid is refined.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Dense>

#include "darcydem/fluid/grid_multigrid.hpp"
#include "darcydem/fluid/pressure_solver.hpp"

using darcydem::CgPreconditioner;
using darcydem::GridMultigrid;
using darcydem::GridOperator;
using darcydem::PressureSolver;
using darcydem::PressureSolverKind;

namespace {

/// A grid of dims (x fastest) with conductances log-uniform in
/// [t_lo, t_hi] between neighbours and storage s per cell.
GridOperator make_grid(const std::vector<int>& dims, double t_lo, double t_hi, double storage,
                       unsigned seed) {
  std::vector<std::size_t> strides;
  std::size_t n = 1;
  for (int d : dims) {
    strides.push_back(n);
    n *= static_cast<std::size_t>(d);
  }
  GridOperator op;
  op.resize(n, strides);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(std::log(t_lo), std::log(t_hi));
  op.diagonal.setConstant(storage);
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t rest = c;
    for (std::size_t k = 0; k < dims.size(); ++k) {
      const auto i = static_cast<int>(rest % static_cast<std::size_t>(dims[k]));
      rest /= static_cast<std::size_t>(dims[k]);
      if (i + 1 == dims[k]) continue;  // the last layer keeps a zero
      const double t = std::exp(u(rng));
      op.upper[k][static_cast<Eigen::Index>(c)] = t;
      op.diagonal[static_cast<Eigen::Index>(c)] += t;
      op.diagonal[static_cast<Eigen::Index>(c + strides[k])] += t;
    }
  }
  return op;
}

Eigen::MatrixXd dense_of(const GridOperator& op) {
  const auto n = op.rows();
  Eigen::MatrixXd a(n, n);
  for (Eigen::Index j = 0; j < n; ++j) a.col(j) = op * Eigen::VectorXd::Unit(n, j);
  return a;
}

int cg_iterations(const GridOperator& op, CgPreconditioner pc, const Eigen::VectorXd& b, double tol,
                  Eigen::VectorXd& x) {
  PressureSolver solver(PressureSolverKind::cg, tol, pc);
  x = Eigen::VectorXd::Zero(b.size());
  return solver.solve(op, b, x).iterations;
}

}  // namespace

TEST(GridMultigrid, CoarseOperatorIsTheScaledGalerkinProduct) {
  // 5 x 4 x 3 cells: aggregates of 2 x 2 x 2, and of 1 along x's last
  // column and z's last layer (odd counts).
  const std::vector<int> dims = {5, 4, 3};
  const GridOperator op = make_grid(dims, 0.1, 10.0, 0.5, 3);
  GridMultigrid mg(8);
  mg.compute(op);
  ASSERT_GE(mg.levels(), 2U);
  // P: fine cell (i, j, k) to coarse (i/2, j/2, k/2) of a 3 x 2 x 2 grid.
  const int n = 60;
  const int cn = 12;
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, cn);
  for (int k = 0; k < 3; ++k) {
    for (int j = 0; j < 4; ++j) {
      for (int i = 0; i < 5; ++i) p(i + 5 * (j + 4 * k), i / 2 + 3 * (j / 2 + 2 * (k / 2))) = 1.0;
    }
  }
  const Eigen::MatrixXd galerkin = p.transpose() * dense_of(op) * p;
  // Scaled: s times P^T A P, plus (1 - s) times its row sums on the
  // diagonal (what the cells hold besides conductances is not scaled).
  const double s = GridMultigrid::coarse_scale;
  const Eigen::MatrixXd expected =
      s * galerkin + (1.0 - s) * Eigen::MatrixXd(galerkin.rowwise().sum().asDiagonal());
  const Eigen::MatrixXd got = dense_of(mg.level(1));
  // Sums of a few terms of size <= 10 each: round-off of 1e-13 at most.
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(GridMultigrid, VCycleIsSymmetricAndPositiveDefinite) {
  // Conjugate gradients need a symmetric positive definite preconditioner.
  const GridOperator op = make_grid({9, 7, 5}, 1e-2, 1e2, 1e-3, 5);
  GridMultigrid mg(8);
  mg.compute(op);
  ASSERT_GE(mg.levels(), 3U);
  std::mt19937 rng(9);
  std::normal_distribution<double> z;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd u(op.rows());
    Eigen::VectorXd v(op.rows());
    for (Eigen::Index c = 0; c < u.size(); ++c) {
      u[c] = z(rng);
      v[c] = z(rng);
    }
    const Eigen::VectorXd bu = mg.solve(u);
    const Eigen::VectorXd bv = mg.solve(v);
    // The same sums in another order: round-off relative to the norms.
    EXPECT_LT(std::abs(bu.dot(v) - u.dot(bv)), 1e-12 * bu.norm() * v.norm());
    EXPECT_GT(bu.dot(u), 0.0);
  }
}

TEST(GridMultigrid, ConjugateGradientsSolveAHighContrastSystem) {
  // Conductances over four orders of magnitude (a packed bed under clear
  // fluid), against a dense LDL^T solve.
  const GridOperator op = make_grid({9, 7, 6}, 1e-2, 1e2, 1e-3, 13);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(op.rows(), -1.0, 2.0);
  const Eigen::VectorXd direct = dense_of(op).ldlt().solve(b);
  Eigen::VectorXd x;
  const int iterations = cg_iterations(op, CgPreconditioner::multigrid, b, 1e-12, x);
  EXPECT_GT(iterations, 0);
  // Relative residual 1e-12 and a condition number of at most about 1e7
  // (conductances up to 1e2 over storage 1e-3): error below 1e-5, in fact
  // far less; 1e-8 leaves a margin of ten over what was measured.
  EXPECT_LT((x - direct).norm() / direct.norm(), 1e-8);
}

TEST(GridMultigrid, IterationsBarelyGrowWhenTheGridIsRefined) {
  // A Laplacian with little storage (an almost incompressible fluid), on
  // 16^3 and then 32^3 cells. Jacobi-preconditioned CG needs about twice
  // as many iterations on the finer grid (its condition number grows as
  // the square of the cells per side); the multigrid's count should stay
  // nearly the same.
  const double storage = 1e-4;
  auto run = [&](int side, CgPreconditioner pc) {
    const GridOperator op = make_grid({side, side, side}, 1.0, 1.0, storage, 1);
    Eigen::VectorXd b(op.rows());
    std::mt19937 rng(2);
    std::normal_distribution<double> z;
    for (Eigen::Index c = 0; c < b.size(); ++c) b[c] = z(rng);
    Eigen::VectorXd x;
    return cg_iterations(op, pc, b, 1e-10, x);
  };
  const int jacobi_coarse = run(16, CgPreconditioner::jacobi);
  const int jacobi_fine = run(32, CgPreconditioner::jacobi);
  const int mg_coarse = run(16, CgPreconditioner::multigrid);
  const int mg_fine = run(32, CgPreconditioner::multigrid);
  RecordProperty("iterations", std::to_string(jacobi_coarse) + " " + std::to_string(jacobi_fine) + " " +
                                   std::to_string(mg_coarse) + " " + std::to_string(mg_fine));
  EXPECT_GT(jacobi_fine, 1.6 * jacobi_coarse);
  // Grid-independence up to the slow growth of aggregation multigrid: at
  // most 30 % more, and a fraction of Jacobi's count.
  EXPECT_LE(mg_fine, 1.3 * mg_coarse + 1);
  EXPECT_LT(mg_fine, jacobi_fine / 4);
}

TEST(GridMultigrid, IterationsAreCountedAsDone) {
  // On 60 cells the multigrid is one dense Cholesky solve, an exact
  // preconditioner: CG converges in exactly one iteration (Eigen's own
  // count says 0 then). From the solution itself, no iteration.
  const GridOperator op = make_grid({5, 4, 3}, 0.1, 10.0, 0.5, 3);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(op.rows(), 1.0, 2.0);
  PressureSolver solver(PressureSolverKind::cg, 1e-10, CgPreconditioner::multigrid);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  EXPECT_EQ(solver.solve(op, b, x).iterations, 1);
  EXPECT_EQ(solver.solve(op, b, x).iterations, 0);
}

TEST(GridMultigrid, AutomaticChoiceFollowsTheGridSize) {
  const PressureSolver solver(PressureSolverKind::cg, 1e-10);
  EXPECT_EQ(solver.preconditioner_for(PressureSolver::multigrid_cells), CgPreconditioner::jacobi);
  EXPECT_EQ(solver.preconditioner_for(PressureSolver::multigrid_cells + 1), CgPreconditioner::multigrid);
}

TEST(GridMultigrid, TwoDimensionalGridAndAColumnOneCellWide) {
  // 2D (the paper's discs) and a grid that coarsens along one axis only.
  for (const std::vector<int>& dims : {std::vector<int>{40, 30}, std::vector<int>{1, 300}}) {
    const GridOperator op = make_grid(dims, 0.1, 10.0, 1e-3, 21);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(op.rows(), 1.0, 3.0);
    const Eigen::VectorXd direct = dense_of(op).ldlt().solve(b);
    Eigen::VectorXd x;
    cg_iterations(op, CgPreconditioner::multigrid, b, 1e-12, x);
    // As above: condition number at most about 1e5.
    EXPECT_LT((x - direct).norm() / direct.norm(), 1e-8) << dims[0] << " x " << dims[1];
  }
}
