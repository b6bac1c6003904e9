// The ACLM outer loops (Acary, Cadoux, Lemarechal & Malick 2011; Acary 2025
// (talk), "Fixed point problem"; docs/references.md): with u(s) the solution
// of the convex problem with s frozen (ipm/socqp_ipm.hpp), a Coulomb solution
// is a fixed point of
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
  static constexpr int D = Form::dim;

 public:
  using Settings = AclmSettings;
  explicit AclmSolver(const AclmSettings& settings = AclmSettings()) : settings_(settings) {}
  AclmSettings& settings() { return settings_; }
  const AclmSettings& settings() const { return settings_; }

  /// Validates the problem, builds the form (KKT pattern, scaling).
  AclmSolver& compute(const typename Form::View& p) {
    this->compute_form(p);
    s0_.resize(0);
    return *this;
  }

  /// Starting tangential speeds for the next solve() (default: s = ||u_T||
  /// of a nonzero warm start, 0 otherwise).
  AclmSolver& set_initial_s(const Vector& s) {
    this->require_computed();
    if (s.size() != this->form_->num_contacts() || !s.allFinite() || (s.array() < 0).any())
      throw InvalidProblem("s", "expected one finite nonnegative entry per contact");
    s0_ = s;
    return *this;
  }

  /// From the warm start r (ipm_solver_base.hpp, try_warm_start): r, and
  /// w = v (global form) or u (local form).
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> w) {
    Stopwatch clock;
    SolverInfo& info = this->begin_solve(r, w);
    const AclmSettings& st = settings_;
    Outer outer;
    if (!this->try_warm_start(r, st, nullptr, st.max_time)) {
      outer.s = s0_.size() ? s0_ : tangential_speeds_of_best();
      outer_loop(outer, clock);
    }
    info.iterations = outer.total;
    summary_ = std::string("ACLM ") + (st.variant == AclmVariant::Newton ? "Newton" : "fixed point") +
               ": " + std::to_string(outer.steps) + " outer steps (" +
               std::to_string(outer.newton_steps) + " Newton, " + std::to_string(outer.fp_steps) +
               " fixed-point), " + std::to_string(outer.total) + " interior-point iterations, error " +
               format_number(this->best_.error);
    if (!outer.note.empty()) summary_ += "; " + outer.note;
    this->add_to_message(summary_);
    const bool out_of_steps = outer.total >= st.max_iter || outer.steps >= st.max_outer;
    return this->finish(r, w, st.tol,
                        out_of_steps ? Status::MaxIterations : this->status_of(outer.last_exit), clock);
  }

  /// What the last solve() did (info().message without the status).
  const std::string& summary() const { return summary_; }

 private:
  /// The state of the outer loop on s.
  struct Outer {
    Vector s, prev_s, Fs, u;
    double prev_residual = 0;
    double failed_polish_error = std::numeric_limits<double>::infinity();
    double inner_tol = 0;
    int total = 0, steps = 0, newton_steps = 0, fp_steps = 0, halvings = 0;
    IpmExit last_exit = IpmExit::MaxIterations;
    std::string note;
  };

  /// The outer loop: an inner IPM solve at fixed s, the FCLIB error of its
  /// point (a polish once small), then the next s.
  void outer_loop(Outer& o, const Stopwatch& clock) {
    const AclmSettings& st = settings_;
    Iterate& it = this->it_;
    it.s = o.s;
    this->engine_->cold_start(it, false, st.max_time - clock.seconds());
    o.prev_s = o.s;
    o.inner_tol = std::max(0.1, st.tol);
    for (; o.steps < st.max_outer && o.total < st.max_iter; ++o.steps) {
      if (clock.seconds() > st.max_time) {
        o.last_exit = IpmExit::TimeLimit;
        break;
      }
      const IpmReport rep = inner_solve(o, clock);
      // Outer residual: F(s) - s, and the FCLIB error of the inner solution.
      Vector r, w;
      this->extract(it, r, w);
      this->form_->velocity(it, o.u);
      o.Fs = tangential_speeds_of_u(o.u);
      const double error = this->form_->error(it, false);
      const double residual = (o.Fs - o.s).norm();
      if (st.record_history) this->info_.history.push_back(error);
      this->consider(r, w, error);
      // (an inner TimeLimit: the time is spent, or the next factorisation
      // would not end within it)
      if (rep.exit == IpmExit::NumericalError || rep.exit == IpmExit::Stopped ||
          rep.exit == IpmExit::TimeLimit) {
        o.note = this->describe("inner IPM", rep);
        break;
      }
      if (error <= st.tol || polished(o, r, w, error, clock)) {
        ++o.steps;
        break;
      }
      next_speeds(o, residual, error);
    }
  }

  /// The IPM on the convex problem at the current s, warm-started from the
  /// previous point, to a tolerance that follows the outer error.
  IpmReport inner_solve(Outer& o, const Stopwatch& clock) {
    const AclmSettings& st = settings_;
    EngineRun opt = this->engine_run(st, false, std::max(o.inner_tol, 0.1 * st.tol),
                                          st.max_iter - o.total, st.max_time - clock.seconds());
    opt.slow_below = 0;
    opt.record_history = false;
    opt.iteration_offset = o.total;
    opt.seconds_offset = clock.seconds();
    const IpmReport rep = this->run_engine(this->it_, opt);
    o.total += rep.iterations;
    o.last_exit = rep.exit;
    return rep;
  }

  /// Polishes (r, w) once the error is small, and again only after the
  /// outer loop has divided it by 10 since a polish that did not finish.
  /// True when the polished point meets tol.
  bool polished(Outer& o, const Vector& r, const Vector& w, double error, const Stopwatch& clock) {
    const AclmSettings& st = settings_;
    if (!st.polish || !(error < st.polish_below) || !(error < 0.1 * o.failed_polish_error))
      return false;
    Vector rp = r, wp = w;
    const PolishResult pr = this->polish(st, rp, wp, nullptr, st.tol, st.max_time - clock.seconds());
    this->consider(rp, wp, pr.error);
    if (pr.error <= st.tol) {
      o.note = this->describe_polish(pr);
      return true;
    }
    o.failed_polish_error = error;
    return false;
  }

  /// The next s: a fixed-point step F(s), or the Newton step, safeguarded
  /// (a step that did not reduce the outer residual is halved twice, then
  /// replaced by a fixed-point step).
  void next_speeds(Outer& o, double residual, double error) {
    const AclmSettings& st = settings_;
    const bool newton = st.variant == AclmVariant::Newton;
    if (newton && o.steps > 0 && residual > o.prev_residual && o.halvings < 2) {
      ++o.halvings;
      const Vector back = o.prev_s + 0.5 * (o.s - o.prev_s);
      restart_from(this->it_, o.s, back);
      o.s = back;
      return;
    }
    Vector next = o.Fs;  // fixed point
    Vector ds(o.s.size());
    if (newton && o.halvings < 2 && newton_direction(o.u, o.Fs - o.s, ds)) {
      next = (o.s + ds).cwiseMax(0.0);
      ++o.newton_steps;
    } else {
      ++o.fp_steps;
    }
    o.halvings = 0;
    o.prev_s = o.s;
    o.prev_residual = residual;
    o.inner_tol = st.inner_ratio * error;
    restart_from(this->it_, o.s, next);
    o.s = next;
  }

  /// s_a = ||u_T^a|| of u (0 on a frictionless contact: mu s = 0).
  Vector tangential_speeds_of_u(const Vector& u) const {
    return tangential_speeds<D>(u, this->form_->mu());
  }

  /// The starting s of the best point so far (the warm start): ||u_T||, or 0
  /// for a zero warm start (a cold start).
  Vector tangential_speeds_of_best() const {
    if ((this->best_.r.array() == 0).all()) return Vector::Zero(this->form_->num_contacts());
    return tangential_speeds_of_u(this->velocity_of(this->best_.w));
  }

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
    std::vector<Vec<D>, Eigen::aligned_allocator<Vec<D>>> n(std::size_t(nc), Vec<D>::Zero());
    const double scale = std::max(u.cwiseAbs().maxCoeff(), 1e-300);
    for (Index a = 0; a < nc; ++a) {
      const auto ut = u.template segment<D - 1>(a * D + 1);
      const double nt = ut.norm();
      if (nt > 1e-12 * scale) n[std::size_t(a)].template tail<D - 1>() = ut / nt;
    }
    Vector dx;
    auto apply = [&](const Vector& p, Vector& out) {
      this->engine_->frozen_sensitivity(p, dx, settings_.refinement);
      out = p;
      for (Index a = 0; a < nc; ++a) out[a] -= n[std::size_t(a)].dot(dx.template segment<D>(a * D));
    };
    const int products = gmres(apply, rhs, ds, 1e-3, 60, 30);
    return products > 0 && ds.allFinite();
  }

  std::string summary_;
  AclmSettings settings_;
  Vector s0_;
};

template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using GlobalAclm = AclmSolver<GlobalForm<Cone, Factorization>>;
template <class Cone = Coulomb3D, class Factorization = SparseKktFactorization<DefaultBackend>>
using LocalAclm = AclmSolver<LocalForm<Cone, Factorization>>;

}  // namespace ipm
}  // namespace fcsolve
