#pragma once
// The implicit (backward Euler) pressure system of the pore fluid,
//   (S + dt L) u = S u_old + sources,
// S the diagonal storage n V / K_f and L the Darcy conductance Laplacian: a
// sparse SPD matrix whose pattern never changes during a run. Solved by a
// sparse LDL^T Cholesky (symbolic analysis once, numeric factorisation each
// fluid step) or by Jacobi-preconditioned conjugate gradients warm-started
// from the last pressure, on the stored matrix or on the grid's stencil
// (GridOperator, no stored matrix).
#include <memory>
#include <string>

#include <Eigen/Sparse>

#include "darcydem/fluid/grid_operator.hpp"

namespace darcydem {

enum class PressureSolverKind { cholesky, cg };

struct SolveStats {
  int iterations = 0;     ///< CG iterations (1 for Cholesky)
  double residual = 0.0;  ///< |A x - b| / |b| after the solve
};

class PressureSolver {
 public:
  using Matrix = Eigen::SparseMatrix<double>;

  explicit PressureSolver(PressureSolverKind kind = PressureSolverKind::cg, double tolerance = 1e-10);
  ~PressureSolver();
  PressureSolver(PressureSolver&&) noexcept;
  PressureSolver& operator=(PressureSolver&&) noexcept;

  /// Solves A x = b; x holds the initial guess on entry (used by CG).
  /// Throws std::runtime_error if the factorisation or CG fails.
  SolveStats solve(const Matrix& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);
  /// The same by conjugate gradients on a grid's stencil (the kind must be
  /// cg). Throws std::logic_error for a Cholesky solver.
  SolveStats solve(const GridOperator& a, const Eigen::VectorXd& b, Eigen::VectorXd& x);

  [[nodiscard]] PressureSolverKind kind() const { return kind_; }
  [[nodiscard]] double tolerance() const { return tolerance_; }

 private:
  struct Impl;
  PressureSolverKind kind_;
  double tolerance_;
  std::unique_ptr<Impl> impl_;
};

[[nodiscard]] inline std::string to_string(PressureSolverKind k) {
  return k == PressureSolverKind::cholesky ? "cholesky" : "cg";
}

}  // namespace darcydem
