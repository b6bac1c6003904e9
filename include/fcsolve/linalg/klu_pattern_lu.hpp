// Sparse LU for a sequence of matrices with one pattern, by SuiteSparse's
// KLU (Davis & Palamadai Natarajan, "Algorithm 907: KLU, a direct sparse
// solver for circuit simulation problems", ACM TOMS 37(3), 2010): a block
// triangular form and AMD ordering once per pattern, a left-looking
// Gilbert-Peierls LU at the first factorisation, then klu_refactor, which
// reuses that factorisation's pivot order on the next matrix of the
// pattern: no pivot search, no allocation.
//
// For the Newton matrices of contact problems J = A W + B (reduced) and the
// global ones, whose pattern is fixed for a whole solve and whose fill is
// small, this is 2 to 4x faster than a multifrontal LU (UMFPACK) that sets
// up its fronts again at every factorisation (nsn-ac, generated box stacks
// of 100 to 1000 contacts, docs/results.md).
//
// A fresh factorisation keeps the diagonal pivots of AMD's order wherever
// they are not tiny (kDiagonalPivotTolerance, far below KLU's default of
// 1e-3): AMD's order and its fill bound assume diagonal pivots, and every
// row swap breaks them. The global Newton matrix [M -H; A H^T B] has
// contact rows whose pivots, B plus what eliminating the velocities adds,
// can fall below 1e-3 of their column: on a wall of 10^4 contacts given as
// FC/I, KLU's default pivoting swapped 5553 rows, filled the factors 24x
// AMD's prediction and took 16-22 s where diagonal pivots take 0.06 s,
// with a backward error of 1.5e-12 (refined once: below 1e-12).
//
// Pivots kept for sparsity, or a reused pivot order, may be bad ones for
// the values at hand (a contact that switched from sticking to sliding
// changes its rows), so such a factorisation is trusted only where its
// solves are accurate: each of its solves checks its backward error
// (Oettli-Prager normwise, ||b - J x|| / (||J|| ||x|| + ||b||), infinity
// norms), takes one step of iterative refinement above
// kRefactorBackwardError (one step in working precision suffices for a
// moderately unstable LU: Skeel, Math. Comp. 35, 1980), and past that
// factorises J afresh with KLU's partial pivoting and solves again. Needs
// KLU (the fcsolve::cholmod target links it when CMake finds it and then
// defines FCSOLVE_WITH_KLU).
#pragma once

#include <fcsolve/core/types.hpp>

#include <klu.h>

#include <cmath>
#include <limits>

namespace fcsolve {

/// Backward error above which a solve from a refactorisation (the previous
/// pivot order) is redone from a fresh pivoted factorisation. A pivoted LU
/// gives about n eps times its growth; 1e-12 leaves that room and catches a
/// pivot order that has gone bad.
inline constexpr double kRefactorBackwardError = 1e-12;

/// KLU's pivot tolerance for a fresh factorisation that keeps AMD's order:
/// the diagonal entry stays the pivot where |a_jj| >= tol max_i |a_ij|. A
/// pivot below it is too small to be checked by one refinement step; a
/// larger one is, and the backward error decides.
inline constexpr double kDiagonalPivotTolerance = 1e-8;

/// KLU's default partial pivoting tolerance, for the fallback.
inline constexpr double kPartialPivotTolerance = 1e-3;

/// A factorisation whose factors hold more than this many times the
/// entries AMD's analysis predicted (row swaps filled them) is not reused
/// by klu_refactor, which would do the same work again: the next matrix is
/// factorised afresh with the diagonal pivots first.
inline constexpr double kRefactorMaxFill = 2.0;

class KluPatternLU {
 public:
  KluPatternLU() { klu_defaults(&common_); }
  ~KluPatternLU() { reset(); }
  // A factorisation is not copied: a copy starts unanalysed.
  KluPatternLU(const KluPatternLU&) : KluPatternLU() {}
  KluPatternLU& operator=(const KluPatternLU& other) {
    if (this != &other) reset();
    return *this;
  }

  /// Forgets the pattern (its symbolic analysis) and the factorisation.
  void reset() {
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    if (symbolic_) klu_free_symbolic(&symbolic_, &common_);
    J_ = nullptr;
  }

  /// The symbolic analysis of J's pattern (block triangular form, AMD);
  /// false if KLU could not analyse it. J: a compressed SparseMatrix or a
  /// Map of one.
  template <class Sparse>
  bool analyse(const Sparse& J) {
    reset();
    symbolic_ = klu_analyze(int(J.rows()), outer(J), inner(J), &common_);
    return symbolic_ != nullptr;
  }

  /// The analysis' estimate of the factorisation's flops (AMD's count).
  double estimated_flops() const {
    return symbolic_ ? symbolic_->est_flops : std::numeric_limits<double>::infinity();
  }

  /// The analysis' estimate of the factorisation's flops per entry of L
  /// and U: the mean length of the dense updates. A left-looking LU does
  /// them one scalar at a time, a multifrontal LU in dense fronts (BLAS), so
  /// this says which of the two the pattern suits (linear_solvers.hpp).
  double flops_per_factor_entry() const {
    if (!symbolic_) return std::numeric_limits<double>::infinity();
    const double entries = symbolic_->lnz + symbolic_->unz;
    return entries > 0 ? symbolic_->est_flops / entries : 0.0;
  }

  /// Factorises J (compressed, square; the pattern of every call after the
  /// first, or after analyse(), must be that one until reset()). J is read
  /// again by solve(): the caller keeps it alive and unchanged until then.
  /// false when J is singular (a zero pivot) or a factor is not finite.
  bool factorize(const SparseMatrix& J) {
    if (!symbolic_ && !analyse(J)) return false;
    J_ = &J;
    norm_ = row_sum_norm(J);
    if (numeric_ && filled_as_predicted()) {
      refactored_ = klu_refactor(outer(J), inner(J), values(J), symbolic_, numeric_, &common_) &&
                    common_.status == KLU_OK && healthy();
      if (refactored_) return true;
    }
    return fresh(kDiagonalPivotTolerance) || fresh(kPartialPivotTolerance);
  }

  /// x = J^{-1} b from the last factorisation. A solve from a
  /// refactorisation or from diagonal pivots is checked: one refinement
  /// step if its backward error is too large, then, if it still is, a
  /// fresh factorisation with partial pivoting and its solve.
  void solve(const Vector& b, Vector& x) {
    substitute(b, x);
    if (!checked() || backward_error(b, x) <= kRefactorBackwardError) return;
    substitute(residual_, correction_);  // residual_ = b - J x, from backward_error
    x += correction_;
    if (backward_error(b, x) <= kRefactorBackwardError) return;
    if (fresh(kPartialPivotTolerance)) substitute(b, x);
    else x.setConstant(std::numeric_limits<double>::quiet_NaN());  // singular: the caller sees no step
  }

  /// Fresh factorisations so far (the others were refactorisations).
  long fresh_factorisations() const { return fresh_count_; }

  /// Fresh factorisations with KLU's partial pivoting, after diagonal
  /// pivots or a reused order failed.
  long pivoted_factorisations() const { return pivoted_count_; }

  /// Entries of the last factors, L and U, over AMD's prediction (1: no
  /// row swap added fill).
  double fill_over_prediction() const {
    if (!symbolic_ || !numeric_) return 0.0;
    const double predicted = symbolic_->lnz + symbolic_->unz;
    return predicted > 0 ? double(numeric_->lnz + numeric_->unz) / predicted : 1.0;
  }

 private:
  template <class Sparse>
  static int* outer(const Sparse& J) { return const_cast<int*>(J.outerIndexPtr()); }
  template <class Sparse>
  static int* inner(const Sparse& J) { return const_cast<int*>(J.innerIndexPtr()); }
  static double* values(const SparseMatrix& J) { return const_cast<double*>(J.valuePtr()); }

  /// A fresh factorisation of *J_ with KLU's pivot tolerance `tolerance`.
  bool fresh(double tolerance) {
    ++fresh_count_;
    if (tolerance == kPartialPivotTolerance) ++pivoted_count_;
    refactored_ = false;
    tolerance_ = tolerance;
    common_.tol = tolerance;
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(outer(*J_), inner(*J_), values(*J_), symbolic_, &common_);
    if (numeric_ && common_.status == KLU_OK && healthy()) return true;
    // A factorisation halted at a zero pivot is no pivot order to reuse.
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    return false;
  }

  /// Solves of a refactorisation or of diagonal pivots are checked; those
  /// of KLU's partial pivoting are trusted, as KLU's own.
  bool checked() const { return refactored_ || tolerance_ < kPartialPivotTolerance; }

  bool filled_as_predicted() const { return fill_over_prediction() <= kRefactorMaxFill; }

  /// No zero or non-finite pivot: KLU's rcond estimate, min |u_ii| / max |u_ii|.
  bool healthy() {
    return klu_rcond(symbolic_, numeric_, &common_) && std::isfinite(common_.rcond) && common_.rcond > 0;
  }

  void substitute(const Vector& b, Vector& x) {
    x = b;
    klu_solve(symbolic_, numeric_, int(x.size()), 1, x.data(), &common_);
  }

  /// ||b - J x||_inf / (||J||_inf ||x||_inf + ||b||_inf); J is compressed
  /// by columns, so the residual is accumulated column by column.
  double backward_error(const Vector& b, const Vector& x) {
    residual_ = b;
    for (Index j = 0; j < J_->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*J_, j); it; ++it) residual_[it.row()] -= it.value() * x[j];
    const double denominator = norm_ * x.lpNorm<Eigen::Infinity>() + b.lpNorm<Eigen::Infinity>();
    const double numerator = residual_.lpNorm<Eigen::Infinity>();
    return denominator > 0 ? numerator / denominator
                           : (numerator > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  }

  /// ||J||_inf, the largest absolute row sum.
  double row_sum_norm(const SparseMatrix& J) {
    row_sums_.setZero(J.rows());
    for (Index j = 0; j < J.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(J, j); it; ++it) row_sums_[it.row()] += std::abs(it.value());
    return J.rows() ? row_sums_.maxCoeff() : 0.0;
  }

  klu_common common_;
  klu_symbolic* symbolic_ = nullptr;
  klu_numeric* numeric_ = nullptr;
  const SparseMatrix* J_ = nullptr;
  bool refactored_ = false;
  double tolerance_ = kPartialPivotTolerance;  // of the last fresh factorisation
  double norm_ = 0;
  long fresh_count_ = 0, pivoted_count_ = 0;
  Vector residual_, correction_, row_sums_;
};

}  // namespace fcsolve
