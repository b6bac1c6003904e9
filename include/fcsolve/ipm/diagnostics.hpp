// Cheap structural diagnostics of a problem, which Acary 2025 (talk, docs/references.md) relates
// to the robustness of the solvers ("the rank of H (~ ratio number of
// contact unknowns / number of dofs) plays an important role"):
//   contact-to-dof ratio c = d nc / n  (c > 1 forces a rank-deficient H),
//   rank(H) from a column-pivoted sparse QR (of a dense symmetric W, from
//   its eigenvalues),
//   the extreme eigenvalues of the symmetric part of W = H^T M^-1 H (cond(W);
//   zero eigenvalues when H is rank-deficient), and the asymmetry of W.
#pragma once

#include <fcsolve/ipm/kkt_factorization.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/linalg/lanczos.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseQR>

#include <limits>

namespace fcsolve {
namespace ipm {

struct ProblemDiagnostics {
  double contact_ratio = std::numeric_limits<double>::quiet_NaN();  ///< d nc / n (global only)
  Index rank_H = -1;           ///< estimated rank of H (global) or W (local); -1 not computed (m > kDiagnosticsDenseLimit)
  Index columns_H = 0;         ///< m
  double lambda_min_W = std::numeric_limits<double>::quiet_NaN();  ///< of (W + W^T) / 2; NaN not computed
  double lambda_max_W = std::numeric_limits<double>::quiet_NaN();
  double cond_W = std::numeric_limits<double>::quiet_NaN();  ///< lambda_max / lambda_min (inf if <= 0 or not positive definite)
  double asymmetry_W = 0;      ///< ||W - W^T||_F / ||W||_F
};

/// Largest m for which the rank of H or W (column-pivoted sparse QR) and
/// the spectrum of a dense W (dense eigensolver) are computed. The QR's fill
/// grows fast on piles: measured (`fcsolve check`, docs/results.md, stop 64)
/// 2.8 s at 3003 columns, 87 s at 9018 and 6.9 minutes at 15 030; above the
/// limit d nc / n still bounds the rank deficiency from below (global). A
/// sparse W's extreme eigenvalues come from Lanczos at any size.
inline constexpr Index kDiagnosticsDenseLimit = 3000;

namespace detail {

inline Index sparse_rank(const SparseMatrix& A) {
  // Column-pivoted QR of the taller orientation; Eigen's default threshold.
  SparseMatrix B = A.rows() >= A.cols() ? A : SparseMatrix(A.transpose());
  B.makeCompressed();
  Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> qr(B);
  return qr.info() == Eigen::Success ? Index(qr.rank()) : Index(-1);
}

/// The sparse QR's default rank threshold for an m x m matrix, 20 (rows +
/// cols) eps times its largest |lambda|.
inline double spectral_rank_threshold(Index m, double largest) {
  return 40.0 * double(m) * std::numeric_limits<double>::epsilon() * largest;
}

/// Rank of a symmetric matrix from its eigenvalues: those above
/// spectral_rank_threshold.
inline Index spectral_rank(const Vector& eigenvalues) {
  const double largest = eigenvalues.size() ? eigenvalues.cwiseAbs().maxCoeff() : 0.0;
  const double threshold = spectral_rank_threshold(eigenvalues.size(), largest);
  return Index((eigenvalues.array().abs() > threshold).count());
}

inline void set_condition(ProblemDiagnostics& d) {
  d.cond_W = d.lambda_min_W > 0 ? d.lambda_max_W / d.lambda_min_W : std::numeric_limits<double>::infinity();
}

/// The whole spectrum of a dense (W + W^T) / 2 into d and `eigenvalues`
/// (m <= kDiagnosticsDenseLimit).
inline void dense_spectrum(const SparseMatrix& W, ProblemDiagnostics& d, Vector& eigenvalues) {
  if (W.rows() == 0 || W.rows() > kDiagnosticsDenseLimit) return;
  const DenseMatrix S = DenseMatrix(symmetric_part(W));
  Eigen::SelfAdjointEigenSolver<DenseMatrix> es(S, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return;
  d.lambda_min_W = es.eigenvalues().minCoeff();
  d.lambda_max_W = es.eigenvalues().maxCoeff();
  set_condition(d);
  eigenvalues = es.eigenvalues();
}

/// Relative accuracy asked of the Lanczos estimates, and the least they
/// must reach to be reported.
inline constexpr double kLanczosTol = 1e-10;
inline constexpr double kLanczosReportTol = 1e-6;

/// The extreme eigenvalues of a sparse S = (W + W^T) / 2, at any size:
/// lambda_max by Lanczos on S; lambda_min = 0 where the rank is known to be
/// below m, else 1 / lambda_max(S^-1) by Lanczos on a sparse Cholesky
/// factor of S (AMD order). Where S has no Cholesky factor (singular or
/// indefinite to roundoff) lambda_min is not computed and cond_W is inf.
/// The dense eigensolver took 5.4 s of `check`'s 7.5 s on a box stack of
/// 3000 columns (docs/results.md, stop 67).
inline void sparse_spectrum(const SparseMatrix& W, ProblemDiagnostics& d) {
  const Index m = W.rows();
  if (m == 0) return;
  const SparseMatrix S = symmetric_part(W);
  const auto top = linalg::largest_eigenvalue(m, [&](const Vector& x, Vector& y) { y.noalias() = S * x; }, kLanczosTol);
  if (top.residual_bound > kLanczosReportTol * std::abs(top.value)) return;
  d.lambda_max_W = top.value;
  if (d.rank_H >= 0 && d.rank_H < m) {
    d.lambda_min_W = 0;
    set_condition(d);
    return;
  }
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> llt(S);
  if (llt.info() != Eigen::Success) {
    d.cond_W = std::numeric_limits<double>::infinity();
    return;
  }
  const auto inverse = linalg::largest_eigenvalue(m, [&](const Vector& x, Vector& y) { y = llt.solve(x); }, kLanczosTol);
  if (inverse.residual_bound > kLanczosReportTol * std::abs(inverse.value) || !(inverse.value > 0)) return;
  d.lambda_min_W = 1.0 / inverse.value;
  set_condition(d);
}

/// How far above the spectral rank's threshold lambda_min must lie for
/// dense_definite_spectrum to claim full rank: a Cholesky factor of a
/// singular S can exist in floating point (backward error about m eps
/// ||S||, Higham, Accuracy and Stability of Numerical Algorithms, 2nd ed.,
/// Thm 10.3), so near the threshold the eigensolver decides.
inline constexpr double kDefiniteRankMargin = 1e3;

/// The extreme eigenvalues of a dense S = (W + W^T) / 2 that is positive
/// definite with room to spare: a dense Cholesky factor, lambda_max by
/// Lanczos on S, lambda_min = 1 / lambda_max(S^-1) by Lanczos on the
/// factor's solves. True (d set) only where both estimates reached
/// kLanczosReportTol and lambda_min is kDefiniteRankMargin times above
/// spectral_rank's threshold, so that S has full rank; false (d untouched)
/// otherwise. The diagnostics of a FEM block's FC/II of 2352 columns: 1.4 s
/// instead of the eigensolver's 3.0 s, the same values to 12 digits
/// (docs/results.md, stop 68).
inline bool dense_definite_spectrum(const SparseMatrix& W, ProblemDiagnostics& d) {
  const Index m = W.rows();
  if (m == 0 || m > kDiagnosticsDenseLimit) return false;
  const DenseMatrix S = DenseMatrix(symmetric_part(W));
  const Eigen::LLT<DenseMatrix> llt(S);
  if (llt.info() != Eigen::Success) return false;
  const auto top = linalg::largest_eigenvalue(
      m, [&](const Vector& x, Vector& y) { y.noalias() = S * x; }, kLanczosTol);
  const auto inverse = linalg::largest_eigenvalue(m, [&](const Vector& x, Vector& y) { y = llt.solve(x); }, kLanczosTol);
  if (top.residual_bound > kLanczosReportTol * std::abs(top.value) ||
      inverse.residual_bound > kLanczosReportTol * std::abs(inverse.value) || !(inverse.value > 0))
    return false;
  const double lambda_min = 1.0 / inverse.value;
  if (!(lambda_min > kDefiniteRankMargin * spectral_rank_threshold(m, top.value))) return false;
  d.lambda_min_W = lambda_min;
  d.lambda_max_W = top.value;
  set_condition(d);
  return true;
}

/// W's spectrum and, for a local problem (`rank_from_W`), its rank. A dense
/// W (an elastic body's FC/II) that is positive definite gets its extreme
/// eigenvalues from a Cholesky factor and Lanczos, and full rank where it is
/// symmetric; otherwise a dense symmetric W takes its rank from the
/// eigenvalues of the dense solver: its sparse QR fills completely and runs
/// without BLAS (7 of `check`'s 18 s on a FEM block of 2352 columns). A
/// sparse W takes its rank from the QR first, which then gives lambda_min = 0.
inline void spectrum_and_rank(const SparseMatrix& W, ProblemDiagnostics& d, bool rank_from_W) {
  d.asymmetry_W = relative_asymmetry(W);
  const Index m = W.rows();
  if (fills_densely(W.nonZeros(), m)) {
    if (dense_definite_spectrum(W, d)) {
      if (rank_from_W) d.rank_H = d.asymmetry_W <= kSymmetryRoundoff ? m : sparse_rank(W);
      return;
    }
    Vector eigenvalues;
    dense_spectrum(W, d, eigenvalues);
    if (rank_from_W && m <= kDiagnosticsDenseLimit)
      d.rank_H = d.asymmetry_W <= kSymmetryRoundoff && eigenvalues.size() ? spectral_rank(eigenvalues) : sparse_rank(W);
    return;
  }
  if (rank_from_W && m <= kDiagnosticsDenseLimit) d.rank_H = sparse_rank(W);
  sparse_spectrum(W, d);
}

}  // namespace detail

/// A global problem's W is formed (by the reduction) only up to
/// kDiagnosticsDenseLimit columns; its rank is H's.
template <class Backend = DefaultBackend>
ProblemDiagnostics diagnose(const GlobalProblemView& p) {
  ProblemDiagnostics d;
  d.contact_ratio = double(p.d) * double(p.num_contacts()) / double(p.num_dofs());
  d.columns_H = p.size();
  if (p.size() <= kDiagnosticsDenseLimit) {
    d.rank_H = detail::sparse_rank(SparseMatrix(p.H));
    GlobalReduction<Backend> reduction(p);
    detail::spectrum_and_rank(reduction.local().W, d, false);
  }
  return d;
}

inline ProblemDiagnostics diagnose(const LocalProblemView& p) {
  ProblemDiagnostics d;
  d.columns_H = p.size();
  detail::spectrum_and_rank(SparseMatrix(p.W), d, true);
  return d;
}

}  // namespace ipm
}  // namespace fcsolve
