// Cheap structural diagnostics of a problem, which Acary 2025 (talk, docs/references.md) relates
// to the robustness of the solvers ("the rank of H (~ ratio number of
// contact unknowns / number of dofs) plays an important role"):
//   contact-to-dof ratio c = d nc / n  (c > 1 forces a rank-deficient H),
//   rank(H) from a column-pivoted sparse QR (of a dense symmetric W, from
//   its eigenvalues),
//   the spectrum of the symmetric part of W = H^T M^-1 H (cond(W); zero
//   eigenvalues when H is rank-deficient), and the asymmetry of W.
#pragma once

#include <fcsolve/ipm/kkt_factorization.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <Eigen/Eigenvalues>
#include <Eigen/OrderingMethods>
#include <Eigen/SparseQR>

#include <limits>

namespace fcsolve {
namespace ipm {

struct ProblemDiagnostics {
  double contact_ratio = std::numeric_limits<double>::quiet_NaN();  ///< d nc / n (global only)
  Index rank_H = -1;           ///< estimated rank of H (global) or W (local); -1 not computed (m > kDiagnosticsDenseLimit)
  Index columns_H = 0;         ///< m
  double lambda_min_W = std::numeric_limits<double>::quiet_NaN();  ///< of (W + W^T) / 2
  double lambda_max_W = std::numeric_limits<double>::quiet_NaN();
  double cond_W = std::numeric_limits<double>::quiet_NaN();  ///< lambda_max / lambda_min (inf if <= 0)
  double asymmetry_W = 0;      ///< ||W - W^T||_F / ||W||_F
};

/// Largest m for which the spectrum of W (dense eigensolver) and the rank
/// of H or W (column-pivoted sparse QR) are computed. The QR's fill grows
/// fast on piles: measured (`fcsolve check`, docs/results.md, stop 64) 2.8 s
/// at 3003 columns, 87 s at 9018 and 6.9 minutes at 15 030; above the limit
/// d nc / n still bounds the rank deficiency from below (global).
inline constexpr Index kDiagnosticsDenseLimit = 3000;

namespace detail {

inline Index sparse_rank(const SparseMatrix& A) {
  // Column-pivoted QR of the taller orientation; Eigen's default threshold.
  SparseMatrix B = A.rows() >= A.cols() ? A : SparseMatrix(A.transpose());
  B.makeCompressed();
  Eigen::SparseQR<SparseMatrix, Eigen::COLAMDOrdering<int>> qr(B);
  return qr.info() == Eigen::Success ? Index(qr.rank()) : Index(-1);
}

/// The spectrum of (W + W^T) / 2 into d (and `eigenvalues`, if given).
inline void spectrum(const SparseMatrix& W, ProblemDiagnostics& d, Vector* eigenvalues = nullptr) {
  d.asymmetry_W = relative_asymmetry(W);
  if (W.rows() == 0 || W.rows() > kDiagnosticsDenseLimit) return;
  const DenseMatrix S = DenseMatrix(symmetric_part(W));
  Eigen::SelfAdjointEigenSolver<DenseMatrix> es(S, Eigen::EigenvaluesOnly);
  if (es.info() != Eigen::Success) return;
  d.lambda_min_W = es.eigenvalues().minCoeff();
  d.lambda_max_W = es.eigenvalues().maxCoeff();
  d.cond_W = d.lambda_min_W > 0 ? d.lambda_max_W / d.lambda_min_W
                                : std::numeric_limits<double>::infinity();
  if (eigenvalues) *eigenvalues = es.eigenvalues();
}

/// Rank of a symmetric matrix from its eigenvalues: those above the sparse
/// QR's default threshold, 20 (rows + cols) eps times the largest |lambda|.
inline Index spectral_rank(const Vector& eigenvalues) {
  const double largest = eigenvalues.size() ? eigenvalues.cwiseAbs().maxCoeff() : 0.0;
  const double threshold = 40.0 * double(eigenvalues.size()) * std::numeric_limits<double>::epsilon() * largest;
  return Index((eigenvalues.array().abs() > threshold).count());
}

}  // namespace detail

template <class Backend = DefaultBackend>
ProblemDiagnostics diagnose(const GlobalProblemView& p) {
  ProblemDiagnostics d;
  d.contact_ratio = double(p.d) * double(p.num_contacts()) / double(p.num_dofs());
  d.columns_H = p.size();
  if (p.size() <= kDiagnosticsDenseLimit) {
    d.rank_H = detail::sparse_rank(SparseMatrix(p.H));
    GlobalReduction<Backend> reduction(p);
    detail::spectrum(reduction.local().W, d);
  }
  return d;
}

/// A dense symmetric W (an elastic body's FC/II) takes its rank from the
/// eigenvalues its spectrum computes: its sparse QR fills completely and
/// runs without BLAS (7 of `check`'s 18 s on a FEM block of 2352 columns).
inline ProblemDiagnostics diagnose(const LocalProblemView& p) {
  ProblemDiagnostics d;
  d.columns_H = p.size();
  const SparseMatrix W(p.W);
  Vector eigenvalues;
  detail::spectrum(W, d, &eigenvalues);
  const bool dense_symmetric = fills_densely(W.nonZeros(), W.rows()) && d.asymmetry_W <= kSymmetryRoundoff;
  if (W.rows() <= kDiagnosticsDenseLimit)
    d.rank_H = dense_symmetric && eigenvalues.size() ? detail::spectral_rank(eigenvalues) : detail::sparse_rank(W);
  return d;
}

}  // namespace ipm
}  // namespace fcsolve
