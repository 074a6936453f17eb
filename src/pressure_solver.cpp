#include "darcydem/fluid/pressure_solver.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>

namespace darcydem {

struct PressureSolver::Impl {
  Eigen::SimplicialLDLT<Matrix> ldlt;
  bool analysed = false;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper> cg;
  Eigen::ConjugateGradient<GridOperator, Eigen::Lower | Eigen::Upper, GridJacobi> grid_cg;
};

PressureSolver::PressureSolver(PressureSolverKind kind, double tolerance)
    : kind_(kind), tolerance_(tolerance), impl_(std::make_unique<Impl>()) {}
PressureSolver::~PressureSolver() = default;
PressureSolver::PressureSolver(PressureSolver&&) noexcept = default;
PressureSolver& PressureSolver::operator=(PressureSolver&&) noexcept = default;

SolveStats PressureSolver::solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  SolveStats stats;
  const double b_norm = b.norm();
  if (kind_ == PressureSolverKind::cholesky) {
    if (!impl_->analysed) {
      impl_->ldlt.analyzePattern(a);
      impl_->analysed = true;
    }
    impl_->ldlt.factorize(a);
    if (impl_->ldlt.info() != Eigen::Success) {
      throw std::runtime_error(
          "pore pressure: the Cholesky factorisation failed (matrix not positive definite)");
    }
    x = impl_->ldlt.solve(b);
    stats.iterations = 1;
  } else {
    impl_->cg.setTolerance(tolerance_);
    impl_->cg.setMaxIterations(std::max<Eigen::Index>(1000, 10 * a.rows()));
    impl_->cg.compute(a);
    x = impl_->cg.solveWithGuess(b, x);
    stats.iterations = static_cast<int>(impl_->cg.iterations());
    if (impl_->cg.info() != Eigen::Success) {
      throw std::runtime_error(
          fmt::format("pore pressure: conjugate gradients did not converge in {} iterations "
                      "(error {:.3g}, tolerance {:.3g})",
                      impl_->cg.iterations(), impl_->cg.error(), tolerance_));
    }
  }
  stats.residual = b_norm > 0.0 ? (a * x - b).norm() / b_norm : (a * x).norm();
  return stats;
}

SolveStats PressureSolver::solve(const GridOperator& a, const Eigen::VectorXd& b, Eigen::VectorXd& x) {
  if (kind_ != PressureSolverKind::cg) {
    throw std::logic_error("pore pressure: the grid's stencil is solved by conjugate gradients only");
  }
  SolveStats stats;
  auto& cg = impl_->grid_cg;
  cg.setTolerance(tolerance_);
  cg.setMaxIterations(std::max<Eigen::Index>(1000, 10 * a.rows()));
  cg.compute(a);
  x = cg.solveWithGuess(b, x);
  stats.iterations = static_cast<int>(cg.iterations());
  if (cg.info() != Eigen::Success) {
    throw std::runtime_error(
        fmt::format("pore pressure: conjugate gradients did not converge in {} iterations "
                    "(error {:.3g}, tolerance {:.3g})",
                    cg.iterations(), cg.error(), tolerance_));
  }
  const double b_norm = b.norm();
  const Eigen::VectorXd ax = a * x;
  stats.residual = b_norm > 0.0 ? (ax - b).norm() / b_norm : ax.norm();
  return stats;
}

}  // namespace darcydem
