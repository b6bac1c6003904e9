// Semismooth Newton on the reduced problem FC/II(W, q, mu) (Alart & Curnier
// 1991; Acary, Bremond & Huber 2018, [NSN-*]; Qi & Sun 1993 for the
// semismooth Newton method):
//   G(r) = [ G^a(r^a, u^a) ]_a = 0,   u = W r + q,
//   J = A W + B  in d x d blocks (A, B block diagonal from the formulation),
//   (J + delta I) d = -G,   r <- r + t d   (t: line search on psi = 1/2 ||G||^2)
// Formulation<Cone> is a one-contact function (formulation/*.hpp): G^a and
// an element (A^a, B^a) of its generalised Jacobian. delta is the
// Levenberg-Marquardt-like shift of newton_step.hpp (rank-deficient W).
// With settings.hybrid, a stalled Newton hands over to the NSGS sweep
// (nsgs/nsgs_solver.hpp) with a few local Alart-Curnier steps per contact
// (local/alart_curnier_backtracking.hpp) and resumes once the error has dropped.
// Convergence is judged by the FCLIB error of core/error.hpp, never by ||G||.
#pragma once

#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/local/alart_curnier_backtracking.hpp>
#include <fcsolve/newton/contact_newton.hpp>
#include <fcsolve/newton/linear_solvers.hpp>
#include <fcsolve/newton/reduced_jacobian.hpp>
#include <fcsolve/nsgs/nsgs_solver.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/validate.hpp>
#include <fcsolve/storage/storage.hpp>

#include <optional>
#include <string>

namespace fcsolve {

template <template <class> class Formulation, class Cone, class Storage = SparseStorage<Cone::dim>,
          class LinearSolver = DefaultNewtonLinearSolver<Storage>>
class Newton
    : public ContactNewton<Newton<Formulation, Cone, Storage, LinearSolver>, Formulation, Cone> {
  using Base = ContactNewton<Newton, Formulation, Cone>;
  friend NewtonLoop<Newton>;
  friend Base;  // calls update_velocity()
  using Base::r_, Base::u_, Base::best_r_, Base::residual_, Base::psi_, Base::scale_, Base::reference_norm_;
  using Base::counters_, Base::info_, Base::settings_;

 public:
  using Base::d;
  static_assert(is_storage_v<Storage> && Storage::block_dim == d, "Storage must store d x d blocks");

  explicit Newton(const NewtonSettings& s = {}) : Base(s) {}

  /// Validates the problem, stores W, fixes the pattern of J. The viewed
  /// data must outlive the solver.
  Newton& compute(const LocalProblemView& p) {
    Stopwatch clock;
    this->check_dimension(p.d, d);
    sweeps_.compute(p);  // validates p, stores W
    const bool known_pattern = problem_ && jacobian_.same_pattern(p.W);
    problem_.emplace(p);
    // A problem with the pattern of the last one (the proximal point's
    // subproblems, W + alpha I) keeps J's pattern and the linear solver's
    // symbolic analysis, as the iterations of one solve do (callgrind, ppa
    // on generated piles: 9-12 % fewer instructions per whole run).
    if (known_pattern) {
      jacobian_.update_values(p.W);
    } else {
      jacobian_.compute(p.W);
      system_.compute(jacobian_);
      this->forget_step_time();
    }
    residual_.compute(p.mu, settings_.rho_strategy, settings_.rho,
                      [this](Index a) { return W().diagonal_block(a); });
    const Index m = p.size();
    r_.resize(m);
    u_.resize(m);
    dr_.resize(m);
    Wd_.resize(m);
    best_r_.resize(m);
    scale_ = error_scale(p.q.norm());
    reference_norm_ = residual_.reference_norm(p.q);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best iterate if the solve fails);
  /// u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    const Index m = problem_ ? problem_->size() : 0;
    fcsolve::check_solve_arguments("Newton", problem_.has_value(), r, m, u, m, "u");
    Stopwatch clock;
    r_ = r;
    update_velocity();
    this->run(clock);
    r = r_;
    u = u_;
    info_.solve_seconds = clock.seconds();
    return info_;
  }

 private:
  // ---- hooks of NewtonLoop (refresh, set_rho_factor: ContactNewton)
  double error() const {
    return std::sqrt(natural_map_norms<Cone>(r_, u_, problem_->mu).squared_sum) / scale_;
  }
  void save_best() { best_r_ = r_; }
  void restore_best() {
    r_ = best_r_;
    update_velocity();
  }
  bool fallback_sweep() {
    sweeps_.sweep(r_, u_);
    return true;
  }

  /// One globalised Newton step; false when no step could be taken. Only
  /// the factorisation (in system_.solve) may allocate.
  bool newton_step() {
    FCSOLVE_NO_MALLOC_BEGIN();
    jacobian_.assemble(residual_.A(), residual_.B(), system_.matrix());
    FCSOLVE_NO_MALLOC_END();
    if (!system_.solve(residual_.G(), dr_, this->shift(psi_, reference_norm_),
                       settings_.singular_regularization, counters_))
      return false;
    FCSOLVE_NO_MALLOC_BEGIN();
    W().multiply(dr_, Wd_);
    const bool stepped = this->take_step([&](double s) { return residual_.trial(r_, dr_, u_, Wd_, s); },
                                         [&](double t) { r_ += t * dr_; });
    FCSOLVE_NO_MALLOC_END();
    return stepped;
  }

  void update_velocity() {
    W().multiply(r_, u_);
    u_ += problem_->q;
  }

  /// The fallback's Gauss-Seidel sweeps (natural order, no freezing); they
  /// also hold W, one copy for both.
  using Sweeps = Nsgs<Cone, Storage, local::AlartCurnierBacktracking<Cone>>;
  static typename Sweeps::Settings sweep_settings() {
    typename Sweeps::Settings s;
    s.freezing = 0;
    return s;
  }
  const Storage& W() const { return sweeps_.storage(); }

  std::optional<LocalProblemView> problem_;
  Sweeps sweeps_{sweep_settings()};
  ReducedJacobian<d> jacobian_;
  RegularisedNewtonSystem<LinearSolver, ReducedJacobian<d>> system_;  // points to jacobian_
  Vector dr_, Wd_;
};

}  // namespace fcsolve
