// Catalogue entries of the interior-point family: ipm-socqp, aclm-fp,
// aclm-newton, nipm. Global problems are solved natively (global form on
// M, H; with bilateral constraints by reduction), local ones on W.
#pragma once

#include <fcsolve/core/error.hpp>
#include <fcsolve/nipm.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/solvers/registry.hpp>

namespace fcsolve {
namespace registry {

namespace detail {

/// Newton systems up to this size use dense factorisations.
inline constexpr Index kDenseKktMaxSize = 96;

enum class IpmKind { Socqp, AclmFixedPoint, AclmNewton, Nipm };

inline std::vector<SettingSpec> ipm_settings(IpmKind kind) {
  std::vector<SettingSpec> v = {
      real_setting("step_fraction", 0.99, "fraction to the cone boundary", 0.5, 0.999999),
      real_setting("sigma_max", kind == IpmKind::Nipm ? 0.5 : 1.0,
                   "upper bound on Mehrotra's centring parameter", 1e-3, 1.0),
      integer_setting("refinement", 2, "iterative-refinement steps per linear solve", 0, 20),
      real_setting("regularization", 0.0, "static regularisation of the Newton matrix (relative)", 0.0, 1e-2),
      real_setting("neighbourhood", 0.0, "wide-neighbourhood parameter of the step (0: off)", 0.0, 0.5),
      boolean_setting("polish", true, "finish with Newton steps on the natural map"),
      integer_setting("polish_iterations", 10, "Newton steps of the polish", 0, 100),
      real_setting("polish_below", 1e-5, "polish once the error is below this and slows down", 0.0, 1.0)};
  if (kind == IpmKind::AclmFixedPoint || kind == IpmKind::AclmNewton) {
    v.push_back(integer_setting("max_outer", 60, "outer (s-update) iterations", 1, 100000));
    v.push_back(real_setting("inner_ratio", 0.1, "inner tolerance / outer error", 1e-6, 1.0));
  }
  if (kind == IpmKind::Nipm) {
    v.push_back(boolean_setting("recover", true, "resume / re-centre / ACLM when the NIPM stalls"));
    v.push_back(boolean_setting("recentre", true, "re-centring as a recovery step"));
  }
  return v;
}

template <class S>
S ipm_settings_from(const SolveRequest& req) {
  S s;
  static_cast<SolverSettings&>(s) = req.common;
  const SettingValues& k = req.settings;
  s.step_fraction = k.real("step_fraction");
  s.sigma_max = k.real("sigma_max");
  s.refinement = int(k.integer("refinement"));
  s.regularization = k.real("regularization");
  s.neighbourhood = k.real("neighbourhood");
  s.polish = k.boolean("polish");
  s.polish_iterations = int(k.integer("polish_iterations"));
  s.polish_below = k.real("polish_below");
  return s;
}

/// ACLM warm start: s = ||u_T|| of the given r (and v).
template <int N, class View>
Vector initial_speeds(const View& p, const SolveRequest& req) {
  Vector u;
  if constexpr (std::is_same_v<View, GlobalProblemView>) {
    if (req.v0.size() == 0) return Vector();
    u = p.H.transpose() * req.v0 + p.w;
  } else {
    if (req.r0.size() == 0) return Vector();
    u = p.W * req.r0 + p.q;
  }
  Vector s(p.num_contacts());
  for (Index a = 0; a < s.size(); ++a) s[a] = u.template segment<N - 1>(a * N + 1).norm();
  return s;
}

/// Runs the solver of `kind` on form Form; returns r and w (v or u).
template <class Form, class View>
SolverInfo run_ipm(IpmKind kind, const View& p, const SolveRequest& req, Vector& r, Vector& w) {
  constexpr int N = Form::dim;
  if (kind == IpmKind::Socqp) {
    ipm::SocqpIpm<Form> solver(ipm_settings_from<ipm::IpmSettings>(req));
    solver.compute(p);
    SolverInfo info = solver.solve(r, w);
    // The registry judges the Coulomb (FCLIB) error: say what was solved.
    info.message = "associated problem (s = 0) " + info.message;
    return info;
  }
  if (kind == IpmKind::Nipm) {
    auto s = ipm_settings_from<ipm::NipmSettings>(req);
    s.recover = req.settings.boolean("recover");
    s.recentre = req.settings.boolean("recentre");
    ipm::NonsmoothIpm<Form> solver(s);
    solver.compute(p);
    return solver.solve(r, w);
  }
  auto s = ipm_settings_from<ipm::AclmSettings>(req);
  s.variant = kind == IpmKind::AclmNewton ? ipm::AclmVariant::Newton : ipm::AclmVariant::FixedPoint;
  s.max_outer = int(req.settings.integer("max_outer"));
  s.inner_ratio = req.settings.real("inner_ratio");
  ipm::AclmSolver<Form> solver(s);
  solver.compute(p);
  const Vector s0 = initial_speeds<N>(p, req);
  if (s0.size()) solver.set_initial_s(s0);
  return solver.solve(r, w);
}

inline void require_friction(int d) {
  if (d != 2 && d != 3)
    throw UsageError("the interior-point solvers need friction cones (d = 2 or 3), got d = " +
                     std::to_string(d));
}

/// An interior point starts from the centre of the cones, not from a given
/// point: a warm start that already meets tol is returned as it is (no
/// iteration), so that restarting from a solution costs one error evaluation.
inline bool accept_warm_start(const LocalProblemView& p, const SolveRequest& req, SolveOutcome& out) {
  if (req.r0.size() != p.size()) return false;
  const Vector u = p.W * req.r0 + p.q;
  const double error = local_error_report(p, req.r0, u).error;
  if (!(error <= req.common.tol)) return false;
  out.r = req.r0;
  out.u = u;
  out.info.status = Status::Converged;
  out.info.error = error;
  out.info.message = "the warm start meets tol";
  return true;
}

inline bool accept_warm_start(const GlobalProblemView& p, const SolveRequest& req, SolveOutcome& out) {
  if (req.r0.size() != p.size() || req.v0.size() != p.num_dofs() || p.has_bilateral()) return false;
  const double q_norm = GlobalReduction<DefaultBackend>(p, /*form_W=*/false).free_velocity_norm();
  const double error = global_error_report(p, q_norm, req.r0, req.v0).error;
  if (!(error <= req.common.tol)) return false;
  out.r = req.r0;
  out.v = req.v0;
  out.info.status = Status::Converged;
  out.info.error = error;
  out.info.message = "the warm start meets tol";
  return true;
}

/// ipm-socqp solves the associated law (s = 0): its own convergence is not
/// the Coulomb problem's. Claim it only when the Coulomb (FCLIB) error of
/// the point is within tol, so that the registry's re-check never has to
/// take a claim back.
template <class View>
void judge_associated_solution(const View& p, const SolveRequest& req, SolveOutcome& out) {
  if (!out.info.converged()) return;
  double error;
  if constexpr (std::is_same_v<View, LocalProblemView>) {
    error = local_error(p, out.r);
  } else {
    const double q_norm = GlobalReduction<DefaultBackend>(p, /*form_W=*/false).free_velocity_norm();
    error = global_error_report(p, q_norm, out.r, out.v).error;
  }
  if (error <= req.common.tol) return;
  out.info.status = Status::Stalled;
  out.info.message += "; the associated problem's solution has Coulomb (FCLIB) error " +
                      ipm::format_number(error) + " > tol";
}

inline LocalSolveFunction ipm_local(IpmKind kind) {
  return [kind](const LocalProblemView& p, const SolveRequest& req) {
    require_friction(p.d);
    SolveOutcome out;
    if (accept_warm_start(p, req, out)) return out;
    const bool dense = p.size() <= kDenseKktMaxSize;
    auto go = [&](auto dim) {
      constexpr int N = decltype(dim)::value;
      if (dense)
        out.info = run_ipm<ipm::LocalForm<N, ipm::DenseKktFactorization>>(kind, p, req, out.r, out.u);
      else
        out.info = run_ipm<ipm::LocalForm<N, ipm::SparseKktFactorization<DefaultBackend>>>(
            kind, p, req, out.r, out.u);
    };
    if (p.d == 3) go(std::integral_constant<int, 3>());
    else go(std::integral_constant<int, 2>());
    if (kind == IpmKind::Socqp) judge_associated_solution(p, req, out);
    return out;
  };
}

inline GlobalSolveFunction ipm_global(IpmKind kind) {
  return [kind](const GlobalProblemView& p, const SolveRequest& req) {
    require_friction(p.d);
    SolveOutcome out;
    if (accept_warm_start(p, req, out)) return out;
    if (p.has_bilateral()) {  // the global form has no (G, b): reduce
      GlobalReduction<DefaultBackend> reduction(p);
      out = ipm_local(kind)(LocalProblemView(reduction.local()), req);
      out.v = reduction.velocity(out.r);
      out.lambda = reduction.multipliers(out.r);
      out.info.message = "solved on the reduced problem (bilateral constraints); " + out.info.message;
      return out;
    }
    const bool dense = p.num_dofs() + p.size() <= kDenseKktMaxSize;
    auto go = [&](auto dim) {
      constexpr int N = decltype(dim)::value;
      if (dense)
        out.info = run_ipm<ipm::GlobalForm<N, ipm::DenseKktFactorization>>(kind, p, req, out.r, out.v);
      else
        out.info = run_ipm<ipm::GlobalForm<N, ipm::SparseKktFactorization<DefaultBackend>>>(
            kind, p, req, out.r, out.v);
    };
    if (p.d == 3) go(std::integral_constant<int, 3>());
    else go(std::integral_constant<int, 2>());
    if (kind == IpmKind::Socqp) judge_associated_solution(p, req, out);
    return out;
  };
}

}  // namespace detail

inline void add_ipm_solvers(std::vector<SolverEntry>& v) {
  using detail::IpmKind;
  v.push_back({"ipm-socqp", "ipm",
               "convex SOCQP IPM with s = 0 (associated friction law; NT scaling, Mehrotra)",
               detail::ipm_settings(IpmKind::Socqp), false, 100, detail::ipm_local(IpmKind::Socqp),
               detail::ipm_global(IpmKind::Socqp)});
  v.push_back({"aclm-fp", "ipm", "ACLM fixed point s <- ||u_T(s)|| over the convex IPM",
               detail::ipm_settings(IpmKind::AclmFixedPoint), false, 400,
               detail::ipm_local(IpmKind::AclmFixedPoint), detail::ipm_global(IpmKind::AclmFixedPoint)});
  v.push_back({"aclm-newton", "ipm", "ACLM Newton on F(s) = s over the convex IPM (GMRES, implicit F')",
               detail::ipm_settings(IpmKind::AclmNewton), false, 400,
               detail::ipm_local(IpmKind::AclmNewton), detail::ipm_global(IpmKind::AclmNewton)});
  v.push_back({"nipm", "ipm", "nonsmooth IPM on FC/I with recovery (polish, re-centring, ACLM)",
               detail::ipm_settings(IpmKind::Nipm), false, 200, detail::ipm_local(IpmKind::Nipm),
               detail::ipm_global(IpmKind::Nipm)});
}

}  // namespace registry
}  // namespace fcsolve
