// The grid's pressure stencil (fluid/grid_operator.hpp) against the matrix
// written out entry by entry from its definition, and Eigen's conjugate
// gradients on it against a dense direct solve.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Dense>

#include "darcydem/fluid/pressure_solver.hpp"

using darcydem::GridOperator;

namespace {

/// A 4 x 3 x 2 grid (x fastest) with random conductances between
/// neighbours and a diagonal that dominates, as storage + conductances does.
struct Case {
  GridOperator op;
  Eigen::MatrixXd dense;
};

Case make_case() {
  const int nx = 4, ny = 3, nz = 2;
  const int n = nx * ny * nz;
  Case c;
  c.op.resize(n, {1, static_cast<std::size_t>(nx), static_cast<std::size_t>(nx * ny)});
  c.dense = Eigen::MatrixXd::Zero(n, n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  auto index = [&](int i, int j, int k) { return i + nx * (j + ny * k); };
  for (int k = 0; k < nz; ++k) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        const int a = index(i, j, k);
        const int up[3][3] = {{i + 1, j, k}, {i, j + 1, k}, {i, j, k + 1}};
        const bool inside[3] = {i + 1 < nx, j + 1 < ny, k + 1 < nz};
        for (int axis = 0; axis < 3; ++axis) {
          if (!inside[axis]) continue;  // the last layer keeps a zero
          const int b = index(up[axis][0], up[axis][1], up[axis][2]);
          const double t = u(rng);
          c.op.upper[axis][a] = t;
          c.dense(a, b) -= t;
          c.dense(b, a) -= t;
          c.dense(a, a) += t;
          c.dense(b, b) += t;
        }
      }
    }
  }
  for (int a = 0; a < n; ++a) {
    const double storage = u(rng);
    c.dense(a, a) += storage;
  }
  c.op.diagonal = c.dense.diagonal();
  return c;
}

}  // namespace

TEST(GridOperator, ProductMatchesTheMatrixEntryByEntry) {
  const Case c = make_case();
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(c.dense.rows(), -1.0, 2.0);
  const Eigen::VectorXd expected = c.dense * x;
  const Eigen::VectorXd got = c.op * x;
  // The same products summed in another order: a few ulp of the largest
  // term (entries <= 10, |x| <= 2).
  EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 1e-13);
}

TEST(GridOperator, ConjugateGradientsSolveTheSystem) {
  const Case c = make_case();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(c.dense.rows(), 1.0, 3.0);
  const Eigen::VectorXd direct = c.dense.ldlt().solve(b);
  darcydem::PressureSolver solver(darcydem::PressureSolverKind::cg, 1e-12);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(b.size());
  const auto stats = solver.solve(c.op, b, x);
  // Relative residual 1e-12 and a well-conditioned matrix (diagonally
  // dominant, condition number below 100): the error is below 1e-10.
  EXPECT_LT((x - direct).norm() / direct.norm(), 1e-10);
  EXPECT_LT(stats.residual, 1e-11);
  EXPECT_GT(stats.iterations, 1);
}

TEST(GridOperator, CholeskyRefusesTheStencil) {
  const Case c = make_case();
  darcydem::PressureSolver solver(darcydem::PressureSolverKind::cholesky);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(c.dense.rows());
  EXPECT_THROW(solver.solve(c.op, Eigen::VectorXd::Ones(c.dense.rows()), x), std::logic_error);
}
