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
// coarse conductances are then scaled by `coarse_scale` = 0.6: plain
// P^T A P is about twice too stiff per level for a Laplacian (the coarse
// grid's own conductances, a face twice as far and, summed, 2^(D-1) times
// as wide, would be half of it), which slows the convergence as levels are
// added; 0.6 took the fewest iterations on the benchmark's grid
// (docs/PERFORMANCE.md).
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
  /// Takes the operator (which must outlive the solves); the coarse levels
  /// are built from its values at the first solve() after this, so that a
  /// CG solve whose initial guess already meets the tolerance costs nothing
  /// here. Called for every matrix: the conductances change with the
  /// porosity.
  GridMultigrid& factorize(const GridOperator& a) {
    matrix_ = &a;
    built_ = false;
    return *this;
  }
  GridMultigrid& compute(const GridOperator& a) { return factorize(a); }
  [[nodiscard]] Eigen::ComputationInfo info() const { return Eigen::Success; }

  /// One V-cycle for A z = r from z = 0.
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& r) const;

  /// Number of levels, the finest included.
  [[nodiscard]] std::size_t levels() const {
    build();
    return levels_.size();
  }
  /// The operator of level l (0: the matrix itself).
  [[nodiscard]] const GridOperator& level(std::size_t l) const {
    build();
    return op(l);
  }

 private:
  struct Level {
    GridOperator op;  ///< unused on level 0: the matrix itself
    std::vector<int> dims;
    Eigen::VectorXd inv_diagonal;
    std::vector<int> parent;  ///< each cell's coarse cell (empty on the coarsest level)
    // Work space of the cycle.
    mutable Eigen::VectorXd x, b, r;
  };
  /// The levels' values from the matrix, if not built since factorize().
  void build() const;
  /// The levels' shapes (once per grid).
  void shape_levels(const GridOperator& a) const;
  void cycle(std::size_t l) const;
  /// The operator of level l, the matrix itself on level 0.
  [[nodiscard]] const GridOperator& op(std::size_t l) const { return l == 0 ? *matrix_ : levels_[l].op; }
  std::size_t coarsest_cells_;
  const GridOperator* matrix_ = nullptr;
  // Built lazily by the const solve(): a cache of the matrix's hierarchy.
  mutable bool built_ = false;
  mutable std::vector<Level> levels_;
  mutable std::vector<std::size_t> shaped_stride_;  ///< the grid the levels were shaped for
  mutable Eigen::Index shaped_rows_ = 0;
  mutable Eigen::LLT<Eigen::MatrixXd> coarsest_;
};

}  // namespace darcydem
