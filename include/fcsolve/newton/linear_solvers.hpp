// Linear-solver policies for the Newton systems J d = -G. J is unsymmetric
// and its pattern never changes during a solve, so the sparse policies run
// the symbolic analysis once (analyzePattern on the first matrix) and only
// the numerical factorisation at each iteration.
//   SparseNewtonLinearSolver<Backend>  Backend::GeneralSolver: UMFPACK
//                                      (SuiteSparseBackend) or Eigen::SparseLU
//                                      (EigenBackend, no dependency)
//   DenseNewtonLinearSolver            full-pivoting dense LU, for the few
//                                      contacts of a DenseStorage scene
// A policy has: using Matrix; bool factorize(const Matrix&) (false: singular
// or failed); void solve(const Vector& b, Vector& x); void reset() (forget
// the symbolic analysis: a new pattern follows).
// UMFPACK keeps pointers into the factorised matrix until the next
// factorisation: the caller keeps J alive and unchanged until solve() is done.
#pragma once

#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/storage/dense.hpp>

#include <Eigen/LU>

#include <type_traits>

namespace fcsolve {

template <class Backend>
class SparseNewtonLinearSolver {
 public:
  using Matrix = SparseMatrix;
  static constexpr const char* name = Backend::name;

  bool factorize(const SparseMatrix& J) {
    if (!analysed_) {
      lu_.analyzePattern(J);
      if (lu_.info() != Eigen::Success) return false;
      analysed_ = true;
    }
    lu_.factorize(J);
    return lu_.info() == Eigen::Success;
  }
  void solve(const Vector& b, Vector& x) { x = lu_.solve(b); }
  void reset() { analysed_ = false; }

 private:
  typename Backend::GeneralSolver lu_;
  bool analysed_ = false;
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
