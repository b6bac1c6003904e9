// Numerical check of the existence assumption of Acary & Cadoux 2013
// (reference talk, "Numerical validation of the key assumption"): if
//   x* = max { x : H^T v + w - a x in K* },  a = (N^1, ..., N^nc), N = (1, 0, 0),
// is positive, some v has H^T v + w in int K*, and FC/I has a solution
// (Slater's assumption; Acary, Cadoux, Lemarechal & Malick 2011, Thm 3.3).
//
// The SOC linear program is unbounded whenever the assumption holds and w
// has no part outside the range of H^T (the feasible set is then a cone: all
// the FCLIB files have w = 0), so the check solves its strongly convex
// regularisation, a convex SOCQP the global IPM handles directly:
//   min 1/2 (||v~||^2 + x^2) - x  s.t.  H~^T v~ + w - a x in K*,
// with H~ = H / h and v~ = h v (h the largest column norm of H, so that v~
// and x are commensurate). Its solution has x* > 0 iff the LP's optimum is
// positive; for w = 0, x* = 1 / (1 + c) with c = min { ||v~||^2 :
// H~^T v~ - a in K* }, so x* near 0 with the assumption true means a huge
// witness. The report gives x*, the verdict x* > threshold, and the witness
// size ||v|| of the v with H^T v + w - a x* in K* (w = 0: normalised to
// x = 1).
//
// For FC/II (only W, q): {H^T v + w} = {W r + q : r in R^m} when
// W = H^T M^-1 H and q = H^T M^-1 f + w (M SPD), so the same check runs with
// H^T replaced by W (as given) and w by q.
#pragma once

#include <fcsolve/ipm/socqp_ipm.hpp>

#include <cmath>

namespace fcsolve {
namespace ipm {

struct ExistenceReport {
  double x = 0;               ///< x* of the regularised program
  bool slater = false;        ///< x* > threshold: a solution of FC/I (or FC/II) exists
  double threshold = 0;       ///< the verdict's threshold on x*
  double witness_norm = 0;    ///< ||v|| of the witness (data units; w = 0: for x = 1)
  double solver_error = 0;    ///< natural-map error of the SOCQP solution
  SolverInfo info;            ///< of the interior-point solve
};

namespace detail {

/// Builds M~ = I, H~ = [H / h; -a^T], f~ = (0, 1), w~ = w and solves it.
template <int N, class Backend>
ExistenceReport solve_existence(const SparseMatrix& Ht_rows, const Vector& w,
                                const Eigen::Ref<const Vector>& mu, int d, double tol) {
  // Ht_rows: the n x m matrix whose transpose acts on v (H, or W^T).
  const Index n = Ht_rows.rows(), m = Ht_rows.cols(), nc = mu.size();
  double h = 0;
  for (Index j = 0; j < m; ++j) h = std::max(h, Ht_rows.col(j).norm());
  if (!(h > 0)) h = 1;
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(std::size_t(Ht_rows.nonZeros() + nc));
  for (Index j = 0; j < m; ++j)
    for (SparseMatrix::InnerIterator it(Ht_rows, j); it; ++it)
      t.emplace_back(int(it.row()), int(j), it.value() / h);
  for (Index a = 0; a < nc; ++a) t.emplace_back(int(n), int(a * d), -1.0);
  GlobalProblem g;
  g.d = d;
  g.H.resize(n + 1, m);
  g.H.setFromTriplets(t.begin(), t.end());
  g.H.makeCompressed();
  g.M.resize(n + 1, n + 1);
  g.M.setIdentity();
  g.M.makeCompressed();
  g.f = Vector::Zero(n + 1);
  g.f[n] = 1;
  g.w = w;
  g.mu = mu;
  IpmSettings s;
  s.tol = tol;
  s.max_iter = 100;
  GlobalSocqpIpm<N, SparseKktFactorization<Backend>> ipm(s);
  ipm.compute(g);
  Vector r, v;
  ExistenceReport rep;
  rep.info = ipm.solve(r, v);
  rep.solver_error = rep.info.error;
  rep.x = v[n];
  rep.threshold = 1e-8 * std::max(1.0, w.cwiseAbs().maxCoeff());
  rep.slater = rep.info.converged() && rep.x > rep.threshold;
  const double vnorm = v.head(n).norm() / h;
  const bool homogeneous = w.cwiseAbs().maxCoeff() == 0;
  rep.witness_norm = (homogeneous && rep.x > 0) ? vnorm / rep.x : vnorm;
  return rep;
}

}  // namespace detail

namespace detail {
/// Runs solve_existence for the problem's cone (d = 2 or 3).
template <class Backend, class View>
ExistenceReport check_existence_of(const View& p, const SparseMatrix& Ht_rows, const Vector& w,
                                   double tol) {
  validate(p);
  return dispatch_cone(p.d, [&](auto cone) -> ExistenceReport {
    constexpr int D = decltype(cone)::dim;
    if constexpr (D == 1)
      throw UsageError("the existence check needs friction cones (d = 2 or 3)");
    else
      return solve_existence<D, Backend>(Ht_rows, w, p.mu, p.d, tol);
  });
}
}  // namespace detail

/// Slater's assumption for FC/I: max x s.t. H^T v + w - a x in K*.
template <class Backend = DefaultBackend>
ExistenceReport check_existence(const GlobalProblemView& p, double tol = 1e-10) {
  return detail::check_existence_of<Backend>(p, SparseMatrix(p.H), Vector(p.w), tol);
}

/// The same for FC/II with H^T replaced by W: exists r with W r + q - a x in K*.
template <class Backend = DefaultBackend>
ExistenceReport check_existence(const LocalProblemView& p, double tol = 1e-10) {
  return detail::check_existence_of<Backend>(p, SparseMatrix(SparseMatrix(p.W).transpose()),
                                             Vector(p.q), tol);
}

}  // namespace ipm
}  // namespace fcsolve
