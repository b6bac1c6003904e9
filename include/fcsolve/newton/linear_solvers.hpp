// Linear-solver policies for the Newton systems J d = -G. J is unsymmetric
// and its pattern never changes during a solve, so the sparse policies run
// the symbolic analysis once (analyzePattern on the first matrix) and only
// the numerical factorisation at each iteration.
//   SparseNewtonLinearSolver<Backend>  Backend::PatternLU where the backend
//                                      has one (KLU, refactorising with the
//                                      first pivot order: SuiteSparseBackend
//                                      with KLU), else Backend::GeneralSolver:
//                                      UMFPACK or Eigen::SparseLU (EigenBackend,
//                                      no dependency); a J at least half full
//                                      goes to the backend's DenseLU where it
//                                      has one (LAPACK)
//   DenseNewtonLinearSolver            full-pivoting dense LU, for the few
//                                      contacts of a DenseStorage scene
// A policy has: using Matrix; bool factorize(const Matrix&) (false: singular
// or failed); void solve(const Vector& b, Vector& x); void reset() (forget
// the symbolic analysis: a new pattern follows).
// UMFPACK and KLU keep pointers into the factorised matrix until the next
// factorisation: the caller keeps J alive and unchanged until solve() is done.
#pragma once

#include <fcsolve/linalg/backend_traits.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/storage/dense.hpp>

#include <Eigen/LU>

#include <type_traits>

namespace fcsolve {

/// Fill (stored entries / n^2) from which J is factorised dense: a sparse
/// LU of a matrix at least half full fills in completely, so it does the
/// dense flops plus its own bookkeeping.
inline constexpr double kDenseLuMinFill = 0.5;

template <class Backend>
class SparseNewtonLinearSolver {
 public:
  using Matrix = SparseMatrix;
  static constexpr const char* name = Backend::name;

  bool factorize(const SparseMatrix& J) {
    if (!analysed_) {
      path_ = Path::general;
      if (has_dense_lu<Backend>::value &&
          double(J.nonZeros()) >= kDenseLuMinFill * double(J.rows()) * double(J.cols()))
        path_ = Path::dense;
      if constexpr (has_pattern_lu<Backend>::value)
        if (path_ == Path::general && pattern_lu_suits(pattern_lu_, J)) path_ = Path::pattern;
      // (Eigen's SparseLU sets no info() in analyzePattern: only factorize() reports)
      if (path_ == Path::general) lu_.analyzePattern(J);
      analysed_ = true;
    }
    if constexpr (has_dense_lu<Backend>::value)
      if (path_ == Path::dense) return dense_lu_.factorize(J);
    if constexpr (has_pattern_lu<Backend>::value)
      if (path_ == Path::pattern) return pattern_lu_.factorize(J);
    lu_.factorize(J);
    return lu_.info() == Eigen::Success;
  }
  void solve(const Vector& b, Vector& x) {
    if constexpr (has_dense_lu<Backend>::value)
      if (path_ == Path::dense) return dense_lu_.solve(b, x);
    if constexpr (has_pattern_lu<Backend>::value)
      if (path_ == Path::pattern) return pattern_lu_.solve(b, x);
    x = lu_.solve(b);
  }
  void reset() { analysed_ = false; }

  /// Which factorisation the last analysis chose: "general" (the backend's
  /// GeneralSolver), "pattern" (its PatternLU) or "dense" (its DenseLU).
  const char* path() const {
    return path_ == Path::dense ? "dense" : path_ == Path::pattern ? "pattern" : "general";
  }

 private:
  enum class Path { general, pattern, dense };
  typename Backend::GeneralSolver lu_;
  typename has_pattern_lu<Backend>::type pattern_lu_;
  typename has_dense_lu<Backend>::type dense_lu_;
  bool analysed_ = false;
  Path path_ = Path::general;
};

class DenseNewtonLinearSolver {
 public:
  using Matrix = DenseMatrix;
  static constexpr const char* name = "dense";

  bool factorize(const DenseMatrix& J) {
    lu_.compute(J);
    return lu_.isInvertible();
  }
  void solve(const Vector& b, Vector& x) { x = lu_.solve(b); }
  void reset() {}

 private:
  Eigen::FullPivLU<DenseMatrix> lu_;
};

/// Dense LU for DenseStorage scenes, the default sparse LU otherwise
/// (UMFPACK when the program links fcsolve::cholmod, Eigen's SparseLU if not).
template <class Storage>
using DefaultNewtonLinearSolver =
    std::conditional_t<std::is_same_v<Storage, DenseStorage<Storage::block_dim>>,
                       DenseNewtonLinearSolver, SparseNewtonLinearSolver<DefaultBackend>>;

}  // namespace fcsolve
