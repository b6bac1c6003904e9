// The convex SOCQP interior-point method: FC/I (or FC/II) with the friction
// term frozen, s given (Acary, Cadoux, Lemarechal & Malick 2011, problems
// (D_s)/(P_s)):
//   min 1/2 v^T M v - f^T v   s.t.  H^T v + w + A s in K*     (FCLIB signs)
// whose KKT conditions are M v = H r + f, u~ = H^T v + w + A s,
// K* ∋ u~ ⊥ r ∈ K, A s = (mu s, 0, 0) per contact; the local form solves the
// dual  min 1/2 r^T W r + (q + A s)^T r,  r in K. With s = 0 this is the
// associated (Tresca-free, "SOCQP") friction problem; the ACLM loops
// (ipm/aclm.hpp) update s.
//
// info() refers to the problem solved (s frozen): status Converged iff its
// natural-map error, in the FCLIB scaling, is <= tol. coulomb_error() is
// the FCLIB error of the same (r, v) for Coulomb's law, which only a fixed
// point s = ||u_T|| drives to zero.
//
//   fcsolve::ipm::GlobalSocqpIpm<Coulomb3D> ipm;   // or LocalSocqpIpm<Coulomb3D>
//   ipm.compute(problem);                  // validates, builds the KKT pattern
//   Vector r = Vector::Zero(problem.size()), v(problem.num_dofs());
//   const SolverInfo& info = ipm.solve(r, v);  // r: warm start in; v: velocities (u, local form)
#pragma once

#include <fcsolve/ipm/global_form.hpp>
#include <fcsolve/ipm/ipm_solver_base.hpp>
#include <fcsolve/ipm/local_form.hpp>
#include <fcsolve/linalg/default_backend.hpp>

namespace fcsolve {
namespace ipm {

template <class Form>
class SocqpIpm : public IpmSolverBase<Form> {

 public:
  using Settings = IpmSettings;
  explicit SocqpIpm(const IpmSettings& settings = IpmSettings()) : settings_(settings) {}

  IpmSettings& settings() { return settings_; }
  const IpmSettings& settings() const { return settings_; }

  /// Validates the problem, builds the form (KKT pattern, scaling).
  SocqpIpm& compute(const typename Form::View& p) {
    this->compute_form(p);
    s_.setZero(p.num_contacts());
    return *this;
  }

  /// The frozen tangential speeds s (default 0); s >= 0, one per contact.
  SocqpIpm& set_frozen_s(const Vector& s) {
    this->require_computed();
    if (s.size() != s_.size() || !s.allFinite() || (s.array() < 0).any())
      throw InvalidProblem("s", "expected " + std::to_string(s_.size()) +
                                    " finite nonnegative entries, one per contact");
    s_ = s;
    return *this;
  }

  /// Solves the frozen-s problem from the warm start r (ipm_solver_base.hpp,
  /// try_warm_start): r the reactions, w the velocities v (global form) or
  /// u = W r + q (local form).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> w) {
    Stopwatch clock;
    SolverInfo& info = this->begin_solve(r, w);
    IpmExit exit = IpmExit::Converged;
    if (!this->try_warm_start(r, settings_, &s_, settings_.max_time)) exit = run_and_polish(clock);
    coulomb_error_ = this->fclib_error(this->best_.r, this->best_.w);
    info.message += "; Coulomb (FCLIB) error of this point " + format_number(coulomb_error_);
    return this->finish(r, w, settings_.tol, this->status_of(exit), clock);
  }

  /// FCLIB error of the last solution for Coulomb's law (not what this
  /// solver minimises unless s = ||u_T||).
  double coulomb_error() const { return coulomb_error_; }

 private:
  /// The IPM from its cold start, then the polish; when the polish cannot
  /// finish from where the IPM slowed down, the IPM resumed and the polish
  /// again. Returns how the (last) IPM run ended.
  IpmExit run_and_polish(const Stopwatch& clock) {
    SolverInfo& info = this->info_;
    const IpmSettings& st = settings_;
    Iterate& it = this->it_;
    it.s = s_;
    this->engine_->cold_start(it, false, st.max_time - clock.seconds());
    EngineRun opt = this->engine_run(st, false, st.tol, st.max_iter, st.max_time);
    const IpmReport rep = this->run_engine(it, opt);
    info.iterations = rep.iterations;
    info.history = rep.history;
    this->add_to_message(this->describe("IPM", rep));
    Vector r, w;
    this->extract(it, r, w);
    this->consider(r, w, rep.error);
    // The polish factorises Newton matrices of the same problem: where the
    // IPM's would not fit in the time left, neither would they.
    if (rep.error <= st.tol || !st.polish || rep.factorization_refused) return rep.exit;
    const PolishResult pr = this->polish(st, r, w, &s_, st.tol, st.max_time - clock.seconds());
    this->add_to_message(this->describe_polish(pr));
    this->consider(r, w, pr.error);
    if (pr.error <= st.tol || rep.exit != IpmExit::SlowProgress || info.iterations >= st.max_iter)
      return rep.exit;
    // The polish could not finish from there: let the IPM go on.
    opt.slow_below = 0;
    opt.max_iter = st.max_iter - info.iterations;
    opt.iteration_offset = info.iterations;
    opt.seconds_offset = clock.seconds();
    opt.max_time = st.max_time - clock.seconds();
    const IpmReport more = this->run_engine(it, opt);
    info.iterations += more.iterations;
    info.history.insert(info.history.end(), more.history.begin(), more.history.end());
    this->add_to_message(this->describe("IPM resumed", more));
    this->extract(it, r, w);
    const PolishResult again = this->polish(st, r, w, &s_, st.tol, st.max_time - clock.seconds());
    this->add_to_message(this->describe_polish(again));
    this->consider(r, w, again.error);
    return more.exit;
  }

  IpmSettings settings_;
  Vector s_;
  double coulomb_error_ = 0;
};

template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalSocqpIpm = SocqpIpm<GlobalForm<Cone, Factorization>>;
template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalSocqpIpm = SocqpIpm<LocalForm<Cone, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
