// The ACLM outer loops (Acary, Cadoux, Lemarechal & Malick 2011; reference
// talk, "Fixed point problem"): with u(s) the solution of the convex problem
// with s frozen (ipm/socqp_ipm.hpp), a Coulomb solution is a fixed point of
//   F(s)_a = ||u_T^a(s)||.
//  * FixedPoint:  s <- F(s).
//  * Newton:      s <- s + ds,  (I - F'(s)) ds = F(s) - s, solved by GMRES;
//    F'(s) p = n^T du_T with du the derivative of the central point of the
//    last interior-point iteration for the data change w -> w + A p (one KKT
//    solve with the last factorisation), n_a = u_T^a / ||u_T^a||. A step that
//    does not reduce ||F(s) - s|| is halved, then replaced by s <- F(s).
// Every inner problem is solved by the IPM warm-started from the previous
// solution pushed back into the interior, to a tolerance that follows the
// outer residual. Convergence is decided on the FCLIB error of (r, v); a
// Newton polish on the natural map takes over once that error is small.
#pragma once

#include <fcsolve/ipm/gmres.hpp>
#include <fcsolve/ipm/socqp_ipm.hpp>

#include <algorithm>

namespace fcsolve {
namespace ipm {

enum class AclmVariant { FixedPoint, Newton };

struct AclmSettings : IpmSettings {
  AclmSettings() { max_iter = 400; }  // interior-point iterations, all outer steps together
  AclmVariant variant = AclmVariant::Newton;
  int max_outer = 60;
  double inner_ratio = 0.1;  ///< inner tolerance = inner_ratio * outer error (>= tol / 10)
};

template <class Form>
class AclmSolver : public IpmSolverBase<Form> {
  static constexpr int N = Form::dim;

 public:
  using Settings = AclmSettings;
  explicit AclmSolver(const AclmSettings& settings = AclmSettings()) : settings_(settings) {}
  AclmSettings& settings() { return settings_; }
  const AclmSettings& settings() const { return settings_; }

  template <class View>
  AclmSolver& compute(const View& p) {
    this->compute_form(p);
    s0_.setZero(p.num_contacts());
    return *this;
  }

  /// Starting tangential speeds (default 0).
  AclmSolver& set_initial_s(const Vector& s) {
    this->require_computed();
    if (s.size() != s0_.size() || !s.allFinite() || (s.array() < 0).any())
      throw InvalidProblem("s", "expected one finite nonnegative entry per contact");
    s0_ = s;
    return *this;
  }

  /// r, and w = v (global form) or u (local form).
  SolverInfo solve(Vector& r, Vector& w) {
    Stopwatch clock;
    SolverInfo& info = this->begin_solve();
    const AclmSettings& st = settings_;
    const Index nc = this->form_->num_contacts();
    Iterate& it = this->it_;
    it.s = s0_;
    this->engine_->cold_start(it, false);
    Vector s = s0_, Fs(nc), u, best_r, best_w, ds(nc);
    double best_error = std::numeric_limits<double>::infinity(), prev_residual = 0;
    double failed_polish_error = std::numeric_limits<double>::infinity();
    Vector prev_s = s;
    int total = 0, outer = 0, newton_steps = 0, fp_steps = 0, halvings = 0;
    double inner_tol = std::max(0.1, st.tol);
    IpmExit last_exit = IpmExit::MaxIterations;
    std::string note;
    bool converged = false;
    for (; outer < st.max_outer && total < st.max_iter; ++outer) {
      if (clock.seconds() > st.max_time) {
        last_exit = IpmExit::TimeLimit;
        break;
      }
      IpmOptions opt = this->engine_options(st, false, std::max(inner_tol, 0.1 * st.tol),
                                            st.max_iter - total, st.max_time - clock.seconds());
      opt.slow_below = 0;
      opt.record_history = false;
      opt.iteration_offset = total;
      opt.seconds_offset = clock.seconds();
      const IpmReport rep = this->run_engine(it, opt);
      total += rep.iterations;
      last_exit = rep.exit;
      // Outer residual: F(s) - s, and the FCLIB error of the inner solution.
      this->extract(it, r, w);
      this->form_->velocity(it, u);
      for (Index a = 0; a < nc; ++a) Fs[a] = u.template segment<N - 1>(a * N + 1).norm();
      const double error = this->form_->error(it, false);
      const double residual = (Fs - s).norm();
      if (st.record_history) info.history.push_back(error);
      if (error < best_error || best_r.size() == 0) {
        best_error = error;
        best_r = r;
        best_w = w;
      }
      if (rep.exit == IpmExit::NumericalError || rep.exit == IpmExit::Stopped) {
        note = this->describe("inner IPM", rep);
        break;
      }
      if (error <= st.tol) {
        converged = true;
        ++outer;
        break;
      }
      // Polish once the error is small, and again only after the outer
      // loop has divided it by 10 since a polish that did not finish.
      if (st.polish && error < st.polish_below && error < 0.1 * failed_polish_error) {
        Vector rp = r, wp = w;
        const PolishResult pr = this->polish(st, rp, wp, nullptr, st.tol,
            st.max_time - clock.seconds());
        if (pr.error < best_error) {
          best_error = pr.error;
          best_r = rp;
          best_w = wp;
        }
        if (pr.error <= st.tol) {
          note = this->describe_polish(pr);
          converged = true;
          ++outer;
          break;
        }
        failed_polish_error = error;
      }
      // Safeguard of the Newton variant: a step that did not reduce the
      // outer residual is halved (twice), then replaced by a fixed-point step.
      if (st.variant == AclmVariant::Newton && outer > 0 && residual > prev_residual &&
          halvings < 2) {
        ++halvings;
        const Vector back = prev_s + 0.5 * (s - prev_s);
        restart_from(it, s, back);
        s = back;
        continue;
      }
      Vector next = Fs;  // fixed point
      if (st.variant == AclmVariant::Newton && halvings < 2) {
        if (newton_direction(u, Fs - s, ds)) {
          next = (s + ds).cwiseMax(0.0);
          ++newton_steps;
        } else {
          ++fp_steps;
        }
      } else {
        ++fp_steps;
      }
      halvings = 0;
      prev_s = s;
      prev_residual = residual;
      inner_tol = st.inner_ratio * error;
      restart_from(it, s, next);
      s = next;
    }
    if (best_r.size() == 0) {  // no inner run (the time budget was spent at once): the start
      this->extract(it, best_r, best_w);
      best_error = this->form_->error(it, false);
    }
    r = best_r;
    w = best_w;
    info.iterations = total;
    info.error = best_error;
    info.status = converged ? Status::Converged
                            : (total >= st.max_iter || outer >= st.max_outer ? Status::MaxIterations
                                                                             : this->status_of(last_exit));
    summary_ = std::string("ACLM ") + (st.variant == AclmVariant::Newton ? "Newton" : "fixed point") +
               ": " + std::to_string(outer) + " outer steps (" + std::to_string(newton_steps) +
               " Newton, " + std::to_string(fp_steps) + " fixed-point), " + std::to_string(total) +
               " interior-point iterations, error " + format_number(best_error);
    if (!note.empty()) summary_ += "; " + note;
    info.message = std::string(converged ? "converged; " : "") + summary_;
    info.solve_seconds = clock.seconds();
    return info;
  }

  /// What the last solve() did (info().message without the status).
  const std::string& summary() const { return summary_; }

 private:
  /// Warm start for the data s_new: the previous point pushed back into the
  /// interior by about the change of the data (|ds| in x's units, scaled by
  /// theta^2, the typical x/y ratio, for y).
  void restart_from(Iterate& it, const Vector& s_old, const Vector& s_new) {
    const double theta = this->form_->initial_scaling();
    const double scale_x = std::max(it.x.cwiseAbs().maxCoeff(), 1e-300);
    const double shift = std::max((s_new - s_old).cwiseAbs().maxCoeff(), 1e-6 * scale_x);
    it.s = s_new;
    InteriorPoint<Form>::push_inside(it, shift, shift / (theta * theta));
  }

  /// (I - F'(s)) ds = F(s) - s by GMRES; false if it made no progress.
  bool newton_direction(const Vector& u, const Vector& rhs, Vector& ds) {
    const Index nc = this->form_->num_contacts();
    std::vector<Vec<N>, Eigen::aligned_allocator<Vec<N>>> n(std::size_t(nc), Vec<N>::Zero());
    const double scale = std::max(u.cwiseAbs().maxCoeff(), 1e-300);
    for (Index a = 0; a < nc; ++a) {
      const auto ut = u.template segment<N - 1>(a * N + 1);
      const double nt = ut.norm();
      if (nt > 1e-12 * scale) n[std::size_t(a)].template tail<N - 1>() = ut / nt;
    }
    Vector dx;
    auto apply = [&](const Vector& p, Vector& out) {
      this->engine_->frozen_sensitivity(p, dx, settings_.refinement);
      out = p;
      for (Index a = 0; a < nc; ++a) out[a] -= n[std::size_t(a)].dot(dx.template segment<N>(a * N));
    };
    const int products = gmres(apply, rhs, ds, 1e-3, 60, 30);
    return products > 0 && ds.allFinite();
  }

  std::string summary_;
  AclmSettings settings_;
  Vector s0_;
};

template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalAclm = AclmSolver<GlobalForm<N, Factorization>>;
template <int N = 3, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalAclm = AclmSolver<LocalForm<N, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
