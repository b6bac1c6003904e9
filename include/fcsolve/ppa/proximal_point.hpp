// The proximal point method on FC/II(W, q, mu) (Rockafellar 1976; Acary,
// Bremond & Huber 2018, sec. on the proximal point method, Siconos' PROX):
//   r_{k+1} solves FC/II(W + alpha_k I, q - alpha_k r_k, mu),
// i.e. the contact law with u + alpha_k (r - r_k) in place of u. The
// regularised W is positive definite on rank-deficient W (many contacts on
// few bodies), where plain Newton's Jacobian is singular. Each subproblem
// is solved by an inner FC/II solver (the Inner policy: semismooth Newton by
// default, NSGS as an alternative) warm-started from r_k.
//
// The outer loop (alpha rule, inner tolerance, failures, best iterate) is
// ProximalPointLoop's (proximal_point_loop.hpp), with alpha in units of
// mean |W_ii|. Success is declared only on the FCLIB error of r
// (problem/error.hpp) of the original problem. The inner solver's compute() runs once per outer
// iteration (its cached diagonal blocks, rho and scale depend on alpha and
// q). The subproblems share one pattern, so the Newton inner rereads the
// values only (newton_solver.hpp: no new Jacobian pattern, no new symbolic
// analysis); the inner iterations allocate nothing.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/newton/newton_solver.hpp>
#include <fcsolve/ppa/proximal_point_loop.hpp>
#include <fcsolve/ppa/proximal_problem.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/validate.hpp>
#include <fcsolve/storage/storage.hpp>

#include <initializer_list>
#include <optional>

namespace fcsolve {

template <class Cone, class Inner = Newton<AlartCurnierFunction, Cone, SparseStorage<Cone::dim>>>
class ProximalPoint : public ProximalPointLoop<ProximalPoint<Cone, Inner>, Inner> {
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");
  static_assert(Inner::d == Cone::dim, "the inner solver must be built for the same cone");
  using Base = ProximalPointLoop<ProximalPoint, Inner>;
  friend Base;
  using Base::info_, Base::inner_;

 public:
  using Base::d;
  explicit ProximalPoint(const typename Base::Settings& s = {}) : Base(s) {}

  /// Validates p and copies W into the regularised storage. The viewed data
  /// must outlive the solver.
  ProximalPoint& compute(const LocalProblemView& p) {
    Stopwatch clock;
    problem_.emplace(validated(p, d));
    error_.emplace(p);
    proximal_.compute(p);
    for (Vector* v : {&r_, &trial_, &u_, &best_}) v->resize(p.size());
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate if the solve fails);
  /// u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    fcsolve::check_solve_arguments("ProximalPoint", problem_.has_value(), r, size(), u, size(),
                                   "u");
    Stopwatch clock;
    r_ = r;
    double error = (*error_)(r_);
    best_ = r_;
    if (this->run(error, clock) != Status::Converged) r_ = best_;
    r = r_;
    u.noalias() = problem_->W * r_;
    u += problem_->q;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

 private:
  // ---- hooks of ProximalPointLoop
  double alpha_unit() const { return proximal_.diagonal_scale(); }
  double outer_scale() const { return error_->scale(); }
  Index num_contacts() const { return problem_->num_contacts(); }
  Index size() const { return problem_ ? problem_->size() : 0; }
  double pose_subproblem(double alpha) {
    proximal_.set_alpha(alpha);
    FCSOLVE_NO_MALLOC_BEGIN();
    proximal_.set_centre(r_);
    FCSOLVE_NO_MALLOC_END();
    const LocalProblemView& sub = proximal_.view();
    inner_.compute(sub);
    return error_scale(sub.q.norm());
  }
  const SolverInfo& solve_subproblem() {
    trial_ = r_;
    return inner_.solve(trial_, u_);
  }
  double trial_error() { return (*error_)(trial_); }
  void take_trial() { r_ = trial_; }
  void save_best() { best_ = r_; }

  std::optional<LocalProblemView> problem_;
  std::optional<LocalErrorEvaluator<Cone>> error_;
  ProximalProblem proximal_;
  Vector r_, trial_, u_, best_;
};

}  // namespace fcsolve
