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
//     EigenBackend (KktSolvers below); an unsymmetric K whose factors fill
//     little goes to the backend's PatternLU where it has one (KLU,
//     refactorised with one pivot order: linalg/klu_pattern_lu.hpp; nipm
//     on generated rigid stacks 1.5 to 2.5x faster than with UMFPACK).
//   DenseKktFactorization: Eigen::LDLT / PartialPivLU for small scenes, which
//     must not pay for sparse machinery.
//   DenseCholeskyKktFactorization: the same with Eigen's blocked Cholesky
//     (LLT) for a symmetric K, where the form makes it positive definite
//     (LocalForm with s frozen: W PSD plus the cone blocks; its small
//     systems, and those of a dense W: kDenseKktFill); a K that is not
//     numerically fails, and KktSystem's caller regularises. At m = 2400
//     (one core, this machine) LLT took 0.2 s, LDLT 1.0 s, CHOLMOD's
//     simplicial LDL^T (no BLAS) some 9 s.
//
// Both store K in full (both triangles): LDL^T reads one, LU both, and the
// assembly code does not depend on the choice.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/linalg/backend_traits.hpp>
#include <fcsolve/linalg/eigen_backend.hpp>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>

#ifdef FCSOLVE_WITH_CHOLMOD
#include <fcsolve/linalg/suitesparse_backend.hpp>
#endif

#include <algorithm>
#include <memory>
#include <type_traits>
#include <vector>

namespace fcsolve {
namespace ipm {

/// Fill (nnz / size^2) from which K is factorised dense: its sparse
/// factors would be dense, and the dense factorisations run blocked, where
/// CHOLMOD's simplicial LDL^T runs without BLAS (an elastic body's FC/II of
/// 2352 columns: some 9 s a factorisation against 0.2 s; docs/results.md,
/// stop 65). A FEM body's W is full; a rigid pile's holds some 50 blocks a
/// row.
inline constexpr double kDenseKktFill = 0.3;

/// Whether a size x size matrix of `nonzeros` entries fills kDenseKktFill.
inline bool fills_densely(Index nonzeros, Index size) {
  const double m = double(size);
  return size > 0 && double(nonzeros) >= kDenseKktFill * m * m;
}

/// The sparse LDL^T and LU a linear-algebra backend offers for K. K is
/// stored pre-permuted (SparseKktFactorization), so LDL^T runs in natural
/// order.
template <class Backend>
struct KktSolvers {
  using Ldlt = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Upper, Eigen::NaturalOrdering<int>>;
  using Lu = typename Backend::GeneralSolver;
  static void configure(Ldlt&) {}
  static void configure(Lu&) {}
  /// The flops of the analysed factorisation: not reported by Eigen's LDL^T.
  static double analysed_flops(const Ldlt&) { return 0; }
};
#ifdef FCSOLVE_WITH_CHOLMOD
template <>
struct KktSolvers<SuiteSparseBackend> {
  using Ldlt = Eigen::CholmodSimplicialLDLT<SparseMatrix, Eigen::Upper>;
  using Lu = SuiteSparseBackend::GeneralSolver;
  /// Natural order (K comes pre-permuted: CHOLMOD would otherwise form
  /// P K P^T at every factorisation), and quiet: a failed factorisation is
  /// an expected event here (the caller then regularises).
  static void configure(Ldlt& s) {
    s.cholmod().print = 0;
    s.cholmod().nmethods = 1;
    s.cholmod().method[0].ordering = CHOLMOD_NATURAL;
    s.cholmod().postorder = 0;
  }
  /// No refinement inside UMFPACK's solve: KktSystem refines against the
  /// unregularised matrix itself, and the polish is a Newton iteration.
  static void configure(Lu& s) { s.umfpackControl()(UMFPACK_IRSTEP) = 0; }
  /// CHOLMOD's flop count of the analysed LDL^T (cholmod_common::fl, set
  /// by cholmod_analyze).
  static double analysed_flops(Ldlt& s) { return s.cholmod().fl; }
};
#endif

/// K in compressed columns, symmetrically permuted once by AMD (the
/// ordering depends on the pattern only), so that every factorisation
/// works on it in place.
template <class Backend_>
class SparseKktFactorization {
 public:
  using Backend = Backend_;
  static constexpr bool is_dense = false;

  /// Takes the pattern (values are overwritten before each factorisation).
  void set_pattern(const SparseMatrix& pattern, bool symmetric) {
    if (perm_.size() != pattern.rows()) {
      Eigen::AMDOrdering<int> amd;
      Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
      amd(pattern, inverse);  // row/column j of the permuted K is inverse(j) of K
      perm_ = inverse.inverse();
    }
    K_ = pattern.twistedBy(perm_);
    K_.makeCompressed();
    symmetric_ = symmetric;
    analysed_ = false;
    pattern_ = false;
    pattern_checked_ = false;
    flops_ = 0;
    sym_.reset();
    gen_.reset();
    pb_.resize(K_.rows());
    px_.resize(K_.rows());
  }
  Index size() const { return K_.rows(); }
  bool symmetric() const { return symmetric_; }
  /// Position of entry (i, j) of K in values() (-1 if not in the pattern).
  Index index_of(Index i, Index j) const {
    const int pi = perm_.indices()[i], pj = perm_.indices()[j];
    const int* inner = K_.innerIndexPtr();
    const int* b = inner + K_.outerIndexPtr()[pj];
    const int* e = inner + K_.outerIndexPtr()[pj + 1];
    const int* it = std::lower_bound(b, e, pi);
    return (it != e && *it == pi) ? Index(it - inner) : Index(-1);
  }
  double* values() { return K_.valuePtr(); }
  Index num_values() const { return K_.nonZeros(); }

  /// Numerical factorisation of the current values (symbolic analysis once).
  bool factorize() {
    if (symmetric_) {
      analyse_with(sym_);
      sym_->factorize(K_);
      return sym_->info() == Eigen::Success;
    }
    if (choose_pattern_lu()) return factorize_pattern_lu();
    analyse_with(gen_);
    gen_->factorize(K_);
    return gen_->info() == Eigen::Success;
  }

  /// The flops of a numerical factorisation as its symbolic analysis counts
  /// them (the analysis is done here if it was not, and kept); 0 where the
  /// factorisation does not say (UMFPACK, Eigen's LDL^T and LU).
  double estimated_flops() {
    if (symmetric_) {
      analyse_with(sym_);
      return flops_;
    }
    if (choose_pattern_lu()) return pattern_lu_flops();
    return 0;
  }
  void solve(const Vector& b, Vector& x) const {
    pb_.noalias() = perm_ * b;
    if (symmetric_) px_ = sym_->solve(pb_);
    else if (pattern_) pattern_solve(pb_, px_);
    else px_ = gen_->solve(pb_);
    x.noalias() = perm_.transpose() * px_;
  }

 private:
  void pattern_solve(const Vector& b, Vector& x) const {
    if constexpr (has_pattern_lu<Backend>::value) pattern_lu_.solve(b, x);
  }

  /// For an unsymmetric K: whether it goes to the backend's PatternLU
  /// (analysed there once, when it suits the pattern).
  bool choose_pattern_lu() {
    if constexpr (has_pattern_lu<Backend>::value) {
      if (!pattern_checked_) {
        pattern_ = pattern_lu_suits(pattern_lu_, K_);
        pattern_checked_ = true;
      }
    }
    return pattern_;
  }
  bool factorize_pattern_lu() {
    if constexpr (has_pattern_lu<Backend>::value) return pattern_lu_.factorize(K_);
    return false;
  }
  double pattern_lu_flops() const {
    if constexpr (has_pattern_lu<Backend>::value) return pattern_lu_.estimated_flops();
    return 0;
  }

  template <class Solver>
  void analyse_with(std::unique_ptr<Solver>& solver) {
    if (!solver) {
      solver = std::make_unique<Solver>();
      KktSolvers<Backend>::configure(*solver);
    }
    if (!analysed_) {
      solver->analyzePattern(K_);
      if constexpr (std::is_same_v<Solver, typename KktSolvers<Backend>::Ldlt>)
        flops_ = KktSolvers<Backend>::analysed_flops(*solver);
    }
    analysed_ = true;
  }

  SparseMatrix K_;  // P K P^T, kept alive: CHOLMOD, UMFPACK and KLU refer to it
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> perm_;
  bool symmetric_ = true, analysed_ = false, pattern_ = false, pattern_checked_ = false;
  double flops_ = 0;  // of the analysed LDL^T, where its analysis counts them
  std::unique_ptr<typename KktSolvers<Backend>::Ldlt> sym_;
  std::unique_ptr<typename KktSolvers<Backend>::Lu> gen_;
  // solve() is const for the callers; KLU's solve checks its backward error
  // and may factorise afresh, which changes the factorisation, not K.
  mutable typename has_pattern_lu<Backend>::type pattern_lu_;
  mutable Vector pb_, px_;
};

template <bool PositiveDefinite>
class BasicDenseKktFactorization {
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
    if (symmetric_ && PositiveDefinite) {
      llt_.compute(K_);
      return llt_.info() == Eigen::Success;
    }
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
  /// n^3 / 3 for LDL^T, 2 n^3 / 3 for LU (Golub & Van Loan, 4th ed., 3.2, 4.1).
  double estimated_flops() const {
    const double n = double(K_.rows());
    return (symmetric_ ? 1.0 : 2.0) * n * n * n / 3.0;
  }
  void solve(const Vector& b, Vector& x) const {
    if (symmetric_ && PositiveDefinite) x = llt_.solve(b);
    else if (symmetric_) x = ldlt_.solve(b);
    else x = lu_.solve(b);
  }

 private:
  DenseMatrix K_;
  bool symmetric_ = true;
  Eigen::LLT<DenseMatrix> llt_;
  Eigen::LDLT<DenseMatrix> ldlt_;
  Eigen::PartialPivLU<DenseMatrix> lu_;
};

using DenseKktFactorization = BasicDenseKktFactorization<false>;
using DenseCholeskyKktFactorization = BasicDenseKktFactorization<true>;

}  // namespace ipm
}  // namespace fcsolve
