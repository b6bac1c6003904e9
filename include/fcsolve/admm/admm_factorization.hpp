// The linear system of the ADMM r-update, (W_s + rho I) r = b, with W_s =
// (W + W^T)/2 the symmetric part of W (W of real data is symmetric only up
// to rounding; the solver puts the antisymmetric rest on the right-hand side).
// Factorised once per rho: the solver refactorises only when rho changes.
//   DenseAdmmFactorization            Eigen::LLT, for the few contacts of a DenseStorage scene
//   SparseAdmmFactorization<Backend>  Backend::SymmetricSolver: CHOLMOD (SuiteSparseBackend)
//                                     or Eigen's SimplicialLDLT (EigenBackend); the symbolic
//                                     analysis once, a numerical factorisation per rho
// A policy has: void compute(const SparseMatrix& Ws); bool factorize(double rho)
// (false: not positive definite or failed); void solve(const Vector& b, Vector& x);
// solve_allocates: whether solve() allocates (CHOLMOD's cholmod_solve returns a
// new dense vector from its own allocator), so that the solver keeps that call
// outside its no-allocation bracket.
#pragma once

#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/storage/dense.hpp>

#include <Eigen/Cholesky>

#include <type_traits>
#include <vector>

namespace fcsolve {

class DenseAdmmFactorization {
 public:
  static constexpr bool solve_allocates = false;
  static constexpr const char* name = "dense-llt";

  void compute(const SparseMatrix& Ws) {
    Ws_ = DenseMatrix(Ws);
    A_.resize(Ws_.rows(), Ws_.cols());
  }
  bool factorize(double rho) {
    A_ = Ws_;
    A_.diagonal().array() += rho;
    llt_.compute(A_);
    return llt_.info() == Eigen::Success;
  }
  void solve(const Vector& b, Vector& x) {
    x = b;
    llt_.solveInPlace(x);
  }

 private:
  DenseMatrix Ws_, A_;
  Eigen::LLT<DenseMatrix> llt_;
};

template <class Backend>
class SparseAdmmFactorization {
 public:
  static constexpr bool solve_allocates = !std::is_same_v<Backend, EigenBackend>;
  static constexpr const char* name = Backend::name;

  /// Keeps W_s + 0 I with every diagonal entry stored, so that a new rho
  /// rewrites those values only and the pattern (and its analysis) stays.
  void compute(const SparseMatrix& Ws) {
    const Index m = Ws.rows();
    SparseMatrix identity(m, m);
    identity.setIdentity();
    A_ = Ws + identity;
    A_.makeCompressed();
    diagonal_position_.assign(std::size_t(m), 0);
    diagonal_.resize(m);
    for (Index j = 0; j < m; ++j)
      for (Index k = A_.outerIndexPtr()[j]; k < A_.outerIndexPtr()[j + 1]; ++k)
        if (A_.innerIndexPtr()[k] == j) {
          diagonal_position_[std::size_t(j)] = k;
          diagonal_[j] = A_.valuePtr()[k] - 1.0;
        }
    solver_.analyzePattern(A_);
    work_.resize(m);
  }
  bool factorize(double rho) {
    for (std::size_t i = 0; i < diagonal_position_.size(); ++i)
      A_.valuePtr()[diagonal_position_[i]] = diagonal_[Index(i)] + rho;
    solver_.factorize(A_);
    if (solver_.info() != Eigen::Success) return false;
    if constexpr (std::is_same_v<Backend, EigenBackend>)
      inverse_d_ = solver_.vectorD().cwiseInverse();  // vectorD() returns a copy: not in solve()
    return true;
  }
  void solve(const Vector& b, Vector& x) {
    if constexpr (std::is_same_v<Backend, EigenBackend>) {
      // SimplicialLDLT::solve permutes in place, which allocates a mask:
      // P^T L D L^T P x = b by hand, through a work vector
      work_.noalias() = solver_.permutationP() * b;
      solver_.matrixL().solveInPlace(work_);
      work_.array() *= inverse_d_.array();
      solver_.matrixU().solveInPlace(work_);
      x.noalias() = solver_.permutationPinv() * work_;
    } else {
      x = solver_.solve(b);
    }
  }

 private:
  SparseMatrix A_;  // kept alive: CHOLMOD refers to the factorised matrix
  Vector diagonal_, work_, inverse_d_;
  std::vector<Index> diagonal_position_;
  typename Backend::SymmetricSolver solver_;
};

/// LLT for DenseStorage scenes, the default sparse Cholesky otherwise
/// (CHOLMOD when the program links fcsolve::cholmod, SimplicialLDLT if not).
template <class Storage>
using DefaultAdmmFactorization =
    std::conditional_t<std::is_same_v<Storage, DenseStorage<Storage::block_dim>>,
                       DenseAdmmFactorization, SparseAdmmFactorization<DefaultBackend>>;

}  // namespace fcsolve
