// The Tresca fixed point on FC/II(W, q, mu) (Acary, Bremond & Huber 2018,
// sec. on fixed points over the friction threshold [TFP]; Siconos' TFP;
// Haslinger 1983 for the underlying successive approximations):
//
//   s_k = mu r_N(k)                  (the threshold, per contact)
//   r_{k+1} solves Tresca(W, q, s_k):  -u in N_C(s_k)(r), u = W r + q,
//                                      C(s) = { r_N >= 0, ||r_T|| <= s }
//
// A fixed point (s = mu r_N) is a Coulomb solution. The map r_N -> r_N is
// no contraction in general (large mu, strong N-T coupling): measured on
// Capsules-i100-889 it falls into a 2-cycle. So the threshold is relaxed,
// s_{k+1} = s_k + theta (mu r_N(k+1) - s_k) (Krasnoselskii-Mann averaging,
// as local/projection_iterative.hpp does), theta halved (down to 1/64) each
// time the FCLIB error grows and doubled (up to 1) each time it falls:
// theta that only shrinks (measured) turned 0.05 s into 10 s on
// Capsules-i101-404 (21495 outer iterations). Each Tresca problem is
// solved by NSGS (nsgs/) on the cylinder policy (cone/tresca.hpp) with one
// projection per contact (local::Projection), warm-started from r_k, to the
// adaptive tolerance max(err_k / 10, tol) (fixed_point/splitting_solver.hpp).
// W's storage is built once; each outer iteration only re-reads the
// thresholds (Nsgs::refresh_q_and_mu), so nothing is allocated after
// compute(). Frictionless contact has no threshold: one Tresca problem is
// the LCP itself.
//
// Success is declared only on the FCLIB error of the Coulomb problem
// (problem/error.hpp); a failed solve returns the best outer iterate.
#pragma once

#include <fcsolve/fixed_point/splitting_solver.hpp>

#include <algorithm>

namespace fcsolve {

template <class Cone, class Storage>
class TrescaFixedPoint : public SplittingSolver<Cone> {
  using Base = SplittingSolver<Cone>;

 public:
  using typename Base::Settings;
  using Set = tresca_set_t<Cone>;
  using Inner = Nsgs<Set, Storage, local::Projection<Set>>;

  explicit TrescaFixedPoint(const Settings& s = {}) : Base(s) {}

  /// Validates p and builds the inner NSGS on Tresca(W, q, s). The viewed
  /// data must outlive *this.
  TrescaFixedPoint& compute(const LocalProblemView& p) {
    Stopwatch clock;
    this->prepare(p);
    const Index nc = p.num_contacts();
    threshold_ = Vector::Zero(nc);
    inner_.settings().ordering = ContactOrdering::Natural;
    inner_.compute(LocalProblemView(p.d, p.W, p.q, VectorMap(threshold_.data(), nc)));
    u_.resize(p.size());
    this->info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best outer iterate if the solve
  /// fails); u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    bool first = true;
    return this->iterate("TrescaFixedPoint", "Tresca problems", r, u,
                         [&](Eigen::Ref<Vector> x, double tol, double remaining, double error) {
                           FCSOLVE_NO_MALLOC_BEGIN();
                           if (first) {
                             relax_ = 1;
                           } else if (error > last_error_) {
                             relax_ = std::max(relax_ / 2, 1.0 / 64);
                           } else {
                             relax_ = std::min(relax_ * 2, 1.0);
                           }
                           update_threshold(x, first ? 1.0 : relax_);
                           first = false;
                           last_error_ = error;
                           FCSOLVE_NO_MALLOC_END();
                           auto& is = inner_.settings();
                           is.tol = tol;  // the Tresca problem has the outer q: the same scale
                           is.max_iter = this->settings_.inner_max_iter;
                           is.max_time = std::max(remaining, 1e-9);
                           inner_.refresh_q_and_mu();
                           return inner_.solve(x, u_).iterations;
                         });
  }

 private:
  /// s <- s + theta (mu r_N - s), contact by contact (frictionless: unused).
  void update_threshold(const Eigen::Ref<const Vector>& r, double theta) {
    constexpr int d = Cone::dim;
    for (Index a = 0; a < threshold_.size(); ++a)
      threshold_[a] += theta * (this->problem_->mu[a] * std::max(r[a * d], 0.0) - threshold_[a]);
  }

  Vector threshold_, u_;
  double relax_ = 1, last_error_ = 0;
  Inner inner_;
};

}  // namespace fcsolve
