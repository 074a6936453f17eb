#pragma once
// The pressure matrix of a Cartesian grid held as its stencil, for Eigen's
// conjugate gradients without a stored matrix (Eigen's "matrix-free
// solvers"): a diagonal and, per axis k, the conductance between each cell
// c and its upper neighbour c + stride_k (zero where c is on the grid's last
// layer along k):
//   (A x)_c = diag_c x_c - sum_k (upper_k[c] x_{c+s_k} + upper_k[c-s_k] x_{c-s_k}).
// A x is then a few whole-vector operations (vectorised), where a stored
// sparse matrix reads an index and a value per entry.
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
  }

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
    y.array() += alpha * diagonal.array() * x.array();
    for (std::size_t k = 0; k < stride.size(); ++k) {
      const auto s = static_cast<Eigen::Index>(stride[k]);
      const Eigen::Index m = diagonal.size() - s;
      if (m <= 0) continue;
      const auto t = upper[k].head(m).array();
      y.head(m).array() -= alpha * t * x.segment(s, m).array();
      y.segment(s, m).array() -= alpha * t * x.head(m).array();
    }
  }

  Eigen::VectorXd diagonal;
  std::vector<Eigen::VectorXd> upper;  ///< per axis, indexed by the lower cell
  std::vector<std::size_t> stride;
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
