#pragma once
// The implicit (backward Euler) pressure system of the pore fluid,
//   (S + dt L) u = S u_old + sources,
// S the diagonal storage n V / K_f and L the Darcy conductance Laplacian: a
// sparse SPD matrix whose pattern never changes during a run. Solved by a
// sparse LDL^T Cholesky (symbolic analysis once, numeric factorisation each
// fluid step) or by preconditioned conjugate gradients warm-started from the
// last pressure, on the stored matrix (Jacobi) or on the grid's stencil
// (GridOperator, no stored matrix; Jacobi or a multigrid V-cycle).
#include <memory>
#include <string>

#include <Eigen/Sparse>

#include "darcydem/fluid/grid_multigrid.hpp"
#include "darcydem/fluid/grid_operator.hpp"

namespace darcydem {

enum class PressureSolverKind { cholesky, cg };
/// The preconditioner of CG on the grid's stencil: the diagonal, or a
/// multigrid V-cycle (grid_multigrid.hpp), which keeps the iteration count
/// nearly independent of the grid's size but costs several Jacobi
/// iterations per iteration; automatic: multigrid on grids of more than
/// PressureSolver::multigrid_cells cells (measured, docs/PERFORMANCE.md).
enum class CgPreconditioner { automatic, jacobi, multigrid };

struct SolveStats {
  int iterations = 0;     ///< CG iterations (1 for Cholesky)
  double residual = 0.0;  ///< |A x - b| / |b| after the solve
};

class PressureSolver {
 public:
  using Matrix = Eigen::SparseMatrix<double>;
  /// Above this many cells the automatic preconditioner is multigrid.
  static constexpr Eigen::Index multigrid_cells = 30'000;

  explicit PressureSolver(PressureSolverKind kind = PressureSolverKind::cg, double tolerance = 1e-10,
                          CgPreconditioner preconditioner = CgPreconditioner::automatic);
  ~PressureSolver();
  PressureSolver(PressureSolver&&) noexcept;
  PressureSolver& operator=(PressureSolver&&) noexcept;

  /// Solves A x = b; x holds the initial guess on entry (used by CG).
  /// Throws std::runtime_error if the factorisation or CG fails. With
  /// `same_matrix`, A is the last solve's, unchanged: its factorisation
  /// (or CG's preconditioner) is used again, for another right-hand side.
  SolveStats solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x, bool same_matrix = false);
  /// The same by conjugate gradients on a grid's stencil (the kind must be
  /// cg), with the preconditioner chosen. Throws std::logic_error for a
  /// Cholesky solver.
  SolveStats solve(const GridOperator& a, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                   bool same_matrix = false);

  [[nodiscard]] PressureSolverKind kind() const { return kind_; }
  [[nodiscard]] double tolerance() const { return tolerance_; }
  [[nodiscard]] CgPreconditioner preconditioner() const { return preconditioner_; }
  /// "cholesky", or "cg" with the preconditioner used on a grid of n cells.
  [[nodiscard]] std::string describe(Eigen::Index n) const;
  /// The preconditioner used on a grid of n cells.
  [[nodiscard]] CgPreconditioner preconditioner_for(Eigen::Index n) const {
    if (preconditioner_ != CgPreconditioner::automatic) return preconditioner_;
    return n > multigrid_cells ? CgPreconditioner::multigrid : CgPreconditioner::jacobi;
  }

 private:
  struct Impl;
  PressureSolverKind kind_;
  double tolerance_;
  CgPreconditioner preconditioner_;
  std::unique_ptr<Impl> impl_;
};

[[nodiscard]] inline std::string to_string(PressureSolverKind k) {
  return k == PressureSolverKind::cholesky ? "cholesky" : "cg";
}
[[nodiscard]] inline std::string to_string(CgPreconditioner p) {
  switch (p) {
    case CgPreconditioner::automatic:
      return "auto";
    case CgPreconditioner::jacobi:
      return "jacobi";
    default:
      return "multigrid";
  }
}

}  // namespace darcydem
