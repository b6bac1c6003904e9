// Factorisation policies for the interior-point Newton matrices: a matrix
// type K with a fixed pattern (its values change every iteration), a
// symbolic analysis done once, and a numerical factorisation per iteration:
// LDL^T without pivoting when K is symmetric (positive definite, or
// quasi-definite [A B; B^T -C], A, C positive definite, which every
// symmetric permutation factorises: Vanderbei, SIAM J. Optim. 5, 1995),
// LU otherwise.
//
//   SparseKktFactorization<Backend>: CHOLMOD's simplicial LDL^T and UMFPACK
//     with SuiteSparseBackend, Eigen's SimplicialLDLT and SparseLU with
//     EigenBackend (KktSolvers below).
//   DenseKktFactorization: Eigen::LDLT / PartialPivLU for small scenes, which
//     must not pay for sparse machinery.
//
// Both store K in full (both triangles): LDL^T reads the lower one, LU
// both, and the assembly code does not depend on the choice.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/linalg/eigen_backend.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SparseCholesky>

#ifdef FCSOLVE_WITH_CHOLMOD
#include <fcsolve/linalg/suitesparse_backend.hpp>
#endif

#include <algorithm>
#include <memory>
#include <vector>

namespace fcsolve {
namespace ipm {

/// The sparse LDL^T and LU a linear-algebra backend offers for K.
template <class Backend>
struct KktSolvers {
  using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;
  using Lu = typename Backend::GeneralSolver;
  static void quiet(Ldlt&) {}
};
#ifdef FCSOLVE_WITH_CHOLMOD
template <>
struct KktSolvers<SuiteSparseBackend> {
  using Ldlt = Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Lower>;
  using Lu = SuiteSparseBackend::GeneralSolver;
  /// A failed factorisation is an expected event here (the caller then
  /// regularises): keep CHOLMOD from printing it.
  static void quiet(Ldlt& s) { s.cholmod().print = 0; }
};
#endif

template <class Backend_>
class SparseKktFactorization {
 public:
  using Backend = Backend_;
  static constexpr bool is_dense = false;

  /// Takes the pattern (values are overwritten before each factorisation).
  void set_pattern(SparseMatrix pattern, bool symmetric) {
    K_ = std::move(pattern);
    K_.makeCompressed();
    symmetric_ = symmetric;
    analysed_ = false;
    sym_.reset();
    gen_.reset();
  }
  Index size() const { return K_.rows(); }
  bool symmetric() const { return symmetric_; }
  /// Position of entry (i, j) in values() (-1 if not in the pattern).
  Index index_of(Index i, Index j) const {
    const int* inner = K_.innerIndexPtr();
    const int* b = inner + K_.outerIndexPtr()[j];
    const int* e = inner + K_.outerIndexPtr()[j + 1];
    const int* it = std::lower_bound(b, e, int(i));
    return (it != e && *it == i) ? Index(it - inner) : Index(-1);
  }
  double* values() { return K_.valuePtr(); }
  Index num_values() const { return K_.nonZeros(); }

  /// Numerical factorisation of the current values (symbolic analysis once).
  bool factorize() {
    if (symmetric_) {
      if (!sym_) {
        sym_ = std::make_unique<typename KktSolvers<Backend>::Ldlt>();
        KktSolvers<Backend>::quiet(*sym_);
      }
      if (!analysed_) sym_->analyzePattern(K_);
      analysed_ = true;
      sym_->factorize(K_);
      return sym_->info() == Eigen::Success;
    }
    if (!gen_) gen_ = std::make_unique<typename KktSolvers<Backend>::Lu>();
    if (!analysed_) gen_->analyzePattern(K_);
    analysed_ = true;
    gen_->factorize(K_);
    return gen_->info() == Eigen::Success;
  }
  void solve(const Vector& b, Vector& x) const {
    if (symmetric_) x = sym_->solve(b);
    else x = gen_->solve(b);
  }
  const SparseMatrix& matrix() const { return K_; }

 private:
  SparseMatrix K_;  // kept alive: CHOLMOD and UMFPACK refer to it
  bool symmetric_ = true, analysed_ = false;
  std::unique_ptr<typename KktSolvers<Backend>::Ldlt> sym_;
  std::unique_ptr<typename KktSolvers<Backend>::Lu> gen_;
};

class DenseKktFactorization {
 public:
  using Backend = EigenBackend;  // for the few sparse solves around the IPM
  static constexpr bool is_dense = true;

  void set_pattern(const SparseMatrix& pattern, bool symmetric) {
    K_.setZero(pattern.rows(), pattern.cols());
    symmetric_ = symmetric;
  }
  Index size() const { return K_.rows(); }
  bool symmetric() const { return symmetric_; }
  Index index_of(Index i, Index j) const { return i + j * K_.rows(); }
  double* values() { return K_.data(); }
  Index num_values() const { return K_.size(); }

  bool factorize() {
    if (symmetric_) {
      ldlt_.compute(K_);
      if (ldlt_.info() != Eigen::Success) return false;
      const auto d = ldlt_.vectorD().cwiseAbs();
      return d.size() == 0 || d.minCoeff() > 1e-300 * std::max(1.0, d.maxCoeff());
    }
    lu_.compute(K_);
    // PartialPivLU does not report singularity: check the pivots.
    const auto d = lu_.matrixLU().diagonal().cwiseAbs();
    return d.size() == 0 || d.minCoeff() > 1e-300 * std::max(1.0, d.maxCoeff());
  }
  void solve(const Vector& b, Vector& x) const {
    if (symmetric_) x = ldlt_.solve(b);
    else x = lu_.solve(b);
  }
  const DenseMatrix& matrix() const { return K_; }

 private:
  DenseMatrix K_;
  bool symmetric_ = true;
  Eigen::LDLT<DenseMatrix> ldlt_;
  Eigen::PartialPivLU<DenseMatrix> lu_;
};

}  // namespace ipm
}  // namespace fcsolve
