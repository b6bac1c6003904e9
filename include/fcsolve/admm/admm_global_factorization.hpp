// The linear system of the v-update of ADMM on FC/I (admm_global.hpp),
//   (M + rho H H^T) v = b.
// A(rho) = M + rho H H^T is kept on the union of the two patterns, so that a
// new rho rewrites values only: the symbolic analysis is done once, each rho
// costs one numerical factorisation. Cholesky (Backend::SymmetricSolver:
// CHOLMOD or SimplicialLDLT) when M is symmetric up to rounding; LU
// (Backend::GeneralSolver: UMFPACK or SparseLU) when it is not, as the LMGC
// files' M, whose symmetric part changes W by 16 % (problem/reduction.hpp).
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/linalg/default_backend.hpp>

#include <Eigen/SparseLU>

#include <memory>
#include <stdexcept>

namespace fcsolve {

template <class Backend = DefaultBackend>
class GlobalAdmmFactorization {
 public:
  /// Both solvers may allocate in solve(): the ADMM loop keeps the call
  /// outside its no-allocation bracket.
  static constexpr bool solve_allocates = true;

  /// The pattern of M + H H^T and the symbolic analysis; `symmetric`
  /// chooses Cholesky (true) or LU.
  void compute(const SparseMap& M, const SparseMap& H, bool symmetric) {
    {
      const SparseMatrix Mc(M), HHt = SparseMatrix(H * SparseMatrix(H.transpose()));
      // 0 * X keeps X's pattern: both sums have the union pattern, in the
      // same order; only their values are kept (one pattern in memory)
      SparseMatrix contact_part = 0.0 * Mc + HHt;
      contact_part.makeCompressed();
      A_ = Mc + 0.0 * HHt;
      A_.makeCompressed();
      if (A_.nonZeros() != contact_part.nonZeros())
        throw std::logic_error("GlobalAdmmFactorization: the two patterns differ");
      mass_values_ = Eigen::Map<const Vector>(A_.valuePtr(), A_.nonZeros());
      contact_values_ = Eigen::Map<const Vector>(contact_part.valuePtr(), A_.nonZeros());
    }
    symmetric_ = symmetric;
    sym_.reset();
    gen_.reset();
    if (symmetric_) {
      sym_ = std::make_unique<typename Backend::SymmetricSolver>();
      sym_->analyzePattern(A_);
    } else {
      gen_ = std::make_unique<typename Backend::GeneralSolver>();
      gen_->analyzePattern(A_);
    }
  }

  /// A(rho) factorised; false if that failed (singular, or not positive
  /// definite for Cholesky).
  bool factorize(double rho) {
    Eigen::Map<Vector>(A_.valuePtr(), A_.nonZeros()) = mass_values_ + rho * contact_values_;
    if (symmetric_) {
      sym_->factorize(A_);
      return sym_->info() == Eigen::Success;
    }
    gen_->factorize(A_);
    return gen_->info() == Eigen::Success;
  }

  void solve(const Vector& b, Vector& x) const {
    if (symmetric_)
      x = sym_->solve(b);
    else
      x = gen_->solve(b);
  }

 private:
  SparseMatrix A_;  // kept alive: UMFPACK and CHOLMOD refer to it
  Vector mass_values_, contact_values_;  // M's and H H^T's values on A_'s pattern
  bool symmetric_ = true;
  std::unique_ptr<typename Backend::SymmetricSolver> sym_;
  std::unique_ptr<typename Backend::GeneralSolver> gen_;
};

}  // namespace fcsolve
