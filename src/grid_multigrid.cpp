#include "darcydem/fluid/grid_multigrid.hpp"

#include <stdexcept>

namespace darcydem {

namespace {

/// Cells per axis from the operator's strides (x fastest).
std::vector<int> dims_of(const GridOperator& a) {
  const std::size_t d = a.stride.size();
  std::vector<int> dims(d);
  for (std::size_t k = 0; k < d; ++k) {
    const std::size_t next = k + 1 < d ? a.stride[k + 1] : static_cast<std::size_t>(a.rows());
    dims[k] = static_cast<int>(next / a.stride[k]);
  }
  return dims;
}

/// Per cell, the sum of its conductances to its neighbours.
Eigen::VectorXd conductance_sums(const GridOperator& a) {
  Eigen::VectorXd sums = Eigen::VectorXd::Zero(a.rows());
  for (std::size_t k = 0; k < a.stride.size(); ++k) {
    const auto s = static_cast<Eigen::Index>(a.stride[k]);
    const Eigen::Index m = a.rows() - s;
    if (m <= 0) continue;
    sums.head(m) += a.upper[k].head(m);
    sums.segment(s, m) += a.upper[k].head(m);
  }
  for (const auto& e : a.extra) {
    sums[e.a] += e.g;
    sums[e.b] += e.g;
  }
  return sums;
}

}  // namespace

void GridMultigrid::shape_levels(const GridOperator& a) const {
  levels_.clear();
  shaped_stride_ = a.stride;
  shaped_rows_ = a.rows();
  Level finest;  // its operator is the matrix itself (op(0))
  finest.dims = dims_of(a);
  levels_.push_back(std::move(finest));
  auto n = static_cast<std::size_t>(a.rows());
  while (true) {
    Level& fine = levels_.back();
    const auto rows = static_cast<Eigen::Index>(n);
    fine.x.resize(rows);
    fine.b.resize(rows);
    fine.r.resize(rows);
    bool coarsens = false;
    for (int d : fine.dims) coarsens = coarsens || d > 1;
    if (n <= coarsest_cells_ || !coarsens) break;
    // The coarse grid: cells paired along every axis with more than one.
    const std::size_t dim = fine.dims.size();
    Level coarse;
    coarse.dims.resize(dim);
    std::vector<std::size_t> cstride(dim);
    std::size_t cn = 1;
    for (std::size_t k = 0; k < dim; ++k) {
      coarse.dims[k] = (fine.dims[k] + 1) / 2;
      cstride[k] = cn;
      cn *= static_cast<std::size_t>(coarse.dims[k]);
    }
    coarse.op.resize(cn, cstride);
    fine.parent.resize(n);
    for (std::size_t c = 0; c < n; ++c) {
      std::size_t rest = c;
      std::size_t p = 0;
      for (std::size_t k = 0; k < dim; ++k) {
        const std::size_t i = rest % static_cast<std::size_t>(fine.dims[k]);
        rest /= static_cast<std::size_t>(fine.dims[k]);
        p += (i / 2) * cstride[k];
      }
      fine.parent[c] = static_cast<int>(p);
    }
    levels_.push_back(std::move(coarse));
    n = cn;
  }
}

void GridMultigrid::build() const {
  if (built_) return;
  if (matrix_ == nullptr) throw std::logic_error("GridMultigrid used before factorize");
  const GridOperator& a = *matrix_;
  // The levels' shapes depend on the grid only; their values on the matrix.
  if (levels_.empty() || shaped_stride_ != a.stride || shaped_rows_ != a.rows()) shape_levels(a);
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    const Level& fine = levels_[l];
    const GridOperator& fine_op = op(l);
    Level& coarse = levels_[l + 1];
    const auto n = static_cast<std::size_t>(fine_op.rows());
    // P^T A P: the conductances across the aggregates' boundaries summed
    // (scaled, see the header); what each fine diagonal holds besides its
    // conductances summed.
    const Eigen::VectorXd fine_sums = conductance_sums(fine_op);
    Eigen::VectorXd held = Eigen::VectorXd::Zero(coarse.op.rows());
    for (std::size_t c = 0; c < n; ++c) {
      const auto ci = static_cast<Eigen::Index>(c);
      held[fine.parent[c]] += fine_op.diagonal[ci] - fine_sums[ci];
    }
    for (std::size_t k = 0; k < fine.dims.size(); ++k) {
      Eigen::VectorXd& up = coarse.op.upper[k];
      up.setZero();
      const std::size_t s = fine_op.stride[k];
      const double* t = fine_op.upper[k].data();
      // t is zero on the fine grid's last layer along k, where c + s is not
      // c's neighbour.
      for (std::size_t c = 0; c + s < n; ++c) {
        const int p = fine.parent[c];
        if (p != fine.parent[c + s]) up[p] += coarse_scale * t[c];
      }
    }
    // Couplings between cells that are not stencil neighbours (a periodic
    // grid's ends): between two aggregates, a coupling of theirs, as above.
    coarse.op.extra.clear();
    for (const auto& e : fine_op.extra) {
      const int pa = fine.parent[static_cast<std::size_t>(e.a)];
      const int pb = fine.parent[static_cast<std::size_t>(e.b)];
      if (pa != pb) coarse.op.extra.push_back({pa, pb, coarse_scale * e.g});
    }
    coarse.op.diagonal = held + conductance_sums(coarse.op);
    if (!(coarse.op.diagonal.minCoeff() > 0.0)) {
      throw std::runtime_error("pore pressure: a multigrid level is not positive definite");
    }
  }
  for (std::size_t l = 0; l < levels_.size(); ++l) levels_[l].inv_diagonal = op(l).diagonal.cwiseInverse();
  // The coarsest level, dense.
  const GridOperator& last = op(levels_.size() - 1);
  const auto m = last.rows();
  Eigen::MatrixXd dense(m, m);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(m);
  Eigen::VectorXd column(m);
  for (Eigen::Index j = 0; j < m; ++j) {
    unit[j] = 1.0;
    column = last * unit;
    dense.col(j) = column;
    unit[j] = 0.0;
  }
  coarsest_.compute(dense);
  if (coarsest_.info() != Eigen::Success) {
    throw std::runtime_error("pore pressure: the multigrid's coarsest level is not positive definite");
  }
  built_ = true;
}

void GridMultigrid::cycle(std::size_t l) const {
  const Level& lv = levels_[l];
  if (l + 1 == levels_.size()) {
    lv.x = coarsest_.solve(lv.b);
    return;
  }
  // One Jacobi sweep in one pass, into r, then swapped with x.
  auto sweep = [&] {
    const double* x = lv.x.data();
    const double* b = lv.b.data();
    const double* inv = lv.inv_diagonal.data();
    double* out = lv.r.data();
    op(l).apply(lv.x,
                [&](Eigen::Index c, double ax) { out[c] = x[c] + jacobi_weight * inv[c] * (b[c] - ax); });
    lv.x.swap(lv.r);
  };
  // Two sweeps from x = 0 (the first is x = w D^-1 b).
  lv.x = jacobi_weight * lv.inv_diagonal.cwiseProduct(lv.b);
  sweep();
  // The residual, summed over each aggregate, is the coarse right-hand side.
  op(l).residual(lv.b, lv.x, lv.r);
  const Level& coarse = levels_[l + 1];
  coarse.b.setZero();
  const auto n = lv.x.size();
  for (Eigen::Index c = 0; c < n; ++c) coarse.b[lv.parent[static_cast<std::size_t>(c)]] += lv.r[c];
  cycle(l + 1);
  for (Eigen::Index c = 0; c < n; ++c) lv.x[c] += coarse.x[lv.parent[static_cast<std::size_t>(c)]];
  sweep();
  sweep();
}

Eigen::VectorXd GridMultigrid::solve(const Eigen::VectorXd& r) const {
  build();
  levels_[0].b = r;
  cycle(0);
  return levels_[0].x;
}

}  // namespace darcydem
