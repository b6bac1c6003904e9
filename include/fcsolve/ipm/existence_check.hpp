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
// The certificate is evaluated at every iterate of the program, which stops
// at the first certified one with x > 0 (stop_when_certified): the verdict
// is then proven and x is that iterate's, not the optimum. It runs to the
// optimum where no witness is certified on the way, or where the caller
// asks for x* (ExistenceStop::AtOptimum).
//
// For FC/II (only W, q): {H^T v + w} = {W r + q : r in R^m} when
// W = H^T M^-1 H and q = H^T M^-1 f + w (M SPD), so the same check runs with
// H^T replaced by any matrix of W's range (W itself, or a factor of W:
// below) and w by q.
//
// A dense W (an elastic body's FC/II) makes the global form's KKT matrix
// hold W twice, and CHOLMOD's simplicial LDL^T factorises it without BLAS
// (a FEM block's FC/II of 2352 columns: 216 s). There the program
// is solved in its reduced form instead (solve_existence_dense): with any L
// such that W = L L^T (never formed) in the place of H^T, range(L) =
// range(W), and the FC/II reduction of the homogenised program,
//   W' = H'^T H' = [W / h^2 0; 0 0] + c_t c_t^T + c_x c_x^T,   q' = c_x,
//   c_t = (w~, e_N of the extra contact),  c_x = (-a, -e_N of the extra contact)
// (the columns of H'^T acting on t and x; h^2 = max_j W_jj, L's largest row
// norm squared), needs W only; v = H' r' + f gives t = c_t . r',
// x = 1 + c_x . r', and the witness r = r'_m / (h^2 t') has
// W r = L v~ / (h t'). Its K = W's + P^-1 T^2 is positive definite: dense
// Cholesky (DenseCholeskyKktFactorization).
//
// The metric matters on a sparse W too. With H^T = W the program minimises
// ||r||^2, the reduced form r^T W r (FC/I's ||v||^2); where W is
// ill-conditioned (heavy bodies on light ones, mass ratio 1e4; box stacks)
// the first one's x* falls below the interior point's accuracy (x* ~ -1e-11,
// no witness) while FC/I's form is certified. A sparse W therefore goes to
// the global form with H^T = L~, L~ L~^T = W_s + eps I (W_s = (W + W^T) / 2,
// sparse Cholesky with AMD ordering, eps = 1e-12 max_j W_jj, raised 100x
// while the factorisation fails, up to 1e-6): its metric is FC/I's, it
// keeps W's sparsity (nnz(L) was 0.5 to 4.3 nnz(W) on the held-out scenes)
// and range(L~) = range(W) up to eps. The witness is r = (W_s + eps I)^-1
// L~ v, v the program's witness, and the certificate is u = W r + q with W as
// given, so eps costs no rigour. Measured (docs/results.md, stop 66): the
// FC/II verdict now equals the FC/I form's on all 118 held-out pairs (9
// more certified), and piles of 8000 to 12 000 contacts that took over 60 s
// are checked in 11 to 34 s.
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/ipm/local_form.hpp>
#include <fcsolve/ipm/socqp_ipm.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <Eigen/SparseCholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fcsolve {
namespace ipm {

struct ExistenceReport {
  double x = 0;               ///< x* of the homogenised program
  bool slater = false;        ///< the witness is strictly feasible: a solution exists
  Vector witness;             ///< v (global) or r (local) with H^T v + w (W r + q) in int K*
  double witness_norm = 0;    ///< ||witness||
  bool witness_found = false; ///< t > 0 at the program's solution: a witness to certify
  double margin = 0;          ///< min_a (u_N - mu ||u_T||) at the witness
  double solver_error = 0;    ///< natural-map error of the SOCQP solution
  SolverInfo info;            ///< of the interior-point solve
  /// The program: "global-form" (FC/I), and for FC/II "cholesky-form" (sparse
  /// W), "reduced-form" (dense W) or "w-form" (H^T = W, where the Cholesky
  /// factorisation failed).
  const char* program = "global-form";
  /// The program stopped at its first iterate with a certified witness
  /// (stop_when_certified): x is that iterate's, not the optimum.
  bool stopped_certified = false;
};

/// Where the existence program stops: at its first iterate whose witness is
/// certified (the verdict proven, x that iterate's), or at its optimum x*
/// (the talk's validation statistic; the verdict then rests on the
/// optimum's witness alone, as it did before the early stop).
enum class ExistenceStop { AtCertifiedWitness, AtOptimum };

/// The program's status as reported (`check_status`): "certified" where it
/// stopped at a certified witness, else its SolverInfo status.
inline std::string check_status(const ExistenceReport& rep) {
  return rep.stopped_certified ? std::string("certified") : to_string(rep.info.status);
}

namespace detail {

/// The certificate: u = H^T v + w (or W r + q) at the witness strictly
/// inside K*, with margin min_a (u_N - mu ||u_T||) > 1e-9 ||u||inf.
template <int D>
void certify(ExistenceReport& rep, const Vector& u, const Eigen::Ref<const Vector>& mu, bool witness_found) {
  rep.witness_found = witness_found;
  rep.witness_norm = rep.witness.norm();
  rep.margin = std::numeric_limits<double>::infinity();
  for (Index a = 0; a < mu.size(); ++a)
    rep.margin = std::min(rep.margin, u[a * D] - mu[a] * u.template segment<D - 1>(a * D + 1).norm());
  const double scale = u.size() ? u.cwiseAbs().maxCoeff() : 0.0;
  rep.slater = witness_found && rep.margin > 1e-9 * scale;
}

/// The program's tolerance and the check's wall-clock limit, counted from
/// check_existence's start (the factorisations before the interior point
/// count too; the time is honoured between its iterations).
struct ExistenceBudget {
  explicit ExistenceBudget(double tol = 1e-10, double max_time = std::numeric_limits<double>::infinity(),
                           ExistenceStop stop = ExistenceStop::AtCertifiedWitness)
      : tol(tol), max_time(max_time), stop(stop) {
    if (!(max_time > 0)) throw UsageError("the existence check's max_time must be positive (seconds; inf: no limit)");
  }
  double tol;
  double max_time;
  ExistenceStop stop;
  Stopwatch clock;

  IpmSettings settings() const {
    IpmSettings s;
    s.tol = tol;
    s.max_iter = 100;
    s.max_time = std::max(0.0, max_time - clock.seconds());
    // No natural-map polish: the verdict rests on the witness' certificate,
    // not on the last digits of x*. Measured (docs/results.md, stop 64): the
    // same verdicts, x* and margins on 94 of the 96 problems checked (the
    // other two not established either way), and a pile of 5000 in 2.6 s
    // instead of 51 s, spent in the polish's UMFPACK factorisations.
    s.polish = false;
    return s;
  }
};

/// Ends the program at the first iterate whose witness is certified: the
/// verdict rests on the certificate, not on x*, and along the path the
/// witnesses become certified well before the optimum (a pile of 5000
/// contacts with penetration correction, FC/II: from the 12th of 22
/// iterations; docs/results.md, stop 68). `evaluate(rep, r, w)` fills a
/// report (x, witness, certificate) from the program's point (r, w).
/// After the solve, `early` holds the certified report if the program
/// stopped there.
template <class Ipm, class Evaluate>
void stop_when_certified(Ipm& ipm, ExistenceReport& early, const Evaluate& evaluate) {
  ipm.settings().callback = [&ipm, &early, &evaluate](const IterationInfo&) {
    Vector r, w;
    ipm.current_point(r, w);
    ExistenceReport candidate;
    evaluate(candidate, r, w);
    if (!candidate.slater || !(candidate.x > 0)) return false;  // x* > 0 iff a solution exists
    early = std::move(candidate);
    early.stopped_certified = true;
    return true;
  };
}

/// Solves the program (with stop_when_certified unless the budget asks
/// for the optimum) and returns the report of the certified iterate, or of the
/// returned point (r, w).
template <class Ipm, class Evaluate>
ExistenceReport run_program(Ipm& ipm, Vector& r, Vector& w, const Evaluate& evaluate,
                            const ExistenceBudget& budget) {
  ExistenceReport early;
  if (budget.stop == ExistenceStop::AtCertifiedWitness) stop_when_certified(ipm, early, evaluate);
  const SolverInfo info = ipm.solve(r, w);
  ExistenceReport rep;
  if (early.stopped_certified) rep = std::move(early);
  else evaluate(rep, r, w);
  rep.info = info;
  rep.solver_error = info.error;
  return rep;
}

/// The certificate of the program's witness v (data units): H^T v + w.
struct CertifyAgainstH {
  const SparseMatrix& Ht_rows;
  const Vector& w;
  template <int D>
  void apply(ExistenceReport& rep, Vector v, const Eigen::Ref<const Vector>& mu, bool found) const {
    rep.witness = std::move(v);
    certify<D>(rep, Vector(Ht_rows.transpose() * rep.witness + w), mu, found);
  }
};

/// Builds the homogenised program (header comment) and solves it. `Ht_rows`
/// is the n x m matrix whose transpose acts on v (H, or W^T). `certifier`
/// maps the program's witness v to the report's witness and certifies it
/// (apply<D>(rep, v, mu, found)): against H^T v + w, or for the FC/II
/// Cholesky form against W r + q.
template <class Cone, class Backend, class Certifier>
ExistenceReport solve_existence(const SparseMatrix& Ht_rows, const Vector& w, const Eigen::Ref<const Vector>& mu,
                                const ExistenceBudget& budget, const Certifier& certifier) {
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
  GlobalSocqpIpm<Cone, SparseKktFactorization<Backend>> ipm(budget.settings());
  ipm.compute(g);
  Vector r = Vector::Zero(g.size()), v(g.num_dofs());
  const auto evaluate = [&](ExistenceReport& rep, const Vector&, const Vector& point) {
    rep.x = point[xr];
    const double tau = point[tr] / omega;  // the t of the data's units
    certifier.template apply<D>(rep, tau > 0 ? Vector(point.head(n) / (h * tau)) : Vector(Vector::Zero(n)), mu,
                                tau > 0);
  };
  return run_program(ipm, r, v, evaluate, budget);
}

/// The same, certified against H^T v + w (FC/I, and FC/II's w-form).
template <class Cone, class Backend>
ExistenceReport solve_existence(const SparseMatrix& Ht_rows, const Vector& w, const Eigen::Ref<const Vector>& mu,
                                const ExistenceBudget& budget) {
  return solve_existence<Cone, Backend>(Ht_rows, w, mu, budget, CertifyAgainstH{Ht_rows, w});
}

/// The FC/II check on the program's reduced form (header comment), for a
/// dense W: no factor of W is formed, W' is W / h^2 plus two rank-one terms.
template <class Cone>
ExistenceReport solve_existence_dense(const SparseMatrix& W, const Vector& q, const Eigen::Ref<const Vector>& mu,
                                      const ExistenceBudget& budget) {
  constexpr int D = Cone::dim;
  const Index m = W.cols(), nc = mu.size(), mm = m + D;
  const double wmax = W.size() ? W.diagonal().maxCoeff() : 0.0;
  const double h2 = wmax > 0 ? wmax : 1.0;
  const double qmax = q.size() ? q.cwiseAbs().maxCoeff() : 0.0;
  const double omega = qmax > 0 ? qmax : 1.0;
  Vector ct = Vector::Zero(mm), cx = Vector::Zero(mm);
  ct.head(m) = q / omega;
  ct[m] = 1;
  for (Index a = 0; a < nc; ++a) cx[a * D] = -1;
  cx[m] = -1;
  DenseMatrix Wr = DenseMatrix::Zero(mm, mm);
  Wr.topLeftCorner(m, m) = W.toDense() / h2;
  Wr.noalias() += ct * ct.transpose();
  Wr.noalias() += cx * cx.transpose();
  LocalProblem reduced;
  reduced.d = D;
  reduced.W = Wr.sparseView();
  reduced.W.makeCompressed();
  Wr.resize(0, 0);
  reduced.q = cx;
  reduced.mu.resize(nc + 1);
  reduced.mu.head(nc) = mu;
  reduced.mu[nc] = 1;
  LocalSocqpIpm<Cone, DenseCholeskyKktFactorization> ipm(budget.settings());
  ipm.compute(reduced);
  Vector r = Vector::Zero(mm), u(mm);
  const auto evaluate = [&](ExistenceReport& rep, const Vector& point, const Vector&) {
    rep.x = 1 + cx.dot(point);
    const double tau = ct.dot(point) / omega;  // t of the data's units
    rep.witness = tau > 0 ? Vector(point.head(m) / (h2 * tau)) : Vector(Vector::Zero(m));
    certify<D>(rep, Vector(W * rep.witness + q), mu, tau > 0);
  };
  ExistenceReport rep = run_program(ipm, r, u, evaluate, budget);
  rep.program = "reduced-form";
  return rep;
}

/// The Cholesky form's certificate: the program's witness v gives r =
/// (W_s + eps I)^-1 L~ v, certified as W r + q with W and q as given.
template <class Llt>
struct CertifyAgainstW {
  const Llt& llt;
  const SparseMatrix& Lt;
  const SparseMatrix& W;
  const Vector& q;
  template <int D>
  void apply(ExistenceReport& rep, const Vector& v, const Eigen::Ref<const Vector>& mu, bool found) const {
    rep.witness = found ? Vector(llt.solve(Vector(Lt * v))) : Vector(Vector::Zero(W.cols()));
    certify<D>(rep, Vector(W * rep.witness + q), mu, found);
  }
};

/// The FC/II check on a sparse W: the global form with H^T = L~ (header
/// comment); with H^T = W where no eps up to 1e-6 lets the Cholesky
/// factorisation succeed.
template <class Cone, class Backend>
ExistenceReport solve_existence_factored(const SparseMatrix& W, const Vector& q, const Eigen::Ref<const Vector>& mu,
                                         const ExistenceBudget& budget) {
  const Index m = W.cols();
  const SparseMatrix Ws = symmetric_part(W);
  const double dmax = m ? Ws.diagonal().maxCoeff() : 0.0;
  SparseMatrix identity(m, m);
  identity.setIdentity();
  Eigen::SimplicialLLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>> llt;
  for (double rel = 1e-12; rel <= 1e-6; rel *= 100) {
    llt.compute(Ws + (rel * (dmax > 0 ? dmax : 1.0)) * identity);
    if (llt.info() == Eigen::Success) break;
  }
  if (llt.info() != Eigen::Success) {
    ExistenceReport rep = solve_existence<Cone, Backend>(SparseMatrix(W.transpose()), q, mu, budget);
    rep.program = "w-form";
    return rep;
  }
  // P (W_s + eps I) P^T = L L^T, so W_s + eps I = L~ L~^T with L~ = P^T L.
  const SparseMatrix Lt = llt.permutationPinv() * SparseMatrix(llt.matrixL());
  ExistenceReport rep =
      solve_existence<Cone, Backend>(SparseMatrix(Lt.transpose()), q, mu, budget, CertifyAgainstW<decltype(llt)>{llt, Lt, W, q});
  rep.program = "cholesky-form";
  return rep;
}

/// Runs `solve(cone)` for the problem's cone (d = 2 or 3).
template <class View, class Solve>
ExistenceReport with_friction_cone(const View& p, Solve&& solve) {
  validate(p);
  return dispatch_cone(p.d, [&](auto cone) -> ExistenceReport {
    using Cone = decltype(cone);
    if constexpr (Cone::dim == 1)
      throw UsageError("the existence check needs friction cones (d = 2 or 3)");
    else
      return solve(cone);
  });
}

}  // namespace detail

/// Slater's assumption for FC/I: max x s.t. H^T v + w - a x in K*.
template <class Backend = DefaultBackend>
ExistenceReport check_existence(const GlobalProblemView& p, double tol = 1e-10,
                                double max_time = std::numeric_limits<double>::infinity(),
                                ExistenceStop stop = ExistenceStop::AtCertifiedWitness) {
  const detail::ExistenceBudget budget(tol, max_time, stop);
  return detail::with_friction_cone(p, [&](auto cone) {
    return detail::solve_existence<decltype(cone), Backend>(SparseMatrix(p.H), Vector(p.w), p.mu, budget);
  });
}

/// The same for FC/II: exists r with W r + q - a x in K*. A W of fill
/// kDenseKktFill or more goes to the reduced form, a sparse one to the
/// Cholesky form (header).
template <class Backend = DefaultBackend>
ExistenceReport check_existence(const LocalProblemView& p, double tol = 1e-10,
                                double max_time = std::numeric_limits<double>::infinity(),
                                ExistenceStop stop = ExistenceStop::AtCertifiedWitness) {
  const detail::ExistenceBudget budget(tol, max_time, stop);
  return detail::with_friction_cone(p, [&](auto cone) {
    using Cone = decltype(cone);
    const SparseMatrix W(p.W);
    if (fills_densely(W.nonZeros(), p.size())) return detail::solve_existence_dense<Cone>(W, Vector(p.q), p.mu, budget);
    return detail::solve_existence_factored<Cone, Backend>(W, Vector(p.q), p.mu, budget);
  });
}

}  // namespace ipm
}  // namespace fcsolve
