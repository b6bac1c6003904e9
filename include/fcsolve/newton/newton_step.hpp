// The Newton system shared by the reduced and the global forms: the matrix
// (pattern fixed by a Pattern object: ReducedJacobian or GlobalJacobian),
// its factorisation by a LinearSolver policy, and its regularisation
// (J + delta I) d = -G. Rank-deficient W (rigid bodies with more contact
// unknowns than degrees of freedom) makes J singular or nearly so when
// contacts stick, and the plain Newton step then has huge components along
// the near-null directions. The shift delta proportional to ||G|| (the
// Levenberg-Marquardt choice of Yamashita & Fukushima, Computing Suppl. 15,
// 2001, for equations with non-isolated solutions) damps them far from the solution and vanishes
// at it, so the local convergence stays superlinear (quadratic for the
// smooth case under a local error bound, ibid.). When the factorisation
// still fails, delta grows 100-fold per try.
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/core/types.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace fcsolve {

/// What a Newton solve did, for info().message and the benchmarks.
struct NewtonCounters {
  int steps = 0;               ///< Newton steps taken
  int nonmonotone_steps = 0;   ///< full steps taken after a failed line search
  int sweeps = 0;              ///< fallback Gauss-Seidel sweeps (hybrid)
  int fallbacks = 0;           ///< times the hybrid handed over to the sweeps
  int regularised = 0;         ///< singular systems solved with delta > 0
  int rho_changes = 0;         ///< adaptive rho rescalings
  int line_search_trials = 0;  ///< merit evaluations in line searches
  int factorisations = 0;
  double factorisation_seconds = 0;  ///< numerical factorisations and solves

  std::string describe() const {
    std::string s = std::to_string(steps) + " Newton steps";
    if (nonmonotone_steps) s += " (" + std::to_string(nonmonotone_steps) + " nonmonotone)";
    if (sweeps) s += ", " + std::to_string(sweeps) + " fallback sweeps in " + std::to_string(fallbacks) + " fallbacks";
    if (regularised) s += ", " + std::to_string(regularised) + " regularised systems";
    if (rho_changes) s += ", " + std::to_string(rho_changes) + " rho changes";
    return s;
  }
};

template <class LinearSolver, class Pattern>
class RegularisedNewtonSystem {
 public:
  using Matrix = typename LinearSolver::Matrix;

  /// Takes the pattern (kept by pointer: it must outlive this object).
  void compute(const Pattern& pattern) {
    pattern_ = &pattern;
    pattern.initialise(J_);
    solver_.reset();
    rhs_.resize(J_.rows());
  }

  /// The matrix whose values the caller assembles before solve().
  Matrix& matrix() { return J_; }

  /// d = -(J + delta I)^-1 G with delta = shift * s, s = max(1, max|J_ii|)
  /// over the rows the pattern regularises; if that system is singular (or
  /// the step not finite), delta grows to max(delta, singular_shift * s),
  /// then 100-fold per failure. false if no system could be solved.
  bool solve(const Vector& G, Vector& d, double shift, double singular_shift,
             NewtonCounters& counters) {
    Stopwatch clock;
    rhs_ = -G;
    const double scale = pattern_->diagonal_scale(J_);
    double applied = shift * scale;
    if (applied > 0) pattern_->add_to_diagonal(applied, J_);
    bool ok = attempt(d);
    if (!ok) {
      ++counters.regularised;
      double delta = std::max({applied, singular_shift * scale, 1e-14 * scale});
      for (int k = 0; k < 8 && !ok; ++k, delta *= 100) {
        pattern_->add_to_diagonal(delta - applied, J_);
        applied = delta;
        ok = attempt(d);
      }
    }
    ++counters.factorisations;
    counters.factorisation_seconds += clock.seconds();
    return ok;
  }

 private:
  bool attempt(Vector& d) {
    if (!solver_.factorize(J_)) return false;
    solver_.solve(rhs_, d);
    return d.allFinite();
  }

  const Pattern* pattern_ = nullptr;
  Matrix J_;  // UMFPACK reads it until the next factorisation: a member
  LinearSolver solver_;
  Vector rhs_;
};

}  // namespace fcsolve
