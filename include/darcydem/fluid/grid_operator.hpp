#pragma once
// The pressure matrix of a Cartesian grid held as its stencil, for Eigen's
// conjugate gradients without a stored matrix (Eigen's "matrix-free
// solvers"): a diagonal and, per axis k, the conductance between each cell
// c and its upper neighbour c + stride_k (zero where c is on the grid's last
// layer along k):
//   (A x)_c = diag_c x_c - sum_k (upper_k[c] x_{c+s_k} + upper_k[c-s_k] x_{c-s_k}).
// A x is then one vectorised pass over the coefficients (apply), where a
// stored sparse matrix reads an index and a value per entry. Couplings
// between cells that are not stencil neighbours (`extra`: a periodic grid's
// last layer and its first) are added after that pass.
#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>

namespace darcydem {
class GridOperator;
}

template <>
struct Eigen::internal::traits<darcydem::GridOperator>
    : public Eigen::internal::traits<Eigen::SparseMatrix<double>> {};

namespace darcydem {

class GridOperator : public Eigen::EigenBase<GridOperator> {
 public:
  using Scalar = double;
  using RealScalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic, IsRowMajor = false };

  /// n cells; stride[k]: the index step to the neighbour along axis k.
  void resize(std::size_t n, const std::vector<std::size_t>& strides) {
    stride = strides;
    diagonal.setZero(static_cast<Eigen::Index>(n));
    upper.assign(strides.size(), Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)));
    extra.clear();
  }

  /// A symmetric coupling of two cells besides the stencil's:
  /// (A x)_a -= g x_b and (A x)_b -= g x_a (their diagonals hold g as well).
  struct Coupling {
    Eigen::Index a = 0, b = 0;
    double g = 0.0;
  };

  [[nodiscard]] Eigen::Index rows() const { return diagonal.size(); }
  [[nodiscard]] Eigen::Index cols() const { return diagonal.size(); }

  template <class Rhs>
  Eigen::Product<GridOperator, Rhs, Eigen::AliasFreeProduct> operator*(
      const Eigen::MatrixBase<Rhs>& x) const {
    return Eigen::Product<GridOperator, Rhs, Eigen::AliasFreeProduct>(*this, x.derived());
  }

  /// y += alpha A x.
  void add_product(const Eigen::Ref<const Eigen::VectorXd>& x, double alpha,
                   Eigen::Ref<Eigen::VectorXd> y) const {
    apply(x, [&](Eigen::Index c, double ax) { y[c] += alpha * ax; });
  }

  /// r = b - A x.
  void residual(const Eigen::VectorXd& b, const Eigen::VectorXd& x, Eigen::VectorXd& r) const {
    r.resize(b.size());
    apply(x, [&](Eigen::Index c, double ax) { r[c] = b[c] - ax; });
  }

  /// out(c, (A x)_c) for every cell c in order, in one pass over the
  /// coefficients (a large grid's product is bound by memory traffic:
  /// one pass reads each coefficient once, where a pass per neighbour
  /// reads and writes the result seven times).
  template <class Out>
  void apply(const Eigen::Ref<const Eigen::VectorXd>& x, Out&& out) const {
    if (extra.empty()) {
      apply_stencil(x, out);
      return;
    }
    // The stencil's product into a vector, the extra couplings added, then
    // passed on cell by cell.
    Eigen::VectorXd ax(diagonal.size());
    apply_stencil(x, [&](Eigen::Index c, double v) { ax[c] = v; });
    for (const Coupling& e : extra) {
      ax[e.a] -= e.g * x[e.b];
      ax[e.b] -= e.g * x[e.a];
    }
    for (Eigen::Index c = 0; c < ax.size(); ++c) out(c, ax[c]);
  }

  Eigen::VectorXd diagonal;
  std::vector<Eigen::VectorXd> upper;  ///< per axis, indexed by the lower cell
  std::vector<std::size_t> stride;
  std::vector<Coupling> extra;

 private:
  template <class Out>
  void apply_stencil(const Eigen::Ref<const Eigen::VectorXd>& x, Out&& out) const {
    switch (stride.size()) {
      case 1:
        apply_with<1>(x, out);
        break;
      case 2:
        apply_with<2>(x, out);
        break;
      default:
        apply_with<3>(x, out);
        break;
    }
  }

  template <int D, class Out>
  void apply_with(const Eigen::Ref<const Eigen::VectorXd>& x, Out& out) const {
    const Eigen::Index n = diagonal.size();
    std::array<Eigen::Index, D> s{};
    std::array<const double*, D> t{};
    for (int k = 0; k < D; ++k) {
      s[k] = static_cast<Eigen::Index>(stride[static_cast<std::size_t>(k)]);
      t[k] = upper[static_cast<std::size_t>(k)].data();
    }
    const double* d = diagonal.data();
    const double* v = x.data();
    // Near the ends some neighbours are outside the vector (their
    // conductances are zero); in between, no checks.
    auto edge = [&](Eigen::Index c) {
      double ax = d[c] * v[c];
      for (int k = 0; k < D; ++k) {
        if (c + s[k] < n) ax -= t[k][c] * v[c + s[k]];
        if (c >= s[k]) ax -= t[k][c - s[k]] * v[c - s[k]];
      }
      out(c, ax);
    };
    const Eigen::Index reach = s[D - 1];
    const Eigen::Index lo = std::min(reach, n);
    const Eigen::Index hi = std::max(lo, n - reach);
    for (Eigen::Index c = 0; c < lo; ++c) edge(c);
#pragma omp simd
    for (Eigen::Index c = lo; c < hi; ++c) {
      double ax = d[c] * v[c];
      for (int k = 0; k < D; ++k) ax -= t[k][c] * v[c + s[k]] + t[k][c - s[k]] * v[c - s[k]];
      out(c, ax);
    }
    for (Eigen::Index c = hi; c < n; ++c) edge(c);
  }
};

/// Jacobi preconditioning from the operator's diagonal (Eigen's
/// DiagonalPreconditioner reads a stored matrix's entries).
class GridJacobi : public Eigen::DiagonalPreconditioner<double> {
 public:
  GridJacobi& analyzePattern(const GridOperator& /*a*/) { return *this; }
  GridJacobi& factorize(const GridOperator& a) {
    m_invdiag = a.diagonal.cwiseInverse();
    m_isInitialized = true;
    return *this;
  }
  GridJacobi& compute(const GridOperator& a) { return factorize(a); }
};

}  // namespace darcydem

template <class Rhs>
struct Eigen::internal::generic_product_impl<darcydem::GridOperator, Rhs, Eigen::SparseShape,
                                             Eigen::DenseShape, Eigen::GemvProduct>
    : Eigen::internal::generic_product_impl_base<
          darcydem::GridOperator, Rhs,
          generic_product_impl<darcydem::GridOperator, Rhs, SparseShape, DenseShape, GemvProduct>> {
  template <class Dest>
  static void scaleAndAddTo(Dest& dst, const darcydem::GridOperator& a, const Rhs& x, const double& alpha) {
    a.add_product(x, alpha, dst);
  }
};
