// Sparse LU for a sequence of matrices with one pattern, by SuiteSparse's
// KLU (Davis & Palamadai Natarajan, "Algorithm 907: KLU, a direct sparse
// solver for circuit simulation problems", ACM TOMS 37(3), 2010): a block
// triangular form and AMD ordering once per pattern, a left-looking
// Gilbert-Peierls LU with partial pivoting at the first factorisation, then
// klu_refactor, which reuses that factorisation's pivot order on the next
// matrix of the pattern: no pivot search, no allocation.
//
// For the Newton matrices of contact problems J = A W + B (reduced) and the
// global ones, whose pattern is fixed for a whole solve and whose fill is
// small, this is 2 to 4x faster than a multifrontal LU (UMFPACK) that sets
// up its fronts again at every factorisation (nsn-ac, generated box stacks
// of 100 to 1000 contacts, docs/results.md).
//
// A reused pivot order may be a bad one for the new values (a contact that
// switched from sticking to sliding changes its rows), so a refactorisation
// is accepted only where its solves are accurate: every solve from a
// refactorisation checks its backward error (Oettli-Prager normwise,
// ||b - J x|| / (||J|| ||x|| + ||b||), infinity norms) and, above
// kRefactorBackwardError, factorises J afresh with pivoting and solves
// again. Needs KLU (the fcsolve::cholmod target links it when CMake finds it
// and then defines FCSOLVE_WITH_KLU).
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
    if (numeric_) {
      refactored_ = klu_refactor(outer(J), inner(J), values(J), symbolic_, numeric_, &common_) &&
                    common_.status == KLU_OK && healthy();
      if (refactored_) return true;
    }
    return fresh();
  }

  /// x = J^{-1} b from the last factorisation; a solve from a
  /// refactorisation whose backward error is too large is redone from a
  /// fresh pivoted factorisation.
  void solve(const Vector& b, Vector& x) {
    substitute(b, x);
    if (!refactored_ || backward_error(b, x) <= kRefactorBackwardError) return;
    if (fresh()) substitute(b, x);
    else x.setConstant(std::numeric_limits<double>::quiet_NaN());  // singular: the caller sees no step
  }

  /// Fresh pivoted factorisations so far (the others were refactorisations).
  long fresh_factorisations() const { return fresh_count_; }

 private:
  template <class Sparse>
  static int* outer(const Sparse& J) { return const_cast<int*>(J.outerIndexPtr()); }
  template <class Sparse>
  static int* inner(const Sparse& J) { return const_cast<int*>(J.innerIndexPtr()); }
  static double* values(const SparseMatrix& J) { return const_cast<double*>(J.valuePtr()); }

  bool fresh() {
    ++fresh_count_;
    refactored_ = false;
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    numeric_ = klu_factor(outer(*J_), inner(*J_), values(*J_), symbolic_, &common_);
    if (numeric_ && common_.status == KLU_OK && healthy()) return true;
    // A factorisation halted at a zero pivot is no pivot order to reuse.
    if (numeric_) klu_free_numeric(&numeric_, &common_);
    return false;
  }

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
  double norm_ = 0;
  long fresh_count_ = 0;
  Vector residual_, row_sums_;
};

}  // namespace fcsolve
