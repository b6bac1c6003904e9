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
//   fcsolve::ipm::GlobalSocqpIpm<3> ipm;   // or LocalSocqpIpm<3>
//   ipm.compute(problem);                  // validates, builds the KKT pattern
//   Vector r, v;
//   SolverInfo info = ipm.solve(r, v);     // v: velocities (u for the local form)
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

  template <class View>
  SocqpIpm& compute(const View& p) {
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

  /// Solves the frozen-s problem: r the reactions, w the velocities v
  /// (global form) or u = W r + q (local form).
  SolverInfo solve(Vector& r, Vector& w) {
    Stopwatch clock;
    SolverInfo& info = this->begin_solve();
    Iterate& it = this->it_;
    it.s = s_;
    this->engine_->cold_start(it, false);
    const IpmSettings& st = settings_;
    IpmOptions opt = this->engine_options(st, false, st.tol, st.max_iter, st.max_time);
    IpmReport rep = this->run_engine(it, opt);
    info.iterations = rep.iterations;
    info.history = rep.history;
    info.message = this->describe("IPM", rep);
    this->extract(it, r, w);
    double error = rep.error;
    if (error > st.tol && st.polish) {
      PolishResult pr = this->polish(st, r, w, &s_, st.tol, st.max_time - clock.seconds());
      info.message += "; " + this->describe_polish(pr);
      if (pr.error > st.tol && rep.exit == IpmExit::SlowProgress &&
          info.iterations < st.max_iter) {
        // The polish could not finish from there: let the IPM go on.
        opt.slow_below = 0;
        opt.max_iter = st.max_iter - info.iterations;
        opt.iteration_offset = info.iterations;
        opt.seconds_offset = clock.seconds();
        opt.max_time = st.max_time - clock.seconds();
        const IpmReport more = this->run_engine(it, opt);
        info.iterations += more.iterations;
        info.history.insert(info.history.end(), more.history.begin(), more.history.end());
        info.message += "; " + this->describe("IPM resumed", more);
        rep = more;
        Vector r2, w2;
        this->extract(it, r2, w2);
        PolishResult pr2 = this->polish(st, r2, w2, &s_, st.tol, st.max_time - clock.seconds());
        info.message += "; " + this->describe_polish(pr2);
        if (pr2.error < pr.error) {
          r = r2;
          w = w2;
          pr = pr2;
        }
      }
      error = std::min(error, pr.error);
    }
    info.error = error;
    coulomb_error_ = this->fclib_error(r, w);
    info.message += "; Coulomb (FCLIB) error of this point " + format_number(coulomb_error_);
    info.status = error <= st.tol ? Status::Converged : this->status_of(rep.exit);
    if (info.status == Status::Converged) info.message = "converged; " + info.message;
    info.solve_seconds = clock.seconds();
    return info;
  }

  /// FCLIB error of the last solution for Coulomb's law (not what this
  /// solver minimises unless s = ||u_T||).
  double coulomb_error() const { return coulomb_error_; }

 private:
  IpmSettings settings_;
  Vector s_;
  double coulomb_error_ = 0;
};

template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalSocqpIpm = SocqpIpm<GlobalForm<N, Factorization>>;
template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalSocqpIpm = SocqpIpm<LocalForm<N, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
