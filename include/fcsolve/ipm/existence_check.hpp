// Numerical check of the existence assumption of Acary & Cadoux 2013
// (Acary & Cadoux 2013; Acary 2025 (talk), "Numerical validation of the key assumption"; docs/references.md): if
//   x* = max { x : H^T v + w - a x in K* },  a = (N^1, ..., N^nc), N = (1, 0, 0),
// is positive, some v has H^T v + w in int K*, and FC/I has a solution
// (Slater's assumption; Acary, Cadoux, Lemarechal & Malick 2011, Thm 3.3).
//
// The SOC linear program is unbounded as soon as the assumption holds with
// w in the range of H^T (all the FCLIB files have w = 0), so the check
// solves the homogenised, strongly convex program (a convex SOCQP for the
// global IPM, s = 0):
//   min 1/2 (||v~||^2 + t^2 + x^2) - x
//   s.t.  H~^T v~ + t w~ - a x in K*,   (t - x, 0, 0) in K*   (i.e. t >= x),
// with H~ = H / h, w~ = w / omega (h the largest column norm of H, omega =
// ||w||inf), so that v~, t and x are commensurate. Dividing by t > 0 maps a
// point with x > 0 to a Slater point, and conversely, so x* > 0 iff the
// assumption holds; x* = 1 / (1 + c), c = min ||(v~, t)||^2 with margin 1,
// so x* near 0 with the assumption true means a huge witness. The verdict
// does not rest on a threshold on x*: the witness v = v~ / (h t') (t' =
// t / omega, the t of the data's units) is checked directly, and the
// assumption is reported to hold iff u = H^T v + w has the positive margin
//   min_a ( u_N^a - mu_a ||u_T^a|| ) > 1e-9 ||u||inf,
// i.e. u is strictly inside K* (a certificate, evaluated in floating point).
//
// For FC/II (only W, q): {H^T v + w} = {W r + q : r in R^m} when
// W = H^T M^-1 H and q = H^T M^-1 f + w (M SPD), so the same check runs with
// H^T replaced by W (as given) and w by q.
#pragma once

#include <fcsolve/ipm/socqp_ipm.hpp>

#include <cmath>
#include <limits>

namespace fcsolve {
namespace ipm {

struct ExistenceReport {
  double x = 0;               ///< x* of the homogenised program
  bool slater = false;        ///< the witness is strictly feasible: a solution exists
  Vector witness;             ///< v (global) or r (local) with H^T v + w (W r + q) in int K*
  double witness_norm = 0;    ///< ||witness||
  double margin = 0;          ///< min_a (u_N - mu ||u_T||) at the witness
  double solver_error = 0;    ///< natural-map error of the SOCQP solution
  SolverInfo info;            ///< of the interior-point solve
};

namespace detail {

/// Builds the homogenised program (header comment) and solves it. `Ht_rows`
/// is the n x m matrix whose transpose acts on v (H, or W^T).
template <class Cone, class Backend>
ExistenceReport solve_existence(const SparseMatrix& Ht_rows, const Vector& w,
                                const Eigen::Ref<const Vector>& mu, double tol) {
  constexpr int D = Cone::dim;
  const Index n = Ht_rows.rows(), m = Ht_rows.cols(), nc = mu.size();
  double h = 0;
  for (Index j = 0; j < m; ++j) h = std::max(h, Ht_rows.col(j).norm());
  if (!(h > 0)) h = 1;
  const double wmax = w.size() ? w.cwiseAbs().maxCoeff() : 0.0;
  const double omega = wmax > 0 ? wmax : 1.0;
  // Unknowns (v~, t, x): rows 0..n-1, n, n+1; contacts 0..nc-1 and the extra
  // contact nc carrying t - x >= 0.
  const Index tr = n, xr = n + 1;
  std::vector<Eigen::Triplet<double, int>> t;
  t.reserve(std::size_t(Ht_rows.nonZeros() + m + nc + 2));
  for (Index j = 0; j < m; ++j) {
    for (SparseMatrix::InnerIterator it(Ht_rows, j); it; ++it)
      t.emplace_back(int(it.row()), int(j), it.value() / h);
    if (w[j] != 0) t.emplace_back(int(tr), int(j), w[j] / omega);
  }
  for (Index a = 0; a < nc; ++a) t.emplace_back(int(xr), int(a * D), -1.0);
  t.emplace_back(int(tr), int(nc * D), 1.0);
  t.emplace_back(int(xr), int(nc * D), -1.0);
  GlobalProblem g;
  g.d = D;
  g.H.resize(n + 2, m + D);
  g.H.setFromTriplets(t.begin(), t.end());
  g.H.makeCompressed();
  g.M.resize(n + 2, n + 2);
  g.M.setIdentity();
  g.M.makeCompressed();
  g.f = Vector::Zero(n + 2);
  g.f[xr] = 1;
  g.w = Vector::Zero(m + D);
  g.mu.resize(nc + 1);
  g.mu.head(nc) = mu;
  g.mu[nc] = 1;
  IpmSettings s;
  s.tol = tol;
  s.max_iter = 100;
  // No natural-map polish: the verdict rests on the witness' certificate,
  // not on the last digits of x*. Measured (docs/results.md, stop 64): the
  // same verdicts, x* and margins on 94 of the 96 problems checked (the
  // other two not established either way), and a pile of 5000 in 2.6 s
  // instead of 51 s, spent in the polish's UMFPACK factorisations.
  s.polish = false;
  GlobalSocqpIpm<Cone, SparseKktFactorization<Backend>> ipm(s);
  ipm.compute(g);
  Vector r = Vector::Zero(g.size()), v(g.num_dofs());
  ExistenceReport rep;
  rep.info = ipm.solve(r, v);
  rep.solver_error = rep.info.error;
  rep.x = v[xr];
  const double tau = v[tr] / omega;  // the t of the data's units
  rep.witness = tau > 0 ? Vector(v.head(n) / (h * tau)) : Vector(Vector::Zero(n));
  rep.witness_norm = rep.witness.norm();
  // Certificate: u = H^T v + w strictly inside K*.
  const Vector u = Ht_rows.transpose() * rep.witness + w;
  rep.margin = std::numeric_limits<double>::infinity();
  for (Index a = 0; a < nc; ++a)
    rep.margin = std::min(rep.margin, u[a * D] - mu[a] * u.template segment<D - 1>(a * D + 1).norm());
  const double scale = u.size() ? u.cwiseAbs().maxCoeff() : 0.0;
  rep.slater = tau > 0 && rep.margin > 1e-9 * scale;
  return rep;
}

/// Runs solve_existence for the problem's cone (d = 2 or 3).
template <class Backend, class View>
ExistenceReport check_existence_of(const View& p, const SparseMatrix& Ht_rows, const Vector& w,
                                   double tol) {
  validate(p);
  return dispatch_cone(p.d, [&](auto cone) -> ExistenceReport {
    using Cone = decltype(cone);
    if constexpr (Cone::dim == 1)
      throw UsageError("the existence check needs friction cones (d = 2 or 3)");
    else
      return solve_existence<Cone, Backend>(Ht_rows, w, p.mu, tol);
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
