// Measured symmetry of W or M. Real FCLIB data is only nearly symmetric
// (||W - W^T|| / ||W|| up to 2e-3 for Capsules; the LMGC global M gives a
// reduced W 16 % asymmetric), so solvers never assume symmetry silently.
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>

namespace fcsolve {

/// ||A - A^T||_F / ||A||_F for a square A (0 for A = 0).
template <class Sparse>
double relative_asymmetry(const Sparse& A) {
  const SparseMatrix At = SparseMatrix(A.transpose());
  const double skew = (SparseMatrix(A) - At).norm();
  const double norm = At.norm();
  return norm > 0 ? skew / norm : 0.0;
}

/// Below this relative asymmetry a matrix is symmetric up to rounding.
inline constexpr double kSymmetryRoundoff = 1e-14;

/// The symmetric part (A + A^T) / 2: what symmetric-only methods work on.
template <class Sparse>
SparseMatrix symmetric_part(const Sparse& A) {
  SparseMatrix S = 0.5 * (SparseMatrix(A) + SparseMatrix(A.transpose()));
  S.makeCompressed();
  return S;
}

}  // namespace fcsolve
