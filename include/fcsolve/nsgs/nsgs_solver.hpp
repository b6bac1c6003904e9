// Nonsmooth (block) Gauss-Seidel for FC/II(W, q, mu) (Jean & Touzot 1988;
// Moreau 1994; Acary, Bremond & Huber 2018, sec. 4.3 [NSGS-*], [PSOR-*]).
//
// A sweep visits every contact a and solves its one-contact problem
//   u^a = W^{aa} r^a + qhat^a,  qhat^a = q^a + sum_{b != a} W^{ab} r^b,
//   K^a* ∋ u^a + g(u^a) ⊥ r^a ∈ K^a,
// with the latest r^b (Gauss-Seidel), by the local solver policy
// (local/*.hpp), then relaxes r^a <- omega r^a_new + (1 - omega) r^a (PSOR).
//
// Storage with row access (DenseStorage, BlockSparseStorage) forms qhat^a
// from the block row of W; SparseStorage (compressed columns) keeps
// u = W r + q up to date with column updates u += W^{.a} (r^a_new - r^a).
// The sweep allocates nothing (proved by the EIGEN_RUNTIME_NO_MALLOC test).
//
// ContactOrdering::Coloured visits the contacts colour by colour
// (nsgs/contact_colouring.hpp) and updates the contacts of one colour with
// an OpenMP `parallel for` (static schedule, settings().threads threads).
// They read only reactions of other colours, and every sum over contacts is
// taken over fixed chunks of contacts whose sums are added in order, so the
// iterates do not depend on the number of threads. Without OpenMP the same
// loop runs serially. Column-update storage adds the colour's columns to u after the
// parallel loop (two contacts of a colour may touch the same rows of u).
// Block-sparse storage keeps a second copy of W, q and the local data
// renumbered so that each colour is contiguous (SlotLayout): a colour then
// streams its rows of W instead of reading every k-th one.
//
// When three successive sweeps shrink the change ||dr|| by one factor rho
// (linear convergence along one mode, typical of a few strongly coupled
// contacts), r is extrapolated by Aitken's rule r + rho / (1 - rho) dr
// (Aitken 1926); the step is kept only if its full error is below rho
// times the current error estimate (settings().extrapolate; Extrapolation below).
//
// Success is declared only on the full FCLIB error (problem/error.hpp) of the
// returned r: error = ||F_nat(r)|| / ||q|| <= tol. When the solve fails
// (iteration or time budget, callback, NaN) r is the iterate with the
// smallest full error seen, and info().error is that error.
#pragma once

#include <fcsolve/core/compiler.hpp>
#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/solver_contract.hpp>
#include <fcsolve/core/solver_settings.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/local/enumerative.hpp>
#include <fcsolve/local/one_contact.hpp>
#include <fcsolve/nsgs/contact_colouring.hpp>
#include <fcsolve/nsgs/nsgs_settings.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/validate.hpp>
#include <fcsolve/storage/storage.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace fcsolve {
namespace detail {
template <class S>
struct is_dense_storage : std::false_type {};
template <int D, class Scalar>
struct is_dense_storage<DenseStorage<D, Scalar>> : std::true_type {};
}  // namespace detail

/// The default local solver is the exact one (local/enumerative.hpp, fast
/// mode: closed-form take-off and stick, Newton on the sliding direction):
/// on the shared FCLIB problems, the fewest sweeps at a few times the cost
/// of one projection step per contact (bench_nsgs).
template <class Cone, class Storage, class LocalSolver = local::Enumerative<Cone>>
class Nsgs {
  static_assert(is_cone_v<Cone>, "Cone must be a cone policy (cone/cones.hpp)");
  static_assert(is_storage_v<Storage>, "Storage must be a storage policy (storage/storage.hpp)");
  static_assert(Storage::block_dim == Cone::dim, "Storage blocks must match the cone dimension");
  static_assert(local::is_local_solver_v<LocalSolver>,
                "LocalSolver must be a local solver policy (local/one_contact.hpp)");
  static_assert(std::is_same_v<typename LocalSolver::Cone, Cone>,
                "LocalSolver must be instantiated on the same cone");

 public:
  static constexpr int d = Cone::dim;
  using Vec = typename Cone::Vec;
  using Mat = SmallMatrix<d>;
  using Settings = NsgsSettings<typename LocalSolver::Settings>;
  using DataVector =
      std::vector<typename LocalSolver::Data, Eigen::aligned_allocator<typename LocalSolver::Data>>;

  Nsgs() = default;
  explicit Nsgs(const Settings& s) : settings_(s) {}

  /// Settings used by the next solve(). The local solver's settings are
  /// read by compute() too (cached per-contact data): call compute() again
  /// after changing them.
  Settings& settings() { return settings_; }
  const Settings& settings() const { return settings_; }
  const SolverInfo& info() const { return info_; }
  const Storage& storage() const { return storage_; }
  /// The colouring of the Coloured ordering (computed by compute() when
  /// that ordering is set, else by the first solve() that uses it).
  const ContactColouring& colouring() {
    if (!problem_) throw UsageError("Nsgs::colouring() called before compute()");
    prepare_colouring();
    return *colouring_;
  }

  /// Stores W in the storage policy and caches each diagonal block with the
  /// local solver's per-contact data. The viewed data must outlive *this.
  /// Throws InvalidProblem on inconsistent data.
  Nsgs& compute(const LocalProblemView& p) {
    Stopwatch clock;
    problem_.emplace(validated(p, d));
    storage_.compute(p.W);
    const Index nc = p.num_contacts(), m = p.size();
    data_.resize(static_cast<std::size_t>(nc));
    for (Index a = 0; a < nc; ++a)
      data_[a] = LocalSolver::prepare(storage_.diagonal_block(a), p.mu[a], settings_.local);
    order_.resize(static_cast<std::size_t>(nc));
    frozen_.assign(static_cast<std::size_t>(nc), 0);
    colouring_.reset();
    if (settings_.ordering == ContactOrdering::Coloured) prepare_colouring();
    u_.resize(m);
    work_.resize(m);
    best_.resize(m);
    previous_.resize(m);
    trial_.resize(m);
    start_.resize(m);
    scale_ = error_scale(p.q.norm());
    decoupled_ = no_coupling(p.W);
    info_ = SolverInfo();
    info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// One sweep over the contacts in their natural order from the caller's
  /// iterate: r in/out, u = W r + q on entry and on exit. The hybrid
  /// Newton's fallback (newton/newton_solver.hpp) sweeps its own iterate
  /// with it. Honours omega and freezing; allocates nothing.
  void sweep(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    if (!problem_) throw UsageError("Nsgs::sweep() called before compute()");
    const LocalProblemView& p = *problem_;
    if constexpr (!Storage::row_access) u_ = u;
    SweepResult out;
    for (Index a = 0; a < p.num_contacts(); ++a) record(a, update_contact(a, r, storage_, p.q, data_), out);
    if constexpr (Storage::row_access) {
      storage_.multiply(r, u);
      u += p.q;
    } else {
      u = u_;
    }
  }

  /// Re-reads q and mu of the viewed problem after the caller changed them
  /// in place, W unchanged: re-prepares the local data and the error scale
  /// and keeps W's storage. The fixed points (fixed_point/) change the
  /// threshold (in mu's place) and q of their subproblems every outer
  /// iteration. Allocates nothing.
  Nsgs& refresh_q_and_mu() {
    if (!problem_) throw UsageError("Nsgs::refresh_q_and_mu() called before compute()");
    const LocalProblemView& p = *problem_;
    for (Index a = 0; a < p.num_contacts(); ++a)
      data_[a] = LocalSolver::prepare(storage_.diagonal_block(a), p.mu[a], settings_.local);
    if constexpr (use_slots) {
      if (colouring_) {
        const std::vector<Index>& contacts = colouring_->contacts;
        for (Index i = 0; i < static_cast<Index>(contacts.size()); ++i) {
          slots_.q.template segment<d>(i * d) = p.q.template segment<d>(contacts[i] * d);
          slots_.data[i] = data_[contacts[i]];
        }
      }
    }
    scale_ = error_scale(p.q.norm());
    return *this;
  }

  /// Solves from the warm start r (overwritten by the solution) and writes
  /// u = W r + q. Returns info().
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    Stopwatch clock;
    check_solve_arguments(r, u);
    const Settings& s = settings_;
    reset_info();

    const ContactOrdering ordering = s.ordering;
    start_ordering(r);

    const LocalProblemView& p = *problem_;
    // LoadAscending starts again from r once the loads have formed
    bool sort_pending = ordering == ContactOrdering::LoadAscending;
    if (sort_pending) start_ = r;
    double error = start_error(r);  // also sets u_ = W r + q (column-update storage)
    best_ = r;
    best_error_ = error;
    if (!start_pending_ && !std::isfinite(error)) return finish(r, u, Status::NumericalError, clock);
    if (error <= s.tol) return finish(r, u, Status::Converged, clock);

    TimeCheck time_check;
    Extrapolation extrapolation;
    const int every = std::max(s.error_every, 1);
    double ratio = 1;  // full error / relative change, at the last full evaluation
    Progress progress{error, 0, ordering == ContactOrdering::ShuffledEachSweep};
    Status status = Status::MaxIterations;
    // A kept Aitken step leaves an error whose decay no longer follows the
    // change (the estimate's ratio is stale): the next sweep evaluates the
    // full error (3-contact cube of bench_nsgs: converged one sweep sooner).
    bool after_aitken = false;
    for (int sweep_no = 1; sweep_no <= s.max_iter; ++sweep_no) {
      FCSOLVE_NO_MALLOC_BEGIN();
      if (progress.reshuffle) reshuffle(ordering);
      const bool armed = s.extrapolate && extrapolation.armed();
      if (armed) previous_ = r;
      const SweepResult sw = ordering == ContactOrdering::Coloured ? coloured_sweep(r) : ordered_sweep(r);
      const double rho = extrapolation.observe(std::sqrt(sw.change2));
      const double change = std::sqrt(sw.change2 / std::max(r.squaredNorm(), 1e-300));
      const bool last = sweep_no == s.max_iter;
      // Without coupling between contacts one sweep of exact local solves is
      // the solution: check it at once (the light test has no ratio yet).
      const bool full = sweep_no % every == 0 || change * ratio <= s.tol || last ||
                        !std::isfinite(sw.change2) || (decoupled_ && sweep_no == 1) || after_aitken;
      after_aitken = false;
      if (full) {
        error = std::isfinite(sw.change2) ? full_error(r) : sw.change2;
        ratio = change > 0 ? error / change : ratio;
      }
      FCSOLVE_NO_MALLOC_END();
      info_.iterations = sweep_no;
      if (!std::isfinite(sw.change2) || (full && !std::isfinite(error))) {
        status = Status::NumericalError;
        break;
      }
      double estimate = full ? error : change * ratio;
      bool exact = full;  // estimate is a full error
      if (full) {
        const Status verdict = judge_full_error(r, error, sw, change, ratio, sweep_no, progress);
        if (verdict != Status::MaxIterations) {
          // the sweep that ends the solve is recorded too: a solve that
          // converges on its first sweep (uncoupled contacts) has a history
          if (s.record_history) info_.history.push_back(error);
          status = verdict;
          break;
        }
      } else if (armed && extrapolation.armed() && rho > 0 &&
                 aitken_step_converges(r, rho, extrapolation, estimate, exact, error)) {
        if (s.record_history) info_.history.push_back(error);
        status = Status::Converged;
        break;
      } else if (exact) {  // an Aitken step was kept but has not converged
        after_aitken = true;
      }
      if (sort_pending && ((full && error <= kLoadSortError) || sweep_no >= kLoadSortSweeps)) {
        sort_pending = false;
        sort_by_load(r);
        r = start_;
        error = start_error(r);
        std::fill(frozen_.begin(), frozen_.end(), 0);
        extrapolation = Extrapolation{};
        ratio = 1;
        progress = Progress{error, sweep_no, false};
        after_aitken = false;
        note("contacts sorted by load after sweep " + std::to_string(sweep_no) + "; started again");
      }
      if (s.record_history) info_.history.push_back(estimate);
      if (s.callback &&
          callback_requests_stop(s.callback, IterationInfo{sweep_no, estimate, exact, clock.seconds()})) {
        status = Status::Stopped;
        break;
      }
      if (time_check.due(p.num_contacts()) && clock.seconds() > s.max_time) {
        status = Status::TimeLimit;
        break;
      }
    }
    if (status != Status::Converged && status != Status::NumericalError) keep_if_best(r, full_error(r));
    if (status != Status::Converged) settle_pending_start();
    return finish(r, u, status, clock);
  }

 private:
  /// Resets info() for a new solve; compute()'s setup time stays.
  void reset_info() {
    const double setup = info_.setup_seconds;
    info_ = SolverInfo();
    info_.setup_seconds = setup;
    if (settings_.record_history)
      info_.history.reserve(std::size_t(std::min(settings_.max_iter, 100000)) + 1);
  }

  /// A new random order of the contacts (or of the colours) for the next sweep.
  void reshuffle(ContactOrdering ordering) {
    if (ordering == ContactOrdering::Coloured) std::shuffle(colour_order_.begin(), colour_order_.end(), rng_);
    else std::shuffle(order_.begin(), order_.end(), rng_);
  }

  /// LoadAscending: the sweeps run in the natural order until the full
  /// error is below kLoadSortError (or for kLoadSortSweeps sweeps), when
  /// the loads r_N have formed; then the contacts are sorted by them and the
  /// solve starts again from the caller's r in that order, kept to the end.
  /// Starting again, not going on: on a pile of 10^4 spheres (FC/II, seed
  /// 903, tol 1e-6) going on from the natural order's iterate took 29 000 to
  /// 73 000 sweeps (its reactions had formed along the natural order's
  /// paths), starting again 9472 (docs/results.md).
  static constexpr double kLoadSortError = 1e-2;
  static constexpr int kLoadSortSweeps = 1000;
  /// Contacts by increasing r_N (component 0 of every cone), ties by index:
  /// std::sort does not allocate.
  void sort_by_load(const Eigen::Ref<const Vector>& r) {
    std::sort(order_.begin(), order_.end(), [&r](Index a, Index b) {
      const double ra = r[a * d], rb = r[b * d];
      return ra < rb || (ra == rb && a < b);
    });
  }

  struct SweepResult {
    double change2 = 0;  ///< ||r_new - r_old||^2 over the visited contacts
    Index skipped = 0;   ///< frozen contacts not visited
  };

  /// One contact's update: its local solve from the current r (or u_).
  struct ContactUpdate {
    Vec dr = Vec::Zero();  ///< r^a_new - r^a_old (zero when skipped or failed)
    double dr2 = 0;        ///< ||dr||^2
    int failures = 0;      ///< local solves that did not converge or gave non-finite values
    bool skipped = false;  ///< frozen: not visited
  };

  /// Solves contact a's one-contact problem with the latest reactions and
  /// writes r^a; reads r (row access) or u_^a, writes only r^a and
  /// frozen_[a], so contacts that share no block can run at the same time.
  /// (W, q, data): the problem in the contacts' numbering, or the slot
  /// layout of the coloured sweep. Always inlined: it is the sweep's whole
  /// body, and in large translation units GCC had left it out of line (a
  /// call and its result through memory a visit: a 3-contact solve 1.95 ->
  /// 2.03 us, bench_nsgs nsgs-small).
  template <class QVector>
  FCSOLVE_ALWAYS_INLINE ContactUpdate update_contact(Index a, Eigen::Ref<Vector> r, const Storage& W,
                               [[maybe_unused]] const QVector& q, const DataVector& data) {
    const Settings& s = settings_;
    ContactUpdate out;
    if (s.freezing > 0 && frozen_[a] > 0) {
      --frozen_[a];
      out.skipped = true;
      return out;
    }
    auto ra = r.template segment<d>(a * d);
    const Vec r_old = ra;
    Vec qhat;  // q^a + sum_{b != a} W^{ab} r^b
    if constexpr (Storage::row_access) {
      qhat = q.template segment<d>(a * d) + W.off_diagonal_row_product(a, r);
    } else {
      qhat = u_.template segment<d>(a * d);
      qhat.noalias() -= W.diagonal_block(a) * r_old;
    }
    Vec r_new = r_old;
    const local::LocalResult lr = LocalSolver::solve(data[a], qhat, r_new, s.local);
    if (!lr.converged) ++out.failures;
    if (!local::OneContact<Cone>::is_finite(r_new)) {  // keep the old value, count it as a failure
      ++out.failures;
      return out;
    }
    if (s.omega != 1.0) r_new = s.omega * r_new + (1 - s.omega) * r_old;
    out.dr = r_new - r_old;
    ra = r_new;
    out.dr2 = out.dr.squaredNorm();
    if (s.freezing > 0 &&
        out.dr2 <= s.freeze_tol * s.freeze_tol * std::max(r_new.squaredNorm(), 1e-300))
      frozen_[a] = s.freezing;
    return out;
  }

  /// Adds contact a's update to the sweep's sums and, for column-update
  /// storage, to u_.
  void record(Index a, const ContactUpdate& c, SweepResult& out) {
    local_failures_ += c.failures;
    if (c.skipped) ++out.skipped;
    out.change2 += c.dr2;
    if constexpr (!Storage::row_access) {
      if (c.dr2 > 0) storage_.add_block_column(a, c.dr, u_);
    }
  }

  /// When to read the clock for max_time: once kContacts contacts have been
  /// visited since the solve began or the clock was last read (after the
  /// first sweep from 64 contacts on). On 3 contacts a read every sweep was
  /// 3% of the solve's instructions (callgrind, bench_nsgs nsgs-small); the
  /// budget is overrun by at most kContacts local solves (about 10 us).
  struct TimeCheck {
    static constexpr Index kContacts = 64;
    Index since_read = 0;
    bool due(Index contacts_swept) {
      since_read += contacts_swept;
      if (since_read < kContacts) return false;
      since_read = 0;
      return true;
    }
  };

  /// Aitken's extrapolation (Aitken 1926) along the sweeps' change: when
  /// successive changes ||dr_k|| shrink by one factor rho, the sweep
  /// converges linearly along one dominant mode (block Gauss-Seidel on a
  /// few strongly coupled contacts: rho = 0.25 on the 3-contact cube of
  /// bench_nsgs), and the remaining error is about rho / (1 - rho) dr_k.
  /// Tried when three successive ratios agree to 2%, at the cost of one
  /// error evaluation (about one sweep's products with W); the result is
  /// kept only if its full FCLIB error is below rho times the current
  /// estimate (change times the last full error / change ratio), i.e. only
  /// if it beats the sweep it costs: on a 500-contact FEM block (rho about
  /// 0.3) a step kept for merely lowering the error moved the iterate off
  /// the sweep's mode and the solve took one sweep more. Either way the
  /// ratio history restarts, and after a rejected try the next one waits
  /// for twice as many agreeing ratios, so a problem where it never pays
  /// spends O(log sweeps) evaluations on it. Success is still declared on a
  /// full error only. Measured on the shared FCLIB problems (tol 1e-8): no
  /// problem needs more sweeps, the small coupled ones (Rover*, NESpheres,
  /// Confeti) 20-45% fewer (docs/results.md).
  struct Extrapolation {
    static constexpr double kAgree = 0.02, kMaxRatio = 0.95;
    double last = 0;        ///< ||dr|| of the previous sweep, 0: none yet
    double ratios[2] = {};  ///< the last two ||dr_k|| / ||dr_{k-1}||
    int count = 0;          ///< ratios seen since the last restart
    int needed = 2;         ///< ratios to see before a try; doubled by back_off()
    /// The last two ratios agree (and are below kMaxRatio: near 1 the
    /// extrapolation would be a long, unreliable step): the next sweep may
    /// complete a third.
    bool armed() const {
      return count >= needed && ratios[1] < kMaxRatio && std::abs(ratios[1] - ratios[0]) <= kAgree * ratios[1];
    }
    /// Records a sweep's ||dr||; returns its ratio to the previous one (0 if none).
    double observe(double dr) {
      double rho = 0;
      if (last > 0) {
        rho = dr / last;
        ratios[0] = ratios[1];
        ratios[1] = rho;
        ++count;
      }
      last = dr;
      return rho;
    }
    void restart() { *this = Extrapolation{0, {0, 0}, 0, needed}; }
    /// A try was rejected: restart, and wait twice as long before the next.
    void back_off() {
      restart();
      needed = std::min(2 * needed, 1 << 20);
    }
  };

  /// Replaces r by r + rho / (1 - rho) (r - previous_) if its FCLIB error,
  /// written to `error`, is below rho * `estimate`, what the next sweep is
  /// expected to reach (and keeps u_ and the slot layout in step). Returns
  /// whether it did.
  bool extrapolate(Eigen::Ref<Vector> r, double rho, double estimate, double& error) {
    trial_ = r + (rho / (1 - rho)) * (r - previous_);
    const double trial = error_of(trial_);
    if (!(trial < rho * estimate)) return false;
    r = trial_;
    error = trial;
    if constexpr (!Storage::row_access) u_ = work_;
    if constexpr (use_slots) {
      if (settings_.ordering == ContactOrdering::Coloured) slots_.gather(*colouring_, r);
    }
    return true;
  }

  /// Three sweeps shrank the change by one factor rho: tries the Aitken limit
  /// (extrapolate()). When it is taken, estimate and error become its full
  /// error (exact); true when that error meets the tolerance.
  bool aitken_step_converges(Eigen::Ref<Vector> r, double rho, Extrapolation& extrapolation,
                             double& estimate, bool& exact, double& error) {
    FCSOLVE_NO_MALLOC_BEGIN();
    const bool taken = extrapolate(r, rho, estimate, error);
    FCSOLVE_NO_MALLOC_END();
    if (!taken) {
      extrapolation.back_off();
      return false;
    }
    extrapolation.restart();
    estimate = error;
    exact = true;
    keep_if_best(r, error);
    return error <= settings_.tol;
  }

  /// Stall detection across full error evaluations.
  struct Progress {
    double error;    ///< the error at the last 1% improvement
    int sweep;       ///< and its sweep
    bool reshuffle;  ///< the contacts (colours) are reshuffled every sweep
  };

  /// The identity order, or the seeded shuffle, or the colouring; thaws
  /// every contact.
  void start_ordering(Eigen::Ref<Vector> r) {
    const ContactOrdering ordering = settings_.ordering;
    std::iota(order_.begin(), order_.end(), Index(0));
    if (ordering == ContactOrdering::Coloured) {
      prepare_colouring();
      std::iota(colour_order_.begin(), colour_order_.end(), Index(0));
      if constexpr (use_slots) slots_.gather(*colouring_, r);
      start_threads();
    } else if (ordering == ContactOrdering::ShuffledOnce || ordering == ContactOrdering::ShuffledEachSweep) {
      rng_.seed(settings_.seed);
      std::shuffle(order_.begin(), order_.end(), rng_);
    }
    std::fill(frozen_.begin(), frozen_.end(), 0);
    local_failures_ = 0;
  }

  /// The full error of the starting r, except for a cold start (r = 0)
  /// that cannot be a solution: its error is bounded below
  /// (zero_reaction_error_bound) and, when half that bound is above tol,
  /// left unevaluated (+inf, start_pending_) until a failed solve needs it
  /// to pick its best iterate (settle_pending_start). The half keeps the
  /// bound's rounding far from tol. On the 3-contact cube of bench_nsgs
  /// (nsgs-small) it was one of a solve's three error evaluations: 2.17 ->
  /// 2.10 us a solve.
  double start_error(const Eigen::Ref<const Vector>& r) {
    const LocalProblemView& p = *problem_;
    start_pending_ = (r.array() == 0).all() &&
                     0.5 * zero_reaction_error_bound<Cone>(p.q, p.mu) / scale_ > settings_.tol;
    if (!start_pending_) return full_error(r);
    if constexpr (!Storage::row_access) u_ = p.q;
    return std::numeric_limits<double>::infinity();
  }

  /// A failed solve that started from an unevaluated r = 0: evaluates it
  /// now and keeps it if no iterate did better (ties to the start, as if
  /// it had been evaluated first).
  void settle_pending_start() {
    if (!start_pending_) return;
    start_pending_ = false;
    trial_.setZero();
    const double error = error_of(trial_);
    if (error <= best_error_ || !(best_error_ < std::numeric_limits<double>::infinity())) {
      best_error_ = error;
      best_.setZero();
    }
  }

  void keep_if_best(const Eigen::Ref<const Vector>& r, double error) {
    if (error < best_error_) {
      best_error_ = error;
      best_ = r;
    }
  }

  /// After a full error evaluation: keeps the best iterate, tests
  /// convergence, reshuffles every sweep after a long stall, thaws the
  /// frozen contacts or detects a fixed point of the sweep. Returns the
  /// final status, or MaxIterations to go on.
  Status judge_full_error(const Eigen::Ref<const Vector>& r, double error, const SweepResult& sw,
                          double change, double ratio, int sweep_no, Progress& progress) {
    const Settings& s = settings_;
    keep_if_best(r, error);
    if (error <= s.tol) return Status::Converged;
    if (error < 0.99 * progress.error) {
      progress.error = error;
      progress.sweep = sweep_no;
    } else if (s.stall_sweeps > 0 && sweep_no - progress.sweep >= s.stall_sweeps && !progress.reshuffle) {
      if (s.ordering != ContactOrdering::ShuffledOnce && s.ordering != ContactOrdering::ShuffledEachSweep)
        rng_.seed(s.seed);
      progress.reshuffle = true;
      progress.sweep = sweep_no;
      note(std::string("no progress: ") + (s.ordering == ContactOrdering::Coloured ? "colours" : "contacts") +
           " reshuffled every sweep from sweep " + std::to_string(sweep_no));
    } else if (progress.reshuffle && s.give_up_sweeps > 0 && sweep_no - progress.sweep >= s.give_up_sweeps) {
      note("no 1% progress in " + std::to_string(sweep_no - progress.sweep) + " sweeps after the reshuffle");
      return Status::Stalled;
    }
    if (sw.skipped > 0 && change * ratio <= s.tol) {
      // converged on the visited contacts only: check the frozen ones
      std::fill(frozen_.begin(), frozen_.end(), 0);
    } else if (change == 0 && sw.skipped == 0) {
      note("the sweep no longer changes r");
      return Status::Stalled;  // a fixed point of the sweep that is not a solution
    }
    return Status::MaxIterations;
  }

  SweepResult ordered_sweep(Eigen::Ref<Vector> r) {
    SweepResult out;
    const LocalProblemView& p = *problem_;
    if constexpr (use_slots) {
      const Index n = static_cast<Index>(order_.size());
      for (Index k = 0; k < n; ++k) {
        if (k + kPrefetchContacts < n)
          prefetch_contact(storage_, data_, order_[static_cast<std::size_t>(k + kPrefetchContacts)]);
        const Index a = order_[static_cast<std::size_t>(k)];
        record(a, update_contact(a, r, storage_, p.q, data_), out);
      }
    } else {  // dense storage: a few contacts, in the cache
      for (const Index a : order_) record(a, update_contact(a, r, storage_, p.q, data_), out);
    }
    return out;
  }

  /// Block-sparse storage: the sweep asks for the row of W (blocks and
  /// block columns) and the local data of the contact kPrefetchContacts
  /// visits ahead. Past the caches (the sphere pile of 10^5 contacts, 66 MB
  /// of W) a visit otherwise waits on memory: the hardware prefetchers
  /// follow a stream only within a 4 KiB page (a row is a sixth of one) and
  /// see no stream at all in a shuffled order. 16 contacts (about 10 KB of
  /// W) ahead hides a DRAM access at the sweep's pace (70-140 ns a contact)
  /// while the lines are still in L1/L2 at the visit: the 10^5 pile's sweep
  /// 22 % faster in the natural order, 35 % shuffled; 8 and 32 ahead gained
  /// less; a cached sweep (10^4) unchanged (docs/results.md, "NSGS: the
  /// sweep prefetches W's rows").
  static constexpr Index kPrefetchContacts = 16;
  static FCSOLVE_ALWAYS_INLINE void prefetch_contact(const Storage& W, const DataVector& data, Index b) {
    W.prefetch_row(b);
    prefetch_lines<cache_lines_spanned(sizeof(data[0]))>(&data[static_cast<std::size_t>(b)]);
  }

  /// Colour by colour; the contacts of a colour in parallel, in one
  /// parallel region per sweep (a barrier per colour). Their updates are
  /// kept in updates_ and recorded serially in the colour order, so the sums
  /// (and u_) do not depend on the number of threads: after the sweep with
  /// row access, after each colour with column updates (the next colour
  /// reads u_). Block-sparse storage sweeps the slot layout (slots_) and
  /// copies its reactions back into r after the sweep.
  SweepResult coloured_sweep(Eigen::Ref<Vector> r) {
    const ContactColouring& colouring = *colouring_;
    const LocalProblemView& p = *problem_;
    // Dense storage reads every r^b in a row product, zero blocks included:
    // contacts of one colour would then race; it is for a few contacts only.
    [[maybe_unused]] const int threads = is_dense_storage ? 1 : settings_.threads;
    SweepResult out;
    const auto update = [&](Index i) {
      if constexpr (use_slots)
        return update_contact(i, slots_.r, slots_.storage, slots_.q, slots_.data);
      else
        return update_contact(colouring.contacts[i], r, storage_, p.q, data_);
    };
    const auto record_colour = [&](Index c) {
      for (Index i = colouring.start[c]; i < colouring.start[c + 1]; ++i)
        record(colouring.contacts[i], updates_[i], out);
    };
#ifdef _OPENMP
#pragma omp parallel num_threads(threads) if (threads > 1)
#endif
    {
      for (const Index c : colour_order_) {
        const Index begin = colouring.start[c], end = colouring.start[c + 1];
        // Static: each thread streams one range of the colour's rows of W.
        // Chunks handed out dynamically were no faster at 10^4 contacts and
        // as slow as one thread at 10^5 (docs/results.md, "Parallel NSGS").
#ifdef _OPENMP
#pragma omp for schedule(static)
#endif
        for (Index i = begin; i < end; ++i) {
          // The slot layout streams like the natural order (prefetch_contact).
          if constexpr (use_slots) {
            if (i + kPrefetchContacts < end) prefetch_contact(slots_.storage, slots_.data, i + kPrefetchContacts);
          }
          updates_[i] = update(i);
        }
        if constexpr (!Storage::row_access) {
#ifdef _OPENMP
#pragma omp single
#endif
          record_colour(c);
        }
      }
      // The slot layout's sums and its copy back into r, chunk by chunk in
      // parallel (they ran on one thread after the loops); fixed chunks
      // summed in slot order: the same sums for any number of threads.
      if constexpr (use_slots) {
        const Index slots = static_cast<Index>(colouring.contacts.size());
#ifdef _OPENMP
#pragma omp for schedule(static)
#endif
        for (Index k = 0; k < num_chunks(slots); ++k) {
          ChunkSum& sum = chunk_sums_[static_cast<std::size_t>(k)];
          sum = ChunkSum{};
          for (Index i = k * kParallelChunk; i < std::min(slots, (k + 1) * kParallelChunk); ++i) {
            const ContactUpdate& c = updates_[static_cast<std::size_t>(i)];
            sum.change2 += c.dr2;
            sum.skipped += c.skipped ? 1 : 0;
            sum.failures += c.failures;
            r.template segment<d>(colouring.contacts[i] * d) = slots_.r.template segment<d>(i * d);
          }
        }
      }
    }
    if constexpr (use_slots) {
      for (Index k = 0; k < num_chunks(static_cast<Index>(colouring.contacts.size())); ++k) {
        const ChunkSum& sum = chunk_sums_[static_cast<std::size_t>(k)];
        out.change2 += sum.change2;
        out.skipped += sum.skipped;
        local_failures_ += sum.failures;
      }
    } else if constexpr (Storage::row_access) {
      for (const Index c : colour_order_) record_colour(c);
    }
    return out;
  }

  /// Contacts per chunk of the parallel loops of the coloured ordering.
  static constexpr Index kParallelChunk = 64;
  static Index num_chunks(Index n) { return (n + kParallelChunk - 1) / kParallelChunk; }
  struct ChunkSum {
    double change2 = 0;
    Index skipped = 0;
    long long failures = 0;
  };

  void prepare_colouring() {
    if (colouring_) return;
    colouring_ = colour_contacts(problem_->W, d);
    colour_order_.resize(static_cast<std::size_t>(colouring_->num_colours()));
    updates_.resize(colouring_->contacts.size());
    chunk_sums_.resize(static_cast<std::size_t>(num_chunks(static_cast<Index>(colouring_->contacts.size()))));
    error_chunks_.resize(chunk_sums_.size());
    if constexpr (use_slots) slots_.compute(*problem_, *colouring_, data_);
  }

  /// The problem renumbered so that each colour is a contiguous range of
  /// slots (slot i is contact colouring.contacts[i]): a colour then streams
  /// its part of W, q, r and the local data instead of reading every k-th
  /// block row (measured: the coloured sweep in the contacts' numbering cost
  /// 1.8-2.6x the natural sweep's CPU on one thread, docs/results.md).
  struct SlotLayout {
    Storage storage;
    Vector q, r;
    DataVector data;

    void compute(const LocalProblemView& p, const ContactColouring& c, const DataVector& by_contact) {
      const Index nc = static_cast<Index>(c.contacts.size());
      std::vector<Index> slot(static_cast<std::size_t>(nc));
      for (Index i = 0; i < nc; ++i) slot[c.contacts[i]] = i;
      std::vector<Eigen::Triplet<double, int>> entries;
      entries.reserve(static_cast<std::size_t>(p.W.nonZeros()));
      for (Index j = 0; j < p.W.outerSize(); ++j)
        for (SparseMap::InnerIterator it(p.W, j); it; ++it)
          entries.emplace_back(int(slot[it.row() / d] * d + it.row() % d),
                               int(slot[j / d] * d + j % d), it.value());
      SparseMatrix W(p.W.rows(), p.W.cols());
      W.setFromTriplets(entries.begin(), entries.end());
      storage.compute(W);
      q.resize(p.size());
      r.resize(p.size());
      data.resize(by_contact.size());
      for (Index i = 0; i < nc; ++i) {
        q.template segment<d>(i * d) = p.q.template segment<d>(c.contacts[i] * d);
        data[i] = by_contact[c.contacts[i]];
      }
    }
    void gather(const ContactColouring& c, const Eigen::Ref<const Vector>& from) {
      for (Index i = 0; i < static_cast<Index>(c.contacts.size()); ++i)
        r.template segment<d>(i * d) = from.template segment<d>(c.contacts[i] * d);
    }
  };

  /// Starts the OpenMP thread team before the sweeps: the runtime allocates
  /// it at the first parallel region with a given number of threads, and
  /// reuses it afterwards.
  void start_threads() const {
#ifdef _OPENMP
    const int threads = settings_.threads;
#pragma omp parallel num_threads(threads) if (threads > 1 && !is_dense_storage)
    {
    }
#endif
  }

  /// True when W has no nonzero outside its diagonal blocks (e.g. one
  /// contact): the contacts' problems are independent.
  static bool no_coupling(const SparseMap& W) {
    for (Index j = 0; j < W.outerSize(); ++j)
      for (SparseMap::InnerIterator it(W, j); it; ++it)
        if (it.row() / d != j / d && it.value() != 0) return false;
    return true;
  }

  /// FCLIB error of r; refreshes u_ (and removes the drift of the column
  /// updates).
  double full_error(const Eigen::Ref<const Vector>& r) {
    const double error = error_of(r);
    if constexpr (!Storage::row_access) u_ = work_;
    return error;
  }

  /// FCLIB error of x, with work_ = W x + q. A cold start (x = 0) skips the
  /// product: on 3 contacts it was a fifth of the solve's error evaluations.
  double error_of(const Eigen::Ref<const Vector>& x) {
    const LocalProblemView& p = *problem_;
    if constexpr (use_slots) {
      if (settings_.ordering == ContactOrdering::Coloured && colouring_) return chunked_error_of(x);
    }
    if ((x.array() == 0).all()) {
      work_ = p.q;
    } else {
      storage_.multiply(x, work_);
      work_ += p.q;
    }
    return std::sqrt(natural_map_norms<Cone>(x, work_, p.mu).squared_sum) / scale_;
  }

  /// error_of() for the coloured ordering: block rows and natural maps in
  /// parallel, chunk by chunk, the chunks' sums added in order (the same
  /// error for any number of threads). With the sums and the copy above,
  /// 2 threads' sweep went from 0.377 to 0.352 ms on a 10^4-contact pile
  /// and from 6.1 to 5.1 ms at 10^5 (best runs, docs/results.md).
  double chunked_error_of(const Eigen::Ref<const Vector>& x) {
    const LocalProblemView& p = *problem_;
    const Index nc = p.num_contacts();
    [[maybe_unused]] const int threads = settings_.threads;
#ifdef _OPENMP
#pragma omp parallel for num_threads(threads) if (threads > 1) schedule(static)
#endif
    for (Index k = 0; k < num_chunks(nc); ++k) {
      const Index begin = k * kParallelChunk, count = std::min(nc, begin + kParallelChunk) - begin;
      for (Index a = begin; a < begin + count; ++a)
        work_.template segment<d>(a * d) = storage_.block_row_product(a, x) + p.q.template segment<d>(a * d);
      error_chunks_[static_cast<std::size_t>(k)] =
          natural_map_norms<Cone>(x.segment(begin * d, count * d), work_.segment(begin * d, count * d),
                                  p.mu.segment(begin, count))
              .squared_sum;
    }
    double squared_sum = 0;
    for (Index k = 0; k < num_chunks(nc); ++k) squared_sum += error_chunks_[static_cast<std::size_t>(k)];
    return std::sqrt(squared_sum) / scale_;
  }

  const SolverInfo& finish(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u, Status status,
                           const Stopwatch& clock) {
    // On success r is the last (and best) iterate, and the full error that
    // accepted it left work_ = W r + q; otherwise return the best one seen,
    // which is finite.
    if (status == Status::Converged) {
      u = work_;
    } else {
      r = best_;
      storage_.multiply(r, u);
      u += problem_->q;
    }
    info_.status = status;
    info_.error = best_error_;
    if (local_failures_ > 0)
      note(std::to_string(local_failures_) + " local solves did not converge");
    info_.solve_seconds = clock.seconds();
    return info_;
  }

  void note(const std::string& text) {
    info_.message += (info_.message.empty() ? "" : "; ") + text;
  }

  void check_solve_arguments(const Eigen::Ref<Vector>& r, const Eigen::Ref<Vector>& u) const {
    const Index m = problem_ ? problem_->size() : 0;
    fcsolve::check_solve_arguments("Nsgs", problem_.has_value(), r, m, u, m, "u");
    if (settings_.threads < 1)
      throw UsageError("NSGS: threads must be >= 1, got " + std::to_string(settings_.threads));
    if (!(settings_.omega > 0 && settings_.omega < 2))
      throw UsageError("NSGS: omega must be in (0, 2), got " + std::to_string(settings_.omega));
  }

  Settings settings_;
  SolverInfo info_;
  std::optional<LocalProblemView> problem_;
  Storage storage_;
  DataVector data_;
  SlotLayout slots_;
  std::vector<Index> order_;
  std::vector<int> frozen_;
  static constexpr bool is_dense_storage = detail::is_dense_storage<Storage>::value;
  /// The coloured sweep of row-access sparse storage runs on the slot layout.
  static constexpr bool use_slots = Storage::row_access && !is_dense_storage;
  std::optional<ContactColouring> colouring_;
  std::vector<Index> colour_order_;  // the colours in the order of the sweep
  std::vector<ContactUpdate, Eigen::aligned_allocator<ContactUpdate>> updates_;  // by colour slot
  std::vector<ChunkSum> chunk_sums_;  // a sweep's sums, by chunk of kParallelChunk slots
  std::vector<double> error_chunks_;  // squared natural maps, by chunk of kParallelChunk contacts
  std::minstd_rand rng_;  // small state: cheap to construct and seed
  Vector u_, work_, best_;
  Vector previous_, trial_;  ///< r before the sweep, and the extrapolated r
  Vector start_;             ///< the caller's r, for LoadAscending's second start
  double scale_ = 1, best_error_ = 0;
  bool decoupled_ = false;  ///< W block-diagonal (no_coupling)
  bool start_pending_ = false;  ///< the cold start's error is not evaluated yet (start_error)
  long long local_failures_ = 0;
};

}  // namespace fcsolve
