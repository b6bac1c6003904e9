// Catalogue entries of the interior-point family: ipm-socqp, aclm-fp,
// aclm-newton, nipm. Global problems are solved natively (global form on
// M, H; with bilateral constraints by reduction), local ones on W.
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/nipm.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/solvers/dispatch.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace fcsolve {
namespace registry {

namespace detail {

/// Newton systems up to this size use dense factorisations.
inline constexpr Index kDenseKktMaxSize = 96;

enum class IpmKind { Socqp, AclmFixedPoint, AclmNewton, Nipm };

/// The settings struct of a kind: where its defaults come from.
inline ipm::IpmSettings default_settings(IpmKind kind) {
  switch (kind) {
    case IpmKind::Socqp: return ipm::IpmSettings();
    case IpmKind::Nipm: return ipm::NipmSettings();
    default: return ipm::AclmSettings();
  }
}

inline std::vector<SettingSpec> ipm_settings(IpmKind kind) {
  const ipm::IpmSettings d = default_settings(kind);
  std::vector<SettingSpec> v = {
      real_setting("step_fraction", d.step_fraction, "fraction to the cone boundary", 0.5, 0.999999),
      real_setting("sigma_max", d.sigma_max, "upper bound on Mehrotra's centring parameter", 1e-3, 1.0),
      integer_setting("refinement", d.refinement, "iterative-refinement steps per linear solve", 0, 20),
      real_setting("regularization", d.regularization,
                   "static regularisation of the Newton matrix (relative)", 0.0, 1e-2),
      real_setting("neighbourhood", d.neighbourhood,
                   "wide-neighbourhood parameter of the step (0: off)", 0.0, 0.5),
      boolean_setting("polish", d.polish, "finish with Newton steps on the natural map"),
      integer_setting("polish_iterations", d.polish_iterations, "Newton steps of the polish", 0, 100),
      real_setting("polish_below", d.polish_below,
                   "polish once the error is below this and slows down", 0.0, 1.0)};
  if (kind == IpmKind::AclmFixedPoint || kind == IpmKind::AclmNewton) {
    const ipm::AclmSettings a;
    v.push_back(integer_setting("max_outer", a.max_outer, "outer (s-update) iterations", 1, 100000));
    v.push_back(real_setting("inner_ratio", a.inner_ratio, "inner tolerance / outer error", 1e-6, 1.0));
  }
  if (kind == IpmKind::Nipm) {
    const ipm::NipmSettings n;
    v.push_back(boolean_setting("recover", n.recover, "resume / re-centre / ACLM when the NIPM stalls"));
    v.push_back(boolean_setting("recentre", n.recentre, "re-centring as a recovery step"));
    v.push_back(real_setting("soft_time", n.soft_time,
                             "soft time limit, s (0: none): past it the interior point goes on only while its rate "
                             "predicts tol within 10 iterations and half the time left to max_time",
                             0.0));
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

/// Runs the solver of `kind` on form Form from the request's warm start r0
/// (zero when absent); returns r and w (v or u). ipm-socqp solves the
/// associated law (s = 0), not the Coulomb problem: it claims convergence
/// only when the Coulomb (FCLIB) error of its point is within tol, so that
/// the registry's re-check never has to take a claim back.
template <class Form, class View>
SolverInfo run_ipm(IpmKind kind, const View& p, const SolveRequest& req, SolveOutcome& out) {
  out.r = initial_reactions(req, p.size());
  Vector& w = Form::is_global ? out.v : out.u;
  if constexpr (Form::is_global) w.setZero(p.num_dofs());
  else w.setZero(p.size());
  auto run = [&](auto& solver) {
    compute_within_time(solver, p);
    const SolverInfo& info = solver.solve(out.r, w);
    if constexpr (Form::is_global)  // the registry need not factorise M again
      out.reduced_q_norm = solver.form().free_velocity_norm();
    return info;
  };
  if (kind == IpmKind::Socqp) {
    ipm::SocqpIpm<Form> solver(ipm_settings_from<ipm::IpmSettings>(req));
    SolverInfo info = run(solver);
    info.message = "associated problem (s = 0) " + info.message;
    if (info.converged() && !(solver.coulomb_error() <= req.common.tol)) {
      info.status = Status::Stalled;
      info.message += "; the associated problem's solution has Coulomb (FCLIB) error " +
                      ipm::format_number(solver.coulomb_error()) + " > tol";
    }
    return info;
  }
  if (kind == IpmKind::Nipm) {
    auto s = ipm_settings_from<ipm::NipmSettings>(req);
    s.recover = req.settings.boolean("recover");
    s.soft_time = req.settings.real("soft_time");
    s.recentre = req.settings.boolean("recentre");
    ipm::NonsmoothIpm<Form> solver(s);
    return run(solver);
  }
  auto s = ipm_settings_from<ipm::AclmSettings>(req);
  s.variant = kind == IpmKind::AclmNewton ? ipm::AclmVariant::Newton : ipm::AclmVariant::FixedPoint;
  s.max_outer = int(req.settings.integer("max_outer"));
  s.inner_ratio = req.settings.real("inner_ratio");
  ipm::AclmSolver<Form> solver(s);
  return run(solver);
}

inline void require_friction(int d) {
  if (d != 2 && d != 3)
    throw UsageError("the interior-point solvers need friction cones (d = 2 or 3), got d = " +
                     std::to_string(d));
}

template <class T>
struct TypeTag {
  using type = T;
};

/// The catalogue's dispatch (solvers/dispatch.hpp) for the interior-point
/// forms: f(TypeTag<Form<Cone, Factorization>>{}) for the friction cones
/// (d = 2 or 3, require_friction()), `DenseFactorization` for small or
/// dense systems: the local form's symmetric K is positive definite
/// (Cholesky), the global form's quasi-definite (LDL^T).
template <template <class, class> class Form, class DenseFactorization, class F>
void dispatch_ipm_form(int d, bool dense, F&& f) {
  dispatch_cone_and_density(d, dense, [&](auto cone, auto is_dense) {
    using Cone = decltype(cone);
    if constexpr (Cone::dim > 1) {
      using Factorization = std::conditional_t<decltype(is_dense)::value, DenseFactorization,
                                               ipm::SparseKktFactorization<DefaultBackend>>;
      using FormType = Form<Cone, Factorization>;
      using View = typename FormType::View;
      static_assert(satisfies_solver_contract_v<ipm::SocqpIpm<FormType>, View> &&
                    satisfies_solver_contract_v<ipm::AclmSolver<FormType>, View> &&
                    satisfies_solver_contract_v<ipm::NonsmoothIpm<FormType>, View>);
      f(TypeTag<FormType>{});
    }
  });
}

inline LocalSolveFunction ipm_local(IpmKind kind) {
  return [kind](const LocalProblemView& p, const SolveRequest& req) {
    require_friction(p.d);
    SolveOutcome out;
    // K has W's pattern (and the diagonal blocks): dense where W is.
    const bool dense = p.size() <= kDenseKktMaxSize || ipm::fills_densely(p.W.nonZeros(), p.size());
    dispatch_ipm_form<ipm::LocalForm, ipm::DenseCholeskyKktFactorization>(p.d, dense, [&](auto form) {
      out.info = run_ipm<typename decltype(form)::type>(kind, p, req, out);
    });
    return out;
  };
}

inline GlobalSolveFunction ipm_global(IpmKind kind) {
  return [kind](const GlobalProblemView& p, const SolveRequest& req) {
    require_friction(p.d);
    SolveOutcome out;
    if (p.has_bilateral())  // the global form has no (G, b)
      return solve_bilateral_by_reduction(
          p, req, [kind](const LocalProblemView& reduced, const SolveRequest& within) {
            return ipm_local(kind)(reduced, within);
          });
    const bool dense = p.num_dofs() + p.size() <= kDenseKktMaxSize;
    dispatch_ipm_form<ipm::GlobalForm, ipm::DenseKktFactorization>(p.d, dense, [&](auto form) {
      out.info = run_ipm<typename decltype(form)::type>(kind, p, req, out);
    });
    return out;
  };
}

inline SolverEntry ipm_entry(std::string name, std::string summary, IpmKind kind) {
  SolverEntry e(std::move(name), "ipm", std::move(summary));
  e.settings = ipm_settings(kind);
  e.default_max_iter = default_settings(kind).max_iter;
  e.solve_local = ipm_local(kind);
  e.solve_global = ipm_global(kind);
  return e;
}

}  // namespace detail

inline void add_ipm_solvers(std::vector<SolverEntry>& v) {
  using detail::IpmKind;
  using detail::ipm_entry;
  v.push_back(ipm_entry("ipm-socqp",
                        "convex SOCQP IPM with s = 0 (associated friction law; NT scaling, Mehrotra)",
                        IpmKind::Socqp));
  v.push_back(ipm_entry("aclm-fp", "ACLM fixed point s <- ||u_T(s)|| over the convex IPM",
                        IpmKind::AclmFixedPoint));
  v.push_back(ipm_entry("aclm-newton",
                        "ACLM Newton on F(s) = s over the convex IPM (GMRES, implicit F')",
                        IpmKind::AclmNewton));
  v.push_back(ipm_entry("nipm", "nonsmooth IPM on FC/I with recovery (polish, re-centring, ACLM)",
                        IpmKind::Nipm));
}

}  // namespace registry
}  // namespace fcsolve
