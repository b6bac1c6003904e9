// The interior point's soft time limit: the rule that lets a path
// following run past it (EngineRun::soft_time, ipm/interior_point.hpp), and
// the note nipm's report carries when a run did, which `auto` reads
// (solvers/auto_entries.hpp). Depends on nothing else, so that `auto` can
// include it without the interior point.
#pragma once

#include <cmath>

namespace fcsolve {
namespace ipm {

/// Past a soft time limit the path following goes on while the rate of its
/// best error over the last kSoftTimeRateWindow iterations predicts tol
/// within twice that many iterations (a rate is not extrapolated far beyond
/// the span that measured it: earlier on the path the error often falls
/// fast, then stalls) and those iterations, at the run's time per iteration
/// so far, fit in half the time left before max_time. The rate is measured
/// again at every iteration, so a run that slows down ends at the iteration
/// that shows it. Why (docs/results.md, 2026-11-29): an interior point
/// cannot resume (a new run starts from the centre of the cones), so a run
/// cut a few iterations short of tol loses all of them; a caller that
/// shares its time between stages (`auto`) gives it a share as soft_time.
inline constexpr int kSoftTimeRateWindow = 5;

/// `best_now`: the best error so far; `best_before`: the same
/// kSoftTimeRateWindow iterations ago.
inline bool soft_time_extends(double best_now, double best_before, double tol, double seconds_per_iteration,
                              double time_left) {
  if (best_now <= tol) return true;
  // no rate yet (fewer iterations than the window), or no progress over it
  if (!std::isfinite(best_before) || !(best_now > 0) || !(best_now < best_before)) return false;
  const double rate = std::pow(best_now / best_before, 1.0 / kSoftTimeRateWindow);
  const double iterations = std::log(tol / best_now) / std::log(rate);
  return iterations <= 2 * kSoftTimeRateWindow && iterations * seconds_per_iteration <= 0.5 * time_left;
}

/// What nipm adds to its message when a run went on past soft_time.
inline constexpr const char* kPastSoftTimeNote = "went on past soft_time: its rate predicted tol";

}  // namespace ipm
}  // namespace fcsolve
