// The catalogue entry `auto`: one default call that aims to be robust AND
// efficient (the open question that closes Acary 2025 (talk), "choose
// efficiency OR robustness"; docs/references.md).
//
// It is a staged plan over the other catalogue entries. Every stage starts
// from the best iterate so far and its result is judged with the FCLIB error
// (registry::solve recomputes it), so the returned r is never worse than an
// earlier stage's, and "converged" is claimed only when that error <= tol.
//
//   features   cheap, measured once: nc, d, m, mu range, kind (FC/I, FC/II),
//              n and d nc / n (rank deficiency of W = H^T M^-1 H) for FC/I,
//              the spread max/min of W_NN over the contacts (mass ratios).
//   0 sticking FC/I reduced to FC/II whose W is much denser than H and M
//              (see below): the interior point on the convex associated
//              problem (`ipm-socqp`, 30 iterations at most), which is
//              Coulomb's where every contact sticks or is frictionless.
//   1 sweeps   NSGS (`nsgs`): a warm start and a first measured convergence
//              rate. Small problems (nc <= kTinyContacts) stay with NSGS to
//              the end: a sweep costs next to nothing there and a Newton
//              step's factorisation does not pay. Otherwise NSGS goes on, in
//              doubling chunks, only while the linear rate measured on the
//              last chunk predicts tol within what is left of an allowance
//              of what three Newton steps cost, in sweeps, estimated
//              from the symbolic analysis of W's LU (at most a thousand
//              sweeps; once it is spent, one last chunk of one step's
//              sweeps where they predict tol within a quarter of a step),
//              and not at all on FC/I with d nc / n above
//              kSingularContactRatio (1.1): W is then singular, the
//              reactions are not unique and Gauss-Seidel plateaus
//              (measured: spheres-in-a-box, d nc / n = 1.3, NSGS stuck at
//              6e-8); sphere piles (1.00 to 1.01) take the sweeps' chunks.
//   2 newton   semismooth Newton on Alart-Curnier (`nsn-ac`, the entry that
//              solves every shared problem, docs/results.md): full steps
//              from the sweeps' iterate (local superlinear convergence);
//              if they stall within 10 x tol after lowering the error
//              1000x, 50 sweeps first (they settle the few degenerate
//              contacts the steps cycle on);
//              if they stall, unless it ran at 1b, the
//              nonsmooth interior point (`nipm`), 100 iterations at most,
//              on a share of the budget (its iteration count barely feels
//              a singular W: rigid stacks, walls, piles); if it did not
//              halve the error, sweeps for as long as it took (if their
//              last chunk still lowered the error); then the
//              line-searched Newton; each Newton stage with a short stall
//              window: it stops early when the error stops halving.
//   3 sweeps   when Newton stalls or diverges: NSGS sweeps from the best
//              iterate (robust, monotone in practice; 50, and 450 more
//              only if those lowered the error), then
//   4 newton   Newton once more from what the sweeps reached (a Newton
//              stage often converges from a better start where it stalled),
//   5 ipm      if it has not run (full steps cut by the time
//              budget at 2): the interior point as above,
//   6 proximal the proximal point method (`ppa`): Newton on the
//              regularised subproblems W + alpha I, robust where W is
//              singular or badly scaled; with a finite max_time, cut by
//              its share while still lowering the error, it keeps the time,
//   7 sweeps   NSGS for whatever time is left.
//
// FC/I is reduced to FC/II (W = H^T M^-1 H) and planned as above when W
// stays sparse: rigid bodies, M block-diagonal. The sweeps run on W; the
// sticking probe, the Newton and the interior-point stages run on FC/I
// itself in (v, r) (`ipm-socqp`, `nsn-ac-global`, `nipm`) when W is much
// denser than H and M (many contacts per body: towers, walls), since a
// step's factorisation then costs less there (kNativeLinearAlgebraFill).
// When M^-1 couples the dofs
// (an elastic body: W dense, d^2 nc^2 entries) forming W costs more than
// solving, so the plan stays on FC/I, W never formed: ADMM in (v, r)
// (`admm-global`, at most kNativeAdmmIterations), then semismooth Newton
// from its iterate (`nsn-ac-global`; with a finite max_time, only where a
// Newton step fits: ADMM keeps the time otherwise, AdmmHandover), then the
// nonsmooth interior point (`nipm`) from scratch for the time left if
// Newton stalls.
//
// Stages switch on iteration counts and measured errors, never on measured
// times, so a run is deterministic for a given input and settings; the wall
// clock only cuts a stage when a finite max_time is given, and the budget is
// split so that later stages keep a share of it. With a finite max_time, a
// factorising stage is not started when the first step measured on an
// earlier one outlasts its share (FactorisationStepCost), sweeps cut by
// their share while predicted to end within one Newton step keep the time
// (Plan::continue_sweeps), so does a proximal stage cut by its share
// while still lowering the error (Plan::robust_tail), and the interior
// point's share is a soft limit it may overrun while its rate predicts tol
// (Plan::interior_point), and on FC/I ADMM hands over to Newton at its
// share only where a Newton step fits the rest (AdmmHandover): the places
// where the clock decides, besides the budget's cuts.
#pragma once

#include <fcsolve/core/short_number.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/ipm/soft_time.hpp>
#include <fcsolve/linalg/backend_traits.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/problem/reduced_density.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/solvers/registry.hpp>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fcsolve {
namespace registry {

// Defined in solvers/catalog.hpp, which registers this entry among the
// others; the plan looks its stages up by name when it runs.
const SolverEntry& find(std::string_view name);
const SettingValues& default_settings(const SolverEntry& e);

namespace auto_detail {

/// Problems with at most this many contacts are left to NSGS.
inline constexpr Index kTinyContacts = 8;
/// Sweeps NSGS gets on them before the robust tail (a few ms at that size).
inline constexpr int kTinySweeps = 20000;
/// The sweeps that end the plan stop on a plateau: NSGS' give_up_sweeps,
/// after its own reshuffle at stall_sweeps (both 5000: 10^4 sweeps, 0.8 s
/// on 1000 contacts). Measured (docs/results.md, 2026-11-29): on a
/// heavy-on-light stack nobody here solves, without a time limit, they swept
/// to max_iter (10^6) at 5.3e-3: 91 s of a 146-s run.
inline constexpr int kFinalSweepsGiveUp = 5000;
/// Warm-start sweeps (two full errors with NSGS' error_every = 10).
inline constexpr int kWarmSweeps = 20;
/// NSGS continues after the warm start if its rate predicts tol within an
/// allowance of kNewtonStepsWorthSweeping Newton steps' cost, counted in
/// sweeps (newton_step_in_sweeps), and at most this many sweeps.
inline constexpr double kSweepsWorthContinuing = 1000;
/// Newton from the warm start takes some ten steps, but the sweeps'
/// prediction (a linear rate) is a bet with a lopsided record, measured on
/// the shared set and the training half of the corpus (docs/results.md,
/// 2026-11-27): where Gauss-Seidel keeps its rate the prediction holds
/// (0.3 to 1.5 times the sweeps it then took), where it slows down it is
/// 3.5 to 12 times short (Capsules, PerioBox, walls and box stacks), and
/// the first chunk cannot tell the two apart. Three steps' worth (ten over
/// the smallest shortfall) lets the sweeps finish where they keep their
/// rate and hands over early where they slow down; chosen among 3, 5 and
/// 10 on that training data, checked on the held-out half.
inline constexpr double kNewtonStepsWorthSweeping = 3;
/// A Newton step's cost in sweeps, modelled as a + x with x = (the LU's
/// estimated flops) / nnz(W): a fixed part (assembling J, the triangular
/// solves, the line search's products with W, each a pass over about
/// nnz(W) entries as a sweep is) and the factorisation's flops, one sweep
/// per nnz(W) flops (the slope the data below gives). Fitted to nsn-ac
/// and nsgs' time per iteration on the generated corpus with KLU
/// (docs/results.md, 2026-11-27): sphere piles x ~ 4, 14 to 51 sweeps a
/// step; box stacks x ~ 18, 15 to 54; walls of 300, x ~ 57, 25 to 78;
/// walls and towers of 1000, x ~ 180 to 220, 216 to 242.
inline constexpr double kNewtonStepFixedSweeps = 25;
/// Sweeps of the first continuation chunk (then 2x, 4x, ...).
inline constexpr int kFirstChunk = 40;
/// A chunk is at most this many times the sweeps its rate predicts (and
/// at least kFirstChunk): where Gauss-Seidel reaches a plateau, the
/// prediction from the chunk before is short, and a chunk sized by the
/// doubling alone spends the allowance on it (a sphere pile of 1000 at
/// 1e-4: 43 sweeps predicted, 640 then 1280 run that lowered the error by
/// 8 %, docs/results.md, 2026-11-28).
inline constexpr double kChunkOverPrediction = 2;
/// Once the allowance is spent, the sweeps still get one last chunk of one
/// Newton step's cost when their rate predicts tol within a quarter of
/// that: the Newton stage that would replace them costs at least one step
/// and its symbolic analysis, and a prediction four times short (over the
/// last chunk's horizon, not the whole run's) still finishes. Measured on
/// LMGC_100_PR_PerioBox at 1e-4: the allowance ran out 14 sweeps short of
/// tol (one step: 75), and the Newton stage then took 1.8 ms where the
/// sweeps had taken 0.85 ms for their last 105 (docs/results.md).
inline constexpr double kLastChunkShortfall = 4;
/// After full Newton steps that did not lower the error, the sweeps get
/// this many Newton steps' cost before the interior point runs. Where full
/// steps stalled on the rigid corpus, nipm took 11 to 68 iterations when it
/// converged (each at least one Newton step's factorisation) and did not
/// converge on 3 problems of 13 (docs/results.md): the sweeps go on where
/// they are predicted to beat an interior point of 20 iterations, the low
/// end of that range. Measured on a sphere pile of 10^4 contacts at 1e-4
/// (docs/results.md, 2026-11-28): the sweeps handed over predicting 776
/// more (2340 were needed), and the plan spent 50 s in Newton, nipm and
/// ppa stages that stalled where NSGS alone converged in 3.9 s; now 4.8 s,
/// and at 1e-8, which no solver had reached in 60 s, 34 s. (The step's
/// estimate from W's pattern is 7x what a full step measured there: the
/// resumed sweeps may run some 30 s.)
inline constexpr double kInteriorPointStepsWorthSweeping = 20;
/// Those resumed sweeps stop when a chunk's rate (its log) is this many
/// times slower than the chunk's before: the prediction that sized the
/// chunk was as many times short, a plateau (the allowance above is seven
/// times the first loop's, so a plateau would cost as much more). The
/// first loop keeps its rule: its smaller allowance bounds what a plateau
/// costs there. Measured: a sphere pile of 1000 at 1e-4 stopped at a
/// plateau of 1.1e-4 after 390 sweeps instead of 2240; on the pile of 10^4
/// the resumed chunks slowed by 2.5x, then 1.2x, and finished.
inline constexpr double kPlateauSlowdown = 4;
/// An interior point that lowered the best error by less than this factor
/// did not pay: the sweeps, if their last chunk still lowered the error,
/// get its time back (Plan::sweeps_match_interior_point). Halving, as the Newton stall
/// window measures progress.
inline constexpr double kInteriorPointGain = 2;
/// FC/I with d nc / n above this goes from the warm sweeps straight to
/// Newton: W = H M^-1 H^T is singular with a null space of at least
/// d nc - n, the reactions are not unique and the sweeps plateau (box
/// stacks 2, walls 3 to 3.7, mixed shapes 1.4 to 1.5). A sphere pile sits
/// at 1.00 to 1.01 (two contacts a sphere): its W is nearly of full rank,
/// and its FC/II form, which the sweeps' chunks decide for, did better on
/// five of the eight held-out piles of 1500 to 7000 contacts
/// (docs/results.md, 2026-12-07, stop 63).
inline constexpr double kSingularContactRatio = 1.1;
/// Newton: iterations without halving the best error that count as a stall.
inline constexpr int kNewtonStallWindow = 25;
/// The same for full Newton steps: they either contract fast or not at all.
inline constexpr int kFullStepStallWindow = 12;
/// A Newton stage that stalled starts again only from an iterate whose
/// error is at most this fraction of its own starting error: the stall
/// window's measure of progress (halving). From a nearly equal iterate it
/// takes nearly the same steps and stalls again. Measured (held-out pile of
/// 7995 contacts, seed 603, tol 1e-8, 20 s, 2026-12-07): the line search
/// stalled from 9.1e-5, 500 sweeps reached 8.8e-5, and it ran again for
/// 2.0 s to 8.7e-5; the rule skips that run (docs/results.md).
inline constexpr double kNewtonRestartGain = 0.5;
inline constexpr int kNewtonMaxIter = 300;
/// Full Newton steps that lowered the error by kFastPhaseReduction or
/// more and stalled within kNearTolPolish of tol hand over to
/// kBridgeProbeSweeps sweeps before the interior point. Near the solution
/// of a singular W (walls, towers: many contacts per body) the full steps,
/// once their fast local phase is over, hover between 1e-9 and 1e-7 for
/// tens of steps while the active set of a few degenerate contacts (r_N and
/// u_N both near 0, or |r_T| near mu r_N) cycles; a Gauss-Seidel sweep
/// solves each of them exactly given the others. Measured on an FC/II wall
/// of 600 contacts (mu 1, mass ratio 10): from the full steps' iterate at
/// 8.1e-9 the sweeps reached 4.5e-10 in 20 sweeps, 8.7e-11 in 50; 50 sweeps
/// cost about one Newton step on W there. Full steps that stall after
/// less progress are not near a solution but on a hard problem, where the
/// interior point is next: at tol 1e-4, walls whose full steps lowered
/// the error 40 to 200x before stalling within 10 x tol took the sweeps,
/// and the path after them changed (a pile 121 -> 175 iterations; of four
/// walls two 2 to 10x faster, two as much slower; docs/results.md,
/// 2026-12-01).
inline constexpr double kNearTolPolish = 10;
inline constexpr double kFastPhaseReduction = 1e3;
/// Sweeps between two Newton stages: a first chunk, and the rest only when
/// that chunk lowered the best error. Measured where the bridge ran (the
/// shared set, the corpus, frictionless scenes with mass ratios; docs/
/// results.md, 2026-11-27): after a stalled Newton stage the 500 sweeps
/// left the best error unchanged on nine problems of ten (heavy-on-light
/// 300 with mass ratio 10^4: 36 of auto's 86 ms) and halved it on one.
inline constexpr int kBridgeProbeSweeps = 50;
inline constexpr int kBridgeSweeps = 500;
/// FC/I is reduced to FC/II unless M^-1 H fills in (reduced_density.hpp):
/// rigid bodies measure nnz(M^-1 H) = nnz(H) exactly, elastic bodies 10 to
/// 10^4 times nnz(H) (M^-1 dense). Forming W then costs one solve with M's
/// factor per column of H, more than the whole native Newton solve measured
/// from a hundred contacts on (fem-block, 300 contacts: 0.54 s to reduce,
/// 0.39 s for nsn-ac-global to 1e-16).
inline constexpr double kInverseMassFill = 4;
/// Below this many entries of M^-1 H either way is cheap: reduce.
inline constexpr double kSmallInverseMassProduct = 1e5;
/// FC/I reduced to FC/II: from this ratio nnz(W) / (nnz(H) + nnz(M)) on,
/// the Newton and interior-point stages run on FC/I in (v, r), where a
/// step factorises a matrix of H's and M's sparsity instead of W's. W
/// couples every two contacts on one body, so the ratio grows with the
/// contacts per body. Measured, each solver alone from scratch, 1e-8
/// (docs/results.md, "auto: Newton and the interior point on FC/I"): box
/// stacks (ratio 5.4) run as fast on either form; walls (8.5 to 13) 1.1 to
/// 1.5x and towers (16 to 21) 3 to 3.5x faster on FC/I (nsn-ac-global
/// against nsn-ac, nipm on FC/I against nipm on W).
inline constexpr double kNativeLinearAlgebraFill = 8;
/// Iterations of the sticking probe (Plan::run: `ipm-socqp` on FC/I).
/// Where it solved the rigid corpus to 1e-8 (towers, walls) it took 5 to
/// 21; where some contact slides it stopped, stalled, in 11 to 28.
inline constexpr int kStickingProbeIterations = 30;
/// Iterations of the interior-point stage (see Plan::interior_point).
inline constexpr int kInteriorPointIterations = 100;

/// The interior-point stage ends when it crawls (InteriorPointCrawl): its
/// best error lowered by less than kCrawlImprovement over kCrawlWindow
/// iterations (the engine's own stall window counts any decrease), once
/// the path following has lowered it to kCrawlPathDone times the first
/// iterate's (a plateau before that is the path following at work).
/// Measured (docs/results.md, 2026-11-28): a sphere pile of 3000 crawled
/// from 4.84e-4 to 4.80e-4 in its last 45 of 100 iterations (1.6 s), and
/// the proximal stage solved it afterwards anyway. The guard:
/// on a heavy-on-light stack the error sits at 0.56 (its first iterate's
/// 0.6) for 12 iterations while the path following goes on, then falls to
/// 1.8e-5; an error test alone stopped that stage, and cost 3 s. One
/// decade below the first iterate is past that early plateau: on a
/// held-out pile of 10^4 contacts (seed 720) the path fell from 2.0 to
/// 3.6e-2 in 10 iterations and stayed at 3.5e-2 for the other 90 (0.28 s
/// each), which a guard of two decades let run to the iteration cap: 29 s
/// of a 144-s run without a time limit (docs/results.md, 2026-12-07).
inline constexpr int kCrawlWindow = 12;
inline constexpr double kCrawlImprovement = 0.01;
inline constexpr double kCrawlPathDone = 0.1;

/// Watches the errors an interior-point run reports (one per iteration,
/// through the stage's callback) and says when it crawls. It keeps the
/// best errors of the last kCrawlWindow + 1 iterations in a ring: it is a
/// member of every run, and a run of one contact must not pay an
/// allocation for it.
class InteriorPointCrawl {
 public:
  void start() {
    count_ = 0;
    fired_ = false;
  }
  bool fired() const { return fired_; }
  /// The next iteration's error; true when the run should stop.
  bool crawls(double error) {
    if (!std::isfinite(error)) return false;  // the engine's own exit
    const double best = count_ == 0 ? error : std::min(bests_[(count_ - 1) % kRing], error);
    if (count_ == 0) first_ = error;
    bests_[count_ % kRing] = best;
    ++count_;
    if (count_ <= std::size_t(kCrawlWindow)) return false;
    // the best error kCrawlWindow iterations ago
    const double before = bests_[(count_ - 1 - kCrawlWindow) % kRing];
    fired_ = best <= kCrawlPathDone * first_ && best > (1 - kCrawlImprovement) * before;
    return fired_;
  }

 private:
  static constexpr std::size_t kRing = kCrawlWindow + 1;
  std::array<double, kRing> bests_{};  ///< best error after each of the last kRing iterations
  std::size_t count_ = 0;              ///< iterations seen since start()
  double first_ = 0;
  bool fired_ = false;
};

/// Shares of the time of `auto` on FC/I solved natively
/// (NativeGlobalPlan): ADMM's first stage, then semismooth Newton.
inline constexpr double kNativeAdmmShare = 0.4;
inline constexpr double kNativeNewtonShare = 0.6;

/// Ends the first ADMM stage on FC/I at its share of the time only where
/// the Newton stage after it could take a step in its own share of the
/// rest. ADMM's first step (set-up: M factorised, the pattern of
/// M + rho H H^T analysed; that matrix factorised; one iteration), read at
/// its first iteration, is a lower bound for a Newton step, whose Jacobian
/// holds M and H (FactorisationStepCost). Where no Newton step would fit,
/// ADMM keeps all the time: a second ADMM stage would pay its set-up again.
/// The run's deadline needs no watch: the stage's max_time counts its
/// set-up (registry::time_left; compute(): 0.3 s on an elastic pair of 1458
/// contacts, 2.2 s on a block of 10^4, measured).
class AdmmHandover {
 public:
  /// Plan-clock seconds: the stage starts at `now`, its share ends at
  /// `share_end`, the run's time at `deadline` (+inf: no limit).
  void start(double now, double share_end, double deadline) {
    stage_start_ = now;
    share_end_ = share_end;
    deadline_ = deadline;
    first_step_ = -1;
    fired_ = false;
  }
  /// At each iteration, the plan clock's seconds; true: end the stage.
  bool hands_over(double now) {
    if (first_step_ < 0) first_step_ = now - stage_start_;
    if (now < share_end_) return false;
    fired_ = !(first_step_ > kNativeNewtonShare * (deadline_ - now));
    return fired_;
  }
  bool fired() const { return fired_; }  ///< ended at its share, for Newton
  double first_step() const { return first_step_; }

 private:
  double stage_start_ = 0, share_end_ = 0, deadline_ = 0;
  double first_step_ = -1;  ///< negative: no iteration seen yet
  bool fired_ = false;
};

/// What the first step of a factorising stage (semismooth Newton, the
/// interior point, the proximal point's inner Newton) has cost so far in a
/// run: its set-up (each stage is a new solve: symbolic analysis, first
/// factorisation) plus one iteration, the least over the stages seen. A
/// factorisation cannot be interrupted, so a stage whose first step
/// outlasts its share of a finite budget overruns it by that step and, cut
/// after one step, seldom lowers the error: such a stage is not started
/// and its time goes to the plan's cheaper stages (the sweeps on FC/II,
/// ADMM on FC/I with elastic bodies). Every later factorising stage
/// factorises a matrix of at least the pattern measured (W's, or H's and
/// M's on FC/I; on FC/I with elastic bodies ADMM's M + rho H H^T, whose
/// pattern a Newton Jacobian holds), hence the least.
/// Measured on a sphere pile of 10^5 contacts with max_time 60 s
/// (docs/results.md, 2026-11-29): a Newton stage given 15 s took 23 s for
/// its one step, then the line search's, given about 3 s, took 27 s, and
/// the run returned after 79 s; now after 57 s, the sweeps given the rest.
class FactorisationStepCost {
 public:
  /// A factorising stage's info and the wall seconds of its call.
  void observe(const SolverInfo& info, double seconds) {
    const double solve = std::min(std::max(info.solve_seconds, 0.0), seconds);
    const double first = (seconds - solve) + solve / std::max(info.iterations, 1);
    if (info.iterations > 0) seconds_ = std::min(seconds_, first);
  }
  /// A first step timed as such (set-up to the end of the first iteration,
  /// AdmmHandover); negative: none.
  void observe_first_step(double seconds) {
    if (seconds >= 0) seconds_ = std::min(seconds_, seconds);
  }
  /// Whether one first step fits `budget` seconds (always, before any
  /// stage was measured or without a time limit).
  bool fits(double budget) const { return !measured() || !(seconds_ > budget); }
  bool measured() const { return std::isfinite(seconds_); }
  double seconds() const { return seconds_; }

 private:
  double seconds_ = std::numeric_limits<double>::infinity();  ///< infinite: none measured
};

/// Whether a proximal stage cut by its share of a finite budget keeps the
/// time left (Plan::robust_tail): the clock cut it (not its stall rule or
/// its iteration cap), it lowered the error, and one more subproblem at
/// the stage's measured cost fits in the time left. Measured
/// (docs/results.md, 2026-11-29): the sweeps that otherwise take the time
/// barely move an iterate that Newton and the interior point have left
/// (heavy-on-light stack of 10^4 contacts at 20 s: 1.3e-5 -> solved in
/// 13.6 s; sphere pile, walls); but where one subproblem outlasts what is
/// left (10^4 pile on FC/I, 0.38 s a subproblem with 0.36 s left), sweeps
/// still move it.
inline bool proximal_keeps_time(const SolverInfo& stage, double stage_seconds, double error_before,
                                double error_after, double time_left) {
  if (stage.status != Status::TimeLimit || !(error_after < error_before)) return false;
  return stage_seconds / std::max(stage.iterations, 1) < time_left;
}

/// FC/I solved natively: iterations of the first stage, ADMM in (v, r)
/// (`admm-global`: M + rho H H^T factorised once per rho, then each
/// iteration one solve with that factor). On the generated elastic scenes
/// (fem-block, fem-two-bodies, 100 to 1500 contacts, mu 0 to 2) it reached
/// 1e-8 in 29 to 52 iterations (158 with mu = 2), 2 to 5 times faster than
/// nsn-ac-global, whose every step factorises a new Jacobian
/// (docs/results.md). 200 bounds what a scene where ADMM crawls costs
/// before Newton takes over from its iterate.
inline constexpr int kNativeAdmmIterations = 200;

/// Cheap features of the problem: the plan decides on nc, the kind,
/// d nc / n, mu > 0 and the spread of W_NN; the mu range is reported with them.
struct Features {
  bool global = false;
  Index nc = 0, m = 0;
  int d = 3;
  Index n = -1;             ///< degrees of freedom (FC/I only)
  double mu_min = 0, mu_max = 0;
  /// d nc / n: above 1, W = H^T M^-1 H is singular (more contact unknowns
  /// than degrees of freedom: many contacts per body).
  double contact_ratio = 0;
  /// nnz(M^-1 H) from the sparsity of M, H, G (FC/I only).
  double inverse_mass_nonzeros = 0;
  double inverse_mass_fill = 1;  ///< nnz(M^-1 H) / nnz(H)
  /// max / min over the contacts of W_NN (FC/II, or FC/I once reduced).
  double normal_spread = 1;
  /// nnz(W) / (nnz(H) + nnz(M)) (FC/I once reduced; 0 otherwise).
  double reduced_fill = 0;
};

inline Features local_features(const LocalProblemView& p) {
  Features f;
  f.nc = p.num_contacts();
  f.m = p.size();
  f.d = p.d;
  if (f.nc > 0) {
    f.mu_min = p.mu.minCoeff();
    f.mu_max = p.mu.maxCoeff();
  }
  return f;
}

/// A message written in one buffer: each piece is copied at a cursor, the
/// buffer grows only when the first guess of its size was short. On a run
/// of one contact the report is a tenth of the solve, and appending its
/// ~35 pieces to a std::string one by one (a capacity check and a call
/// each) was most of that (callgrind, docs/results.md 2026-11-28).
class MessageWriter {
 public:
  explicit MessageWriter(std::size_t capacity) : buf_(capacity, '\0') {}
  template <class... Pieces>
  void operator()(const Pieces&... pieces) {
    (put(pieces), ...);
  }
  std::string take() && {
    buf_.resize(used_);
    return std::move(buf_);
  }

 private:
  void put(const char* text) { put(text, std::strlen(text)); }
  void put(const std::string& text) { put(text.data(), text.size()); }
  void put(const char* text, std::size_t n) {
    std::memcpy(room(n), text, n);
    used_ += n;
  }
  void put(double x) {
    char* c = room(kShortNumberChars);  // may move the buffer: before the end is taken
    used_ += std::size_t(write_short_number(c, x) - c);
  }
  template <class Integer, class = std::enable_if_t<std::is_integral_v<Integer>>>
  void put(Integer i) {
    constexpr std::size_t kDigits = 24;
    char* c = room(kDigits);
    used_ += std::size_t(std::to_chars(c, c + kDigits, i).ptr - c);
  }
  /// Where the next n characters go.
  char* room(std::size_t n) {
    if (buf_.size() - used_ < n) buf_.resize(std::max(2 * buf_.size(), used_ + n));
    return buf_.data() + used_;
  }

  std::string buf_;
  std::size_t used_ = 0;
};

/// Text, integers and numbers (numbers as printf's "%.3g", without
/// snprintf's exact conversion: on a run of one contact its numbers cost
/// more than the solve, measured) in one string.
template <class... Pieces>
std::string text(const Pieces&... pieces) {
  MessageWriter m(64);
  m(pieces...);
  return std::move(m).take();
}

inline std::string number(double x) { return text(x); }

/// The message of a run: its features and every stage's report (a JSON
/// object each). It is built on every run, hence MessageWriter.
inline std::string run_message(const Features& f, const std::vector<StageReport>& stages,
                               const std::string& note) {
  std::size_t guess = 160 + note.size();
  for (const StageReport& s : stages) guess += 160 + s.name.size() + s.solver.size() + s.why.size();
  MessageWriter m(guess);
  m("auto (nc=", f.nc, " d=", f.d, " mu=[", f.mu_min, ",", f.mu_max, "]");
  if (f.normal_spread != 1) m(" W_NN spread=", f.normal_spread);
  if (f.global) m(" n=", f.n, " d*nc/n=", f.contact_ratio, " nnz(M^-1 H)/nnz(H)=", f.inverse_mass_fill);
  if (f.reduced_fill > 0) m(" nnz(W)/nnz(H,M)=", f.reduced_fill);
  m("): stages [");
  for (std::size_t k = 0; k < stages.size(); ++k) {
    const StageReport& s = stages[k];
    m(k ? ", " : "", "{\"stage\": \"", s.name, "\", \"solver\": \"", s.solver, "\", \"seconds\": ", s.seconds,
      ", \"iterations\": ", s.iterations, ", \"error\": ", s.error, ", \"status\": \"", s.status, "\", \"why\": \"",
      s.why, "\"}");
  }
  m("]");
  if (!note.empty()) m("; ", note);
  return std::move(m).take();
}

/// What every staged plan shares: the best iterate so far (judged by the
/// FCLIB error that registry::solve recomputes), the clock and budget, the
/// stage reports, and finish(). `View` is LocalProblemView (FC/II) or
/// GlobalProblemView (FC/I solved natively: v is kept with r).
template <class View>
class StagedRun {
 protected:
  StagedRun(const View& p, const SolveRequest& req, const Features& f)
      : p_(p), req_(req), f_(f), best_(initial_reactions(req, p.size())),
        reduced_q_norm_(req.reduced_q_norm) {}

  double tol() const { return req_.common.tol; }
  bool done() const { return best_error_ <= tol() || out_of_time() || out_of_iterations() || stopped_; }
  bool out_of_time() const { return clock_.seconds() >= req_.common.max_time; }
  bool out_of_iterations() const { return iterations_ >= req_.common.max_iter; }
  int max_iter_left() const { return std::max(req_.common.max_iter - iterations_, 0); }
  /// A share of the time left (all of it when there is no time limit).
  double budget(double share) const {
    const double left = req_.common.max_time - clock_.seconds();
    return std::isfinite(left) ? std::max(share * left, 0.0) : left;
  }

  /// Runs one catalogue entry from the best iterate, keeps its result if
  /// it is better, records the stage.
  const SolveOutcome& stage(const char* label, const char* entry_name, double max_time, int max_iter,
                            std::string why, bool history = false, const char* line_search = nullptr,
                            int stall_window = 0) {
    const SolverEntry& entry = run_on(p_, entry_name, max_time, max_iter, history, line_search, stall_window);
    keep(label, entry.name, std::move(why));
    return last_;
  }

  /// One catalogue entry on `problem` (p_, or the FC/I problem that p_
  /// reduces), from the best iterate, into last_; not kept yet.
  template <class Problem>
  const SolverEntry& run_on(const Problem& problem, const char* entry_name, double max_time, int max_iter,
                            bool history = false, const char* line_search = nullptr, int stall_window = 0,
                            const Vector& v0 = Vector()) {
    StageRequest& s = stage_request(entry_name, line_search, stall_window);
    SolveRequest& req = s.req;
    req.common.tol = tol();
    // A spent budget still asks for a valid (positive) limit: one iteration.
    req.common.max_time = max_time > 0 ? max_time : 1e-9;
    req.common.max_iter = std::max(max_iter, 1);
    req.common.record_history = history || req_.common.record_history;
    if ((req_.common.callback || watch_crawl_ || watch_handover_) && !req.common.callback) {
      // The caller sees one run: iterations and seconds continue across stages.
      // The caller's callback sees every iteration, the one that ends a
      // crawling stage included; its stop is a stop of the whole run.
      req.common.callback = [this](const IterationInfo& it) {
        if (req_.common.callback) {
          IterationInfo whole = it;
          whole.iteration += iterations_;
          whole.seconds = clock_.seconds();
          if (req_.common.callback(whole)) return true;
        }
        return (watch_crawl_ && crawl_.crawls(it.error)) ||
               (watch_handover_ && handover_.hands_over(clock_.seconds()));
      };
    }
    req.r0 = best_;
    req.v0 = v0.size() ? v0 : best_v_;
    req.reduced_q_norm = reduced_q_norm_;  // FC/I: factorise M for the error scale once
    // The problem was validated by the registry::solve that called `auto`
    // (or is the reduction of one, validated once by solve_global).
    last_ = registry::solve_validated(problem, *s.entry, req);
    return *s.entry;
  }

  /// Folds the last stage's result in: iterations, history, the best
  /// iterate, the stage's report.
  void keep(const char* label, const std::string& entry_name, std::string why) {
    reduced_q_norm_ = last_.reduced_q_norm;
    last_status_ = last_.info.status;
    iterations_ += last_.info.iterations;
    setup_seconds_ += last_.info.setup_seconds;
    if (req_.common.record_history) {
      // A stage that records its starting point repeats the previous one's end.
      const auto& h = last_.info.history;
      const bool with_start = !history_.empty() && int(h.size()) > last_.info.iterations;
      history_.insert(history_.end(), h.begin() + (with_start ? 1 : 0), h.end());
    }
    // Stopped by the crawl watch, not by the caller: the plan goes on.
    if (last_status_ == Status::Stopped && watch_crawl_ && crawl_.fired()) {
      last_status_ = last_.info.status = Status::Stalled;
      why += "; stopped crawling (" + number(100 * kCrawlImprovement) + " % in " + std::to_string(kCrawlWindow) +
             " iterations)";
    }
    // Stopped by the handover watch at its share of the time, for Newton.
    if (last_status_ == Status::Stopped && watch_handover_ && handover_.fired()) {
      last_status_ = last_.info.status = Status::TimeLimit;
      why += text("; ended at its share of the time: a Newton step, at least ADMM's first (", handover_.first_step(),
                  " s), fits the rest");
    }
    if (last_status_ == Status::Stopped) stopped_ = true;
    if (std::isfinite(last_.info.error) && last_.info.error < best_error_) {
      best_error_ = last_.info.error;
      best_ = last_.r;
      best_v_ = last_.v;
      best_lambda_ = last_.lambda;
    }
    StageReport s;
    s.name = label;
    s.solver = entry_name;
    s.seconds = last_.seconds;
    s.iterations = last_.info.iterations;
    s.error = last_.info.error;
    s.status = to_string(last_status_);
    s.why = std::move(why);
    stages_.push_back(std::move(s));
  }

  /// A stage's request: the entry's default settings (copied once per run
  /// and entry configuration, not rebuilt per stage) with the stage's line
  /// search and stall window.
  struct StageRequest {
    const SolverEntry* entry;
    const char* line_search;
    int stall_window;
    SolveRequest req;
  };
  StageRequest& stage_request(const char* entry_name, const char* line_search, int stall_window) {
    const auto same = [](const char* a, const char* b) { return a == b || (a && b && !std::strcmp(a, b)); };
    for (StageRequest& s : requests_)
      if (s.entry->name == entry_name && same(s.line_search, line_search) && s.stall_window == stall_window)
        return s;
    const SolverEntry& entry = find(entry_name);
    StageRequest s{&entry, line_search, stall_window, SolveRequest()};
    s.req.settings = default_settings(entry);
    if (line_search) s.req.settings.set("line_search", std::string(line_search));
    if (stall_window > 0) s.req.settings.set("stall_window", (long long)stall_window);
    requests_.push_back(std::move(s));
    return requests_.back();
  }

  /// Whether a factorising stage may start with `max_time` seconds
  /// (FactorisationStepCost); when not, the run's report says so, naming
  /// what gets its time, and last_status_ is NotRun.
  bool factorisation_fits(const char* label, const char* entry_name, double max_time,
                          const char* instead = "the sweeps") {
    if (step_cost_.fits(max_time)) return true;
    StageReport s;
    s.name = label;
    s.solver = entry_name;
    s.error = best_error_;
    s.status = to_string(Status::NotRun);
    s.why = text("a first factorising step took ", step_cost_.seconds(), " s, more than the ", max_time,
                 " s this stage would get: its time goes to ", instead);
    stages_.push_back(std::move(s));
    last_status_ = Status::NotRun;
    return false;
  }

  SolveOutcome finish(const std::string& note = "") {
    SolveOutcome out;
    // The run ends here: its iterates move out.
    out.r = std::move(best_);
    out.v = std::move(best_v_);
    out.lambda = std::move(best_lambda_);
    out.info.error = best_error_;
    out.info.iterations = iterations_;
    out.info.history = std::move(history_);
    // A run that ends on a stage not started (NotRun: its first step would
    // not fit the time left, factorisation_fits) ends for lack of time.
    out.info.status = best_error_ <= tol()  ? Status::Converged
                      : stopped_            ? Status::Stopped
                      : out_of_time() || last_status_ == Status::NotRun ? Status::TimeLimit
                      : out_of_iterations() ? Status::MaxIterations
                      : !std::isfinite(best_error_) ? Status::NumericalError
                                                    : Status::Stalled;
    out.info.message = run_message(f_, stages_, note);
    // The stages' set-ups ran inside the plan's clock: counted once, as
    // setup (setup + solve is the run's wall time, message included, as for
    // every entry).
    out.info.setup_seconds = setup_seconds_;
    out.info.solve_seconds = std::max(clock_.seconds() - setup_seconds_, 0.0);
    out.stages = std::move(stages_);
    out.reduced_q_norm = reduced_q_norm_;
    return out;
  }

  const View& p_;
  const SolveRequest& req_;
  Features f_;
  Stopwatch clock_;
  Vector best_, best_v_, best_lambda_;
  double best_error_ = std::numeric_limits<double>::infinity();
  SolveOutcome last_;
  Status last_status_ = Status::NotRun;
  int iterations_ = 0;
  double setup_seconds_ = 0;
  bool stopped_ = false;
  std::vector<double> history_;
  std::vector<StageReport> stages_;
  std::vector<StageRequest> requests_;  ///< a few: one per entry configuration
  /// Set around the interior-point stage (Plan::interior_point): its
  /// request's callback feeds crawl_, which may stop it.
  bool watch_crawl_ = false;
  InteriorPointCrawl crawl_;
  /// Set around NativeGlobalPlan's first ADMM stage: its request's
  /// callback feeds handover_, which may end it at its share of the time.
  bool watch_handover_ = false;
  AdmmHandover handover_;
  FactorisationStepCost step_cost_;  ///< the least first step of the factorising stages so far
  double reduced_q_norm_ = -1;  ///< FC/I error scale once a stage computed it
};

/// What a Newton step on W costs in sweeps of NSGS, estimated from W's
/// pattern (J = A W + B has it) by the symbolic analysis of the LU that
/// Newton's linear solver would use (newton/linear_solvers.hpp); infinite
/// (no estimate) without a backend PatternLU.
inline double newton_step_in_sweeps(const LocalProblemView& p) {
  if constexpr (has_pattern_lu<DefaultBackend>::value) {
    typename DefaultBackend::PatternLU lu;
    if (p.W.nonZeros() > 0 && lu.analyse(p.W))
      return kNewtonStepFixedSweeps + lu.estimated_flops() / double(p.W.nonZeros());
  }
  return std::numeric_limits<double>::infinity();
}

/// max / min over the contacts of the normal diagonal entry of W (1 when
/// some W_NN is not positive: no mass ratio to read).
inline double normal_diagonal_spread(const LocalProblemView& p) {
  const Index nc = p.num_contacts();
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (Index i = 0; i < nc; ++i) {
    const double w = p.W.coeff(p.d * i, p.d * i);
    lo = std::min(lo, w);
    hi = std::max(hi, w);
  }
  return nc > 0 && lo > 0 ? hi / lo : 1.0;
}

/// The FC/I problem that a Plan's FC/II problem is the reduction of.
struct ReducedFrom {
  const GlobalProblemView* problem = nullptr;
  const GlobalReduction<DefaultBackend>* reduction = nullptr;
};

/// The staged run on FC/II.
class Plan : private StagedRun<LocalProblemView> {
 public:
  /// `from`: the FC/I problem p reduces, if any; the Newton and
  /// interior-point stages run on it when W is much denser than H and M
  /// (kNativeLinearAlgebraFill).
  Plan(const LocalProblemView& p, const SolveRequest& req, const Features& f, const ReducedFrom& from = {})
      : StagedRun(p, req, f) {
    // The starting point's own error: a stage never returns worse than it.
    // From r = 0 (no warm start) u is q: no product with W.
    best_error_ = req.r0.size() ? local_error_report(p, best_, Vector(p.W * best_ + p.q)).error
                                : local_error_report(p, best_, p.q).error;
    f_.normal_spread = normal_diagonal_spread(p);
    if (from.problem) {
      const double hm = double(from.problem->H.nonZeros() + from.problem->M.nonZeros());
      f_.reduced_fill = hm > 0 ? double(p.W.nonZeros()) / hm : 0;
      // With bilateral constraints (G, b) the FC/I entries reduce again.
      if (f_.reduced_fill >= kNativeLinearAlgebraFill && !from.problem->has_bilateral()) native_ = from;
    }
  }

  SolveOutcome run() {
    if (best_error_ <= tol()) return finish("the starting point already meets tol");
    if (f_.nc <= kTinyContacts) {
      std::string why = text("nc <= ", kTinyContacts, ": sweeps are cheapest");
      stage("nsgs", "nsgs", budget(0.5), std::min(kTinySweeps, max_iter_left()), std::move(why));
      if (done()) return finish();
      return robust_tail("nsgs did not reach tol");
    }
    if (native_.problem) {
      // Where every contact sticks (u_T = 0), Coulomb's law and the
      // associated law of the convex SOCQP (velocities in the dual cone:
      // u_N >= mu ||u_T||, here with u_T = 0) have the same solutions (De
      // Saxce & Feng 1991, the bipotential; Acary & Brogliato 2008, ch. 13):
      // stacks at rest stick, and an interior point solves the convex
      // problem in some ten iterations of FC/I's cheap linear algebra. A
      // frictionless contact has no De Saxce shift (mu ||u_T|| = 0): the two
      // laws agree there whether it slides or not, so a frictionless scene
      // is solved by this probe outright (wall, tower of the corpus with
      // mu = 0: 8.1 -> 2.9 ms, 10.6 -> 5.4 ms, docs/results.md).
      // Measured on the rigid corpus given as FC/I (docs/results.md,
      // "auto: a sticking probe"): `ipm-socqp` alone solved 16 of the 21
      // towers and walls where this runs to 1e-8, in 5 to 50 % of auto's
      // time; where a contact slides it stalls, and the plan goes on.
      native_stage("sticking", "ipm-socqp", budget(0.2), std::min(kStickingProbeIterations, max_iter_left()),
                   "W much denser than H and M: if every contact sticks or is frictionless, the convex associated "
                   "problem is Coulomb's");
      step_cost_.observe(last_.info, last_.seconds);
      if (done()) return finish();
    }
    const double e_start = best_error_;
    const SolveOutcome& warm = stage("nsgs", "nsgs", budget(0.1), std::min(kWarmSweeps, max_iter_left()),
                                     "warm start and first rate", /*history=*/true);
    if (done()) return finish();
    // Linear rate of the sweeps, per sweep, from the last ten warm sweeps
    // (full errors every 10 sweeps; the first ten are a transient).
    const std::vector<double>& h = warm.info.history;
    double rate = 1;
    if (h.size() >= 20 && h[9] > 0 && h[19] > 0 && h[19] < h[9]) rate = std::pow(h[19] / h[9], 0.1);
    else if (e_start > 0 && best_error_ < e_start) rate = std::pow(best_error_ / e_start, 1.0 / kWarmSweeps);
    // Mass ratios (a large W_NN spread) do not send the plan to the interior
    // point before Newton: full Newton steps stall within their window where
    // they crawl (heavy-on-light stacks: the interior point then runs, some
    // 12 steps later) and converge where they do not (a sphere pile with
    // mass ratio 100: 5 to 18 steps, 6x faster than the interior point
    // first; docs/results.md, 2026-11-27).
    std::string why_newton;
    if (f_.global && f_.contact_ratio > kSingularContactRatio)
      why_newton = "d*nc/n = " + number(f_.contact_ratio) + " > " + number(kSingularContactRatio) +
                   ": W singular (reactions not unique), sweeps plateau";
    // Sweeps go on, in doubling chunks, while the rate measured on the last
    // chunk predicts tol within what is left of the allowance: Gauss-Seidel
    // usually slows down as it goes, and a chunk that shows it hands over
    // to Newton early. The allowance is what three Newton steps on W cost
    // (kNewtonStepsWorthSweeping; at most kSweepsWorthContinuing), where
    // Newton runs on W.
    double allowance = kSweepsWorthContinuing;
    sweep_rate_ = rate;
    if (why_newton.empty() && !native_.problem) {
      newton_step_ = newton_step_in_sweeps(p_);
      allowance = std::min(allowance, kNewtonStepsWorthSweeping * newton_step_);
    }
    if (why_newton.empty()) {
      why_newton = continue_sweeps(allowance, "");
      if (done()) return finish();
    }
    newton(why_newton);
    if (done()) return finish();
    return robust_tail("newton stopped: " + std::string(to_string(last_status_)));
  }

 private:
  /// Semismooth Newton from the best iterate: first with full steps (no
  /// line search), which converge locally superlinearly (Qi & Sun 1993,
  /// Math. Prog. 58) once the sweeps brought r near the solution; measured
  /// on the shared set, the line search on 1/2 ||G||^2 started there often
  /// crawls with tiny steps (Capsules: 25 steps without halving the error
  /// where full steps need 5 to 11). A short stall window catches the
  /// cases where full steps do not contract; the globalised Newton (the
  /// entry's Goldstein-Price line search) then takes over from the best
  /// iterate.
  ///
  /// When the full steps stall, the interior point runs before the line
  /// search (once per run): where full steps stall on the rigid
  /// corpus (box stacks, walls, towers, sphere piles: W singular, many
  /// contacts per body) `nipm` converged in 11 to 68 iterations on 10 of 13
  /// problems, in 0.3 to 0.5x the time the Newton stages then took
  /// (docs/results.md, "auto: the interior point when full Newton steps
  /// stall"); where it stops short of tol, the line search goes on from
  /// the better of the two iterates. Full steps that stalled near tol
  /// after their fast phase (kFastPhaseReduction, kNearTolPolish) get a
  /// chunk of sweeps first.
  void newton(const std::string& why) {
    const double before = best_error_;
    newton_stage("newton-full", budget(0.5), why + "; full steps", "none", kFullStepStallWindow);
    if (done()) return;
    const Status full_steps = last_status_;
    const bool progressed = best_error_ < before;
    if (full_steps != Status::TimeLimit && best_error_ * kFastPhaseReduction <= before &&
        best_error_ <= kNearTolPolish * tol()) {
      stage("nsgs", "nsgs", budget(0.4), std::min(kBridgeProbeSweeps, max_iter_left()),
            text("full Newton steps ", to_string(full_steps), " within ", kNearTolPolish,
                 " x tol: sweeps on the degenerate contacts"));
      if (done()) return;
    }
    if (full_steps != Status::TimeLimit) {
      std::string why_ipm = std::string("full Newton steps ") + to_string(full_steps);
      // Full steps that did not lower the error at all leave the sweeps'
      // rate as the best measure of progress. The interior point that
      // would replace them costs more than the three steps' allowance the
      // sweeps were held to (kNewtonStepsWorthSweeping): once, they go on
      // while they predict tol within kInteriorPointStepsWorthSweeping
      // steps.
      if (!progressed && !sweeps_resumed_ && sweep_rate_ < 1 && std::isfinite(newton_step_)) {
        sweeps_resumed_ = true;
        const char* reason = full_steps == Status::NotRun ? "full Newton steps not run (a step would not fit); "
                                                          : "full Newton steps made no progress; ";
        why_ipm += ", " + continue_sweeps(kInteriorPointStepsWorthSweeping * newton_step_, reason,
                                          /*stop_on_slowdown=*/true);
        if (done()) return;
      }
      const bool ipm_ran_before = interior_point_ran_;
      const double before_ipm = best_error_;
      interior_point(why_ipm);
      if (done()) return;
      if (!ipm_ran_before && interior_point_ran_) sweeps_match_interior_point(before_ipm);
      if (done()) return;
    }
    newton_stage("newton", budget(0.6), std::string("full steps ") + to_string(full_steps) + ": line search",
                 "goldstein-price", kNewtonStallWindow);
  }

  /// After an interior point that gained less than kInteriorPointGain,
  /// the sweeps, if their last chunk still lowered the error, get as much
  /// time as the interior point took (at most half the time left) before
  /// the line search: neither bet has paid, and the sweeps' was paying.
  /// Gauss-Seidel on a pile goes through transients where the force
  /// network rearranges (the error stalls or rises, then falls at a linear
  /// rate) that no prediction from the earlier chunks foresees, nor the
  /// plateau test (kPlateauSlowdown). Measured (docs/results.md,
  /// 2026-12-07): on a held-out pile of 7995 contacts (seed 603, tol 1e-8,
  /// 20 s) plain NSGS rose from 1.6e-4 at sweep 2800 to 1e-3 at 5000 and
  /// fell to 1.2e-6 at 7400, while auto handed its sweeps over at 5100 to
  /// the interior point (4.6 s) and the line search (4.4 s), which gained
  /// 1.6 % between them: 8e-5 at 20 s, now converged in 17 s.
  void sweeps_match_interior_point(double before_ipm) {
    if (!(best_error_ * kInteriorPointGain > before_ipm) || !(sweep_rate_ < 1)) return;
    const double seconds = std::min(last_.seconds, budget(0.5));
    stage("nsgs", "nsgs", seconds, max_iter_left(),
          text("the interior point gained less than ", kInteriorPointGain, "x in ", last_.seconds,
               " s and the sweeps were still lowering the error: as much time for them"));
  }

  /// Sweeps in doubling chunks (from sweep_chunk_) while the rate measured
  /// on the last chunk (sweep_rate_) predicts tol within what is left of
  /// `allowance` sweeps; once it is spent, one last chunk of a Newton
  /// step's sweeps when the prediction is within a quarter of that
  /// (kLastChunkShortfall). Returns why they stopped (empty when done()).
  std::string continue_sweeps(double allowance, const std::string& reason, bool stop_on_slowdown = false) {
    bool last_chunk = false;
    for (bool first = true;; first = false) {
      const double rate = sweep_rate_;
      if (stop_on_slowdown && !first && rate_before_ < 1 &&
          !(std::log(rate) <= std::log(rate_before_) / kPlateauSlowdown))
        return "sweep rate " + number(rate_before_) + " then " + number(rate) + ": a plateau";
      const double predicted = rate < 1 ? std::log(tol() / best_error_) / std::log(rate)
                                        : std::numeric_limits<double>::infinity();
      std::string prediction = "sweep rate " + number(rate) + " predicts " + number(predicted) + " sweeps";
      if (first) prediction = reason + prediction;
      // A chunk of at most twice the prediction: where the sweeps reach a
      // plateau the next chunk's rate shows it, before the allowance is spent.
      int sweeps_now = std::min(sweep_chunk_, int(allowance));
      double share = 0.5;
      if (predicted <= allowance)
        sweeps_now = std::min(sweeps_now, std::max(kFirstChunk, int(std::ceil(kChunkOverPrediction * predicted))));
      else if (last_chunk && last_status_ == Status::TimeLimit && predicted <= newton_step_) {
        // The last chunk was cut by its share of max_time, not done, and the
        // sweeps still predict tol within one Newton step's cost: Newton
        // could not finish a step sooner, so the sweeps keep the time left.
        share = 1.0;
        sweeps_now = int(std::ceil(newton_step_));  // finite: last_chunk is set only then
        prediction += ", within one Newton step (" + number(newton_step_) +
                      "), the last chunk cut by its share of the time: the sweeps keep the rest";
      } else {
        if (last_chunk || !std::isfinite(newton_step_) || !(kLastChunkShortfall * predicted <= newton_step_))
          return prediction + " (allowance " + number(allowance) + "): sweeps too slow";
        last_chunk = true;  // allowance spent, tol near: one Newton step's sweeps
        sweeps_now = int(std::ceil(newton_step_));
        prediction += ", allowance spent, a Newton step costs " + number(newton_step_) + ": last chunk";
      }
      const double before = best_error_;
      stage("nsgs", "nsgs", budget(share), std::min(sweeps_now, max_iter_left()), std::move(prediction));
      if (done()) return std::string();
      const int sweeps = std::max(last_.info.iterations, 1);
      allowance -= sweeps;
      rate_before_ = sweep_rate_;
      sweep_rate_ = before > 0 && best_error_ < before ? std::pow(best_error_ / before, 1.0 / sweeps) : 1;
      if (sweep_chunk_ < (1 << 29)) sweep_chunk_ *= 2;
    }
  }
  double sweep_rate_ = 1;              ///< per sweep, measured on the last chunk of sweeps
  double rate_before_ = 1;             ///< the same on the chunk before
  int sweep_chunk_ = kFirstChunk;      ///< sweeps of the next chunk
  double newton_step_ = std::numeric_limits<double>::infinity();  ///< a Newton step on W, in sweeps
  bool sweeps_resumed_ = false;

  /// Semismooth Newton on Alart-Curnier: on FC/II (`nsn-ac`), or on the
  /// FC/I problem it reduces when that is the cheaper form (`nsn-ac-global`).
  /// A Newton stage is deterministic: from the iterate it last stalled
  /// from, with the same settings and no more budget, it would stall again
  /// in the same steps (measured: a sphere pile of 3000 ran the line search
  /// twice from the interior point's iterate, 1.2 s of 9.4, docs/results.md),
  /// and from one nearly as good it nearly does; so it is skipped until the
  /// error has halved from where it last started and stalled
  /// (kNewtonRestartGain).
  void newton_stage(const char* label, double max_time, std::string why, const char* line_search,
                    int stall_window) {
    double& stalled_from =
        std::strcmp(label, "newton-full") == 0 ? full_steps_stalled_from_ : line_search_stalled_from_;
    if (best_error_ > kNewtonRestartGain * stalled_from) {
      last_status_ = Status::Stalled;
      return;
    }
    const char* entry = native_.problem ? "nsn-ac-global" : "nsn-ac";
    if (!factorisation_fits(label, entry, max_time)) return;
    const double start = best_error_;
    const int max_iter = std::min(kNewtonMaxIter, max_iter_left());
    if (native_.problem)
      native_stage(label, entry, max_time, max_iter, std::move(why), line_search, stall_window);
    else
      stage(label, entry, max_time, max_iter, std::move(why), false, line_search, stall_window);
    step_cost_.observe(last_.info, last_.seconds);
    if (last_status_ == Status::Stalled) stalled_from = start;
  }
  /// The best error when the full steps last started and stalled (infinite: never).
  double full_steps_stalled_from_ = std::numeric_limits<double>::infinity();
  double line_search_stalled_from_ = std::numeric_limits<double>::infinity();  ///< the same for the line search

  /// A stage on the FC/I problem (native_), from the best r and the v it
  /// determines (v = M^-1 (H r + f)); its r is judged on FC/II like every
  /// stage's, so that the best iterate is chosen by one measure. The FC/I
  /// velocities are not kept: solve_global recovers v from the final r.
  void native_stage(const char* label, const char* entry_name, double max_time, int max_iter, std::string why,
                    const char* line_search = nullptr, int stall_window = 0) {
    reduced_q_norm_ = native_.reduction->free_velocity_norm();  // the FC/I error scale, known
    const SolverEntry& entry = run_on(*native_.problem, entry_name, max_time, max_iter, false, line_search,
                                      stall_window, native_.reduction->velocity(best_));
    last_.info.error = local_error(p_, last_.r);
    // The entry's FC/I error met tol, its r's FC/II error (v recomputed
    // from r) did not: the stage did not converge by the plan's measure.
    if (last_.info.status == Status::Converged && !(last_.info.error <= tol())) last_.info.status = Status::Stalled;
    last_.v = Vector();
    last_.lambda = Vector();
    keep(label, entry.name, std::move(why) + "; on FC/I: nnz(W)/nnz(H,M) = " + number(f_.reduced_fill));
  }

  /// The nonsmooth interior point (`nipm`; Nguyen & Armand, NIPM,
  /// docs/references.md), from the centre of the cones. Measured, its
  /// iteration count hardly depends on how degenerate the problem is, where
  /// semismooth Newton crawls when W is singular with many contacts per body
  /// (the reactions are not unique) or badly scaled by mass ratios: where
  /// nipm alone converges on the rigid corpus it takes 3 to 68 iterations
  /// (box stacks of 1000 contacts: 20, 0.14 s, where the Newton stages
  /// stall at 1e-2 and the proximal stage needs 3 s), so it gets 100. Where
  /// it stops short of tol, its iterate is a good start for Newton on
  /// heavy-on-light stacks (1e-5 after 100 iterations, then 2 to 4 Newton
  /// steps to 1e-10); starting the next stages from the iterate before it
  /// instead cost those 10 s and more (measured, not kept). Frictionless
  /// contacts included (ipm/form_common.hpp: heavy-on-light with mu = 0,
  /// 52 -> 28 ms where the line search took over before); a share of the
  /// budget so that the tail keeps the rest. It ends early when it crawls
  /// (InteriorPointCrawl): the stages after it go on from its best iterate.
  /// Runs at most once (a second run would start from the same centre). For
  /// the same reason its share is a soft limit (nipm's soft_time,
  /// ipm/soft_time.hpp: soft_time_extends): it goes on past it while
  /// its rate predicts tol within a few iterations and half the time left.
  /// Measured (docs/results.md, 2026-11-29): a held-out tower of 4872
  /// contacts, whose 24 iterations (4.7-5.8 s) the share cut at 17 to 23
  /// when the machine was slower.
  void interior_point(const std::string& why) {
    const double share = budget(0.3);
    if (interior_point_ran_ || !factorisation_fits("ipm", "nipm", share)) return;
    interior_point_ran_ = true;
    const int max_iter = std::min(kInteriorPointIterations, max_iter_left());
    const bool soft = std::isfinite(share);  // no time limit: nothing to overrun
    stage_request("nipm", nullptr, 0).req.settings.set("soft_time", soft ? std::max(share, 1e-9) : 0.0);
    const double max_time = soft ? budget(1.0) : share;
    watch_crawl_ = true;
    crawl_.start();
    if (native_.problem)
      native_stage("ipm", "nipm", max_time, max_iter, why + ": the interior point");
    else
      stage("ipm", "nipm", max_time, max_iter, why + ": the interior point");
    if (last_.info.message.find(ipm::kPastSoftTimeNote) != std::string::npos)
      stages_.back().why += "; went on past its share of the time: its rate predicted tol";
    watch_crawl_ = false;
    step_cost_.observe(last_.info, last_.seconds);
  }
  bool interior_point_ran_ = false;
  ReducedFrom native_;  ///< set when the Newton and IPM stages run on FC/I


  /// After Newton stalled or NSGS did not finish: sweeps, Newton once more
  /// from what they reached, the interior point (if it has not run), the
  /// proximal point method, then sweeps until the budget is spent.
  SolveOutcome robust_tail(const std::string& why) {
    const double before = best_error_;
    stage("nsgs", "nsgs", budget(0.4), std::min(kBridgeProbeSweeps, max_iter_left()), why);
    if (done()) return finish();
    if (best_error_ < before) {
      stage("nsgs", "nsgs", budget(0.4), std::min(kBridgeSweeps - kBridgeProbeSweeps, max_iter_left()),
            "the first sweeps lowered the error: the rest of the bridge");
      if (done()) return finish();
    }
    newton(best_error_ < before ? "sweeps improved the iterate: Newton again"
                                : "sweeps did not improve: Newton from the best iterate");
    if (done()) return finish();
    interior_point("Newton not done in its shares of the budget");
    if (done()) return finish();
    // Newton stalls twice where W is singular or badly scaled (many contacts
    // per body, mass ratios): each proximal subproblem FC/II(W + alpha I,
    // q - alpha r_k) is strongly monotone and Newton solves it (Rockafellar
    // 1976; Acary, Bremond & Huber 2018, docs/references.md). Measured:
    // heavy-on-light stacks that nsn-ac leaves at 3e-3 are solved. After
    // the second Newton, not before: from the sweeps' iterate Newton often
    // converges (a sphere pile of 1000: 0.7 s) where the proximal stage
    // takes longer.
    if (factorisation_fits("proximal", "ppa", budget(0.6))) {
      const double before_proximal = best_error_;
      stage("proximal", "ppa", budget(0.6), std::min(find("ppa").default_max_iter, max_iter_left()),
            "Newton stalled twice: regularised subproblems W + alpha I");
      step_cost_.observe(last_.info, last_.seconds);
      if (done()) return finish();
      // Cut by its share of the budget while still lowering the error: it
      // keeps the time left where one more subproblem fits; otherwise the
      // sweeps take it.
      if (proximal_keeps_time(last_.info, last_.seconds, before_proximal, best_error_, budget(1.0))) {
        stage("proximal", "ppa", budget(1.0), std::min(find("ppa").default_max_iter, max_iter_left()),
              "still lowering the error when its share of the budget ran out");
        if (done()) return finish();
      }
    }
    stage_request("nsgs", nullptr, 0).req.settings.set("give_up_sweeps", (long long)kFinalSweepsGiveUp);
    stage("nsgs", "nsgs", budget(1.0), max_iter_left(), "the rest of the budget to the robust sweeps");
    return finish();
  }
};

/// The staged run on FC/I in (v, r), W never formed (see the top of the
/// file: an elastic body's W is dense). Starts from the request's r0, v0
/// when given.
class NativeGlobalPlan : private StagedRun<GlobalProblemView> {
 public:
  NativeGlobalPlan(const GlobalProblemView& p, const SolveRequest& req, const Features& f)
      : StagedRun(p, req, f) {
    best_v_ = req.v0.size() ? req.v0 : Vector(Vector::Zero(p.num_dofs()));
  }

  SolveOutcome run() {
    const std::string why = "nnz(M^-1 H) = " + number(f_.inverse_mass_fill) +
                            " nnz(H): M^-1 couples the dofs, W would be dense; FC/I in (v, r)";
    // ADMM gets all the time, and ends at its share only where a Newton step
    // fits the rest (AdmmHandover).
    handover_.start(clock_.seconds(), clock_.seconds() + budget(kNativeAdmmShare), req_.common.max_time);
    watch_handover_ = true;
    stage("admm-global", "admm-global", budget(1.0), std::min(kNativeAdmmIterations, max_iter_left()),
          why + ", one factorisation per rho");
    watch_handover_ = false;
    // Timed at its first iteration: the factorisation of M + rho H H^T in
    // it, not spread over the stage's iterations as observe() would.
    step_cost_.observe_first_step(handover_.first_step());
    if (done()) return finish();
    // ADMM's first step (compute: M factorised, the pattern of M + rho H H^T
    // analysed; then one iteration) is a lower bound for a Newton step on
    // FC/I, whose Jacobian holds M and H: a step that would not fit is not
    // started (FactorisationStepCost). Measured (docs/results.md,
    // 2026-11-29): an elastic pair of 1458 contacts at max_time 1 s returned
    // after 2.6 s, one Newton step of 1.8 s started with 0.1 s left.
    if (newton_global(budget(kNativeNewtonShare), std::string("admm-global ") + to_string(last_status_) +
                                       ": semismooth Newton from its iterate")) {
      if (done()) return finish();
      if (last_status_ == Status::TimeLimit) {
        // Cut by its share of the budget, not by its stall window: Newton was
        // still converging (measured: a 10^4-contact elastic block needs 5
        // steps of 10 s each), so it keeps the time left.
        newton_global(budget(1.0), "still converging when its share of the budget ran out");
        if (done() || last_status_ == Status::TimeLimit) return finish();
      }
      if (factorisation_fits("ipm", "nipm", budget(1.0), "nothing: the run ends"))
        stage("ipm", "nipm", budget(1.0), max_iter_left(),
              std::string("newton ") + to_string(last_status_) + ": the interior point for the time left");
      return finish();
    }
    // No Newton step fits: ADMM, whose steps are cheap once factorised, goes
    // on from its best iterate where its first step fits the time left, to
    // the run's deadline (its set-up counted: no share to hand over at).
    if (factorisation_fits("admm-global", "admm-global", budget(1.0), "nothing: the run ends"))
      stage("admm-global", "admm-global", budget(1.0), max_iter_left(),
            "no Newton step fits the time left: ADMM goes on from its best iterate");
    return finish();
  }

 private:
  /// A Newton stage on FC/I where its first step fits `max_time`; false
  /// when it was not started.
  bool newton_global(double max_time, std::string why) {
    if (!factorisation_fits("newton-global", "nsn-ac-global", max_time, "admm-global, if its step fits"))
      return false;
    stage("newton-global", "nsn-ac-global", max_time, std::min(kNewtonMaxIter, max_iter_left()), std::move(why),
          false, nullptr, kNewtonStallWindow);
    step_cost_.observe(last_.info, last_.seconds);
    return true;
  }
};

inline SolveOutcome solve_local(const LocalProblemView& p, const SolveRequest& req) {
  return Plan(p, req, local_features(p)).run();
}

/// FC/I features, from the data as given (nothing factorised).
inline Features global_features(const GlobalProblemView& p) {
  Features f;
  f.global = true;
  f.nc = p.num_contacts();
  f.m = p.size();
  f.d = p.d;
  f.n = p.num_dofs();
  if (f.nc > 0) {
    f.mu_min = p.mu.minCoeff();
    f.mu_max = p.mu.maxCoeff();
  }
  f.contact_ratio = f.n > 0 ? double(f.m) / double(f.n) : 0;
  f.inverse_mass_nonzeros = inverse_mass_times_h_nonzeros(p);
  f.inverse_mass_fill = p.H.nonZeros() > 0 ? f.inverse_mass_nonzeros / double(p.H.nonZeros()) : 1.0;
  return f;
}

/// Whether forming W = H^T M^-1 H pays (see kInverseMassFill).
inline bool reduction_pays(const Features& f) {
  return f.inverse_mass_fill <= kInverseMassFill || f.inverse_mass_nonzeros <= kSmallInverseMassProduct;
}

/// FC/I: reduced once (W = H^T M^-1 H) when W stays sparse, the plan runs on
/// FC/II and v (and the bilateral multipliers) are recovered from r; the
/// reduction's time counts against max_time. Otherwise solved natively.
inline SolveOutcome solve_global(const GlobalProblemView& p, const SolveRequest& req) {
  const Features f = global_features(p);
  if (!reduction_pays(f)) return NativeGlobalPlan(p, req, f).run();
  Stopwatch clock;
  GlobalReduction<DefaultBackend> reduction(p);
  const LocalProblemView local(reduction.local());
  validate(local);  // once: the stages skip it (StagedRun::stage)
  SolveRequest inner = req;
  inner.common.max_time = time_left(req.common.max_time, clock.seconds());
  SolveOutcome out = Plan(local, inner, f, ReducedFrom{&p, &reduction}).run();
  out.v = reduction.velocity(out.r);
  if (p.has_bilateral()) out.lambda = reduction.multipliers(out.r);
  out.info.setup_seconds += reduction.seconds();
  out.reduced_q_norm = reduction.free_velocity_norm();  // the error scale, already known
  return out;
}

}  // namespace auto_detail

inline void add_auto_solvers(std::vector<SolverEntry>& v) {
  SolverEntry e("auto", "auto",
                "staged default: NSGS warm start, semismooth Newton (nsn-ac), NSGS/Newton/interior point (nipm)/proximal point "
                "fallback (nipm first with mass ratios); "
                "each stage from the best iterate (rigid FC/I with W much denser than H and M: ipm-socqp sticking probe, "
                "Newton and nipm on FC/I; FC/I with a dense W: admm-global, nsn-ac-global, then nipm)");
  e.default_max_iter = 1000000;
  e.solve_local = auto_detail::solve_local;
  e.solve_global = auto_detail::solve_global;
  v.push_back(std::move(e));
}

}  // namespace registry
}  // namespace fcsolve
