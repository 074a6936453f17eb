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
  Eigen::ConjugateGradient<GridOperator, Eigen::Lower | Eigen::Upper, GridMultigrid> grid_mg_cg;
};

PressureSolver::PressureSolver(PressureSolverKind kind, double tolerance, CgPreconditioner preconditioner)
    : kind_(kind), tolerance_(tolerance), preconditioner_(preconditioner), impl_(std::make_unique<Impl>()) {}
PressureSolver::~PressureSolver() = default;
PressureSolver::PressureSolver(PressureSolver&&) noexcept = default;
PressureSolver& PressureSolver::operator=(PressureSolver&&) noexcept = default;

namespace {

/// Conjugate gradients warm-started from x (Eigen's solver on a stored
/// matrix or on the grid's stencil); throws if they do not converge.
/// Returns the number of iterations done (matrix products after the
/// initial residual). Eigen's iterations() is one less when CG converges
/// inside its loop (it stops before counting the last iteration), and 0
/// both then and when the start already meets the tolerance; the start
/// is left unchanged only in the second case.
template <class Cg, class Operator>
int run_cg(Cg& cg, const Operator& a, double tolerance, const Eigen::VectorXd& b, Eigen::VectorXd& x,
           bool same_matrix) {
  cg.setTolerance(tolerance);
  cg.setMaxIterations(std::max<Eigen::Index>(1000, 10 * a.rows()));
  if (!same_matrix) cg.compute(a);
  const Eigen::VectorXd start = x;
  x = cg.solveWithGuess(b, start);
  if (cg.info() != Eigen::Success) {
    throw std::runtime_error(
        fmt::format("pore pressure: conjugate gradients did not converge in {} iterations "
                    "(error {:.3g}, tolerance {:.3g})",
                    cg.iterations(), cg.error(), tolerance));
  }
  const bool moved = b.squaredNorm() > 0.0 && x != start;
  return moved ? static_cast<int>(cg.iterations()) + 1 : 0;
}

/// |A x - b| / |b| (|A x| for b = 0).
template <class Operator>
double relative_residual(const Operator& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const double b_norm = b.norm();
  const Eigen::VectorXd ax = a * x;
  return b_norm > 0.0 ? (ax - b).norm() / b_norm : ax.norm();
}

}  // namespace

SolveStats PressureSolver::solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                 bool same_matrix) {
  SolveStats stats;
  if (kind_ == PressureSolverKind::cholesky) {
    if (!impl_->analysed) {
      impl_->ldlt.analyzePattern(a);
      impl_->analysed = true;
    }
    if (!same_matrix) impl_->ldlt.factorize(a);
    if (impl_->ldlt.info() != Eigen::Success) {
      throw std::runtime_error(
          "pore pressure: the Cholesky factorisation failed (matrix not positive definite)");
    }
    x = impl_->ldlt.solve(b);
    stats.iterations = 1;
  } else {
    stats.iterations = run_cg(impl_->cg, a, tolerance_, b, x, same_matrix);
  }
  stats.residual = relative_residual(a, b, x);
  return stats;
}

std::string PressureSolver::describe(Eigen::Index n) const {
  if (kind_ == PressureSolverKind::cholesky) return "cholesky";
  return fmt::format("cg ({} preconditioner)", to_string(preconditioner_for(n)));
}

SolveStats PressureSolver::solve(const GridOperator& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                 bool same_matrix) {
  if (kind_ != PressureSolverKind::cg) {
    throw std::logic_error("pore pressure: the grid's stencil is solved by conjugate gradients only");
  }
  SolveStats stats;
  stats.iterations = preconditioner_for(a.rows()) == CgPreconditioner::multigrid
                         ? run_cg(impl_->grid_mg_cg, a, tolerance_, b, x, same_matrix)
                         : run_cg(impl_->grid_cg, a, tolerance_, b, x, same_matrix);
  stats.residual = relative_residual(a, b, x);
  return stats;
}

}  // namespace darcydem
