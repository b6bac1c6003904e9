// The largest eigenvalue of a symmetric operator by the Lanczos process,
// from products alone (a sparse W's spectrum without a dense eigensolver).
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace fcsolve {
namespace linalg {

struct LanczosEstimate {
  double value = std::numeric_limits<double>::quiet_NaN();  ///< the largest Ritz value
  double residual_bound = std::numeric_limits<double>::infinity();  ///< an eigenvalue lies within it of `value`
  Index steps = 0;
  bool converged = false;  ///< residual_bound <= rel_tol |value|
};

/// Largest eigenvalue of the symmetric m x m operator `apply(x, y)` (y = A x,
/// x and y distinct) by the Lanczos process without reorthogonalisation
/// (Golub and Van Loan, Matrix Computations, 4th ed., Alg. 10.1.1). Lost
/// orthogonality makes converged Ritz values reappear as copies; it does not
/// spoil the extreme one (Paige 1980; G&VL Sec. 10.3). With T_k = S diag(theta)
/// S^T, the Ritz pair of theta has ||A y - theta y|| = beta_k |s_k| (G&VL
/// Thm 10.1.4), so an eigenvalue of A lies within that bound of theta; and
/// theta <= lambda_max (interlacing). The loop stops once the bound is at most
/// rel_tol |theta|. The start vector is pseudo-random with a fixed seed, so a
/// run gives the same answer every time.
template <class Apply>
LanczosEstimate largest_eigenvalue(Index m, Apply&& apply, double rel_tol = 1e-10, Index max_steps = 300) {
  LanczosEstimate out;
  if (m <= 0) return out;
  Vector q(m), q_previous = Vector::Zero(m), w(m);
  std::mt19937 generator(12345);
  std::normal_distribution<double> normal;
  for (Index i = 0; i < m; ++i) q[i] = normal(generator);
  q.normalize();
  std::vector<double> alpha, beta;  // T_k's diagonal and subdiagonal
  Eigen::SelfAdjointEigenSolver<DenseMatrix> ritz;
  double beta_k = 0;
  for (Index k = 0; k < max_steps; ++k) {
    apply(q, w);
    w -= beta_k * q_previous;
    const double a = q.dot(w);
    w -= a * q;
    alpha.push_back(a);
    beta_k = w.norm();
    out.steps = k + 1;
    const bool invariant = beta_k <= 1e-14 * std::abs(a);  // the Krylov space holds an eigenvector
    if (invariant || out.steps % 5 == 0 || out.steps == max_steps) {
      const Index n = Index(alpha.size());
      const Vector diagonal = Eigen::Map<const Vector>(alpha.data(), n);
      const Vector subdiagonal = n > 1 ? Vector(Eigen::Map<const Vector>(beta.data(), n - 1)) : Vector();
      ritz.computeFromTridiagonal(diagonal, subdiagonal, Eigen::ComputeEigenvectors);
      if (ritz.info() != Eigen::Success) return out;
      out.value = ritz.eigenvalues()[n - 1];  // ascending order
      out.residual_bound = beta_k * std::abs(ritz.eigenvectors()(n - 1, n - 1));
      out.converged = invariant || out.residual_bound <= rel_tol * std::abs(out.value);
      if (out.converged) return out;
    }
    beta.push_back(beta_k);
    q_previous.swap(q);
    q = w / beta_k;
  }
  return out;
}

}  // namespace linalg
}  // namespace fcsolve
