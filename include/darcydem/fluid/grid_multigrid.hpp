#pragma once
// A multigrid V-cycle on the grid's pressure stencil (GridOperator), used
// as the preconditioner of conjugate gradients on large grids, where the
// Jacobi preconditioner's iteration count grows with the grid's size
// (docs/PERFORMANCE.md).
//
// Coarsening by aggregation: each coarse cell is a block of 2 x 2 (x 2)
// fine cells (1 wide where an axis has an odd count or a single cell), the
// interpolation P is piecewise constant and the coarse operator is
// P^T A P (Galerkin), which is again a stencil of the same kind: the
// conductance between two coarse cells is the sum of the fine conductances
// across their common boundary, and what a fine cell holds on its diagonal
// besides its conductances (storage, drained boundaries) is summed. The
// coarse conductances are then scaled by 1/2, so that they are those of
// the coarse grid itself (a face twice as far and, summed, 2^(D-1) times as
// wide): plain P^T A P is twice too stiff per level for a Laplacian, which
// would slow the convergence as levels are added.
// Smoothing: two weighted Jacobi sweeps before and two after the coarse
// correction (the same on the way down and up, so that the cycle is a
// symmetric operator, as conjugate gradients needs); on the coarsest grid
// (64 cells or fewer by default) a dense Cholesky solve.
#include <cstddef>
#include <vector>

#include <Eigen/Dense>

#include "darcydem/fluid/grid_operator.hpp"

namespace darcydem {

class GridMultigrid {
 public:
  /// Coarsening stops at `coarsest_cells` cells or fewer.
  explicit GridMultigrid(std::size_t coarsest_cells = 64) : coarsest_cells_(coarsest_cells) {}

  static constexpr double jacobi_weight = 0.8;
  static constexpr double coarse_scale = 0.6;

  /// The Eigen preconditioner interface (IterativeSolverBase calls these).
  GridMultigrid& analyzePattern(const GridOperator& /*a*/) { return *this; }
  /// Builds the coarse levels from the operator's values (every solve with
  /// a new matrix: the conductances change with the porosity).
  GridMultigrid& factorize(const GridOperator& a);
  GridMultigrid& compute(const GridOperator& a) { return factorize(a); }
  [[nodiscard]] Eigen::ComputationInfo info() const { return Eigen::Success; }

  /// One V-cycle for A z = r from z = 0.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& r) const;

  /// Number of levels, the finest included (after factorize).
  [[nodiscard]] std::size_t levels() const { return levels_.size(); }
  /// The operator of level l (0: the matrix itself).
  [[nodiscard]] const GridOperator& level(std::size_t l) const { return levels_[l].op; }

 private:
  struct Level {
    GridOperator op;
    std::vector<int> dims;
    Eigen::VectorXd inv_diagonal;
    std::vector<int> parent;  ///< each cell's coarse cell (empty on the coarsest level)
    // Work space of the cycle.
    mutable Eigen::VectorXd x, b, r;
  };
  void build_levels(const GridOperator& a);
  void cycle(std::size_t l) const;
  std::size_t coarsest_cells_;
  std::vector<Level> levels_;
  Eigen::LLT<Eigen::MatrixXd> coarsest_;
};

}  // namespace darcydem
