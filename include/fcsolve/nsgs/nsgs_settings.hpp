// Settings of the nonsmooth Gauss-Seidel solver (nsgs/nsgs_solver.hpp).
#pragma once

#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/solver_settings.hpp>

#include <cstdint>

namespace fcsolve {

/// The order in which a sweep visits the contacts.
enum class ContactOrdering {
  Natural,          ///< 0, 1, ..., nc - 1
  ShuffledOnce,     ///< one random permutation (seeded), kept for the whole solve
  ShuffledEachSweep, ///< a new random permutation every sweep
  /// Colour by colour (nsgs/contact_colouring.hpp): contacts of one colour
  /// share no body (no block W^{ab}), so they are updated in parallel with
  /// `threads` OpenMP threads, with the same iterates for any thread count.
  Coloured,
  /// By increasing normal reaction r_N, ties by index: natural sweeps until
  /// the loads have formed, then the contacts sorted by them and the solve
  /// started again from the caller's r in that order (nsgs_solver.hpp,
  /// kLoadSortError). Under gravity the load flows from lightly loaded
  /// contacts (the top of a pile) to heavily loaded ones (its floor):
  /// visited in that order a sweep passes the weight above down the pile
  /// (Gauss-Seidel ordered along the flow). It needs no geometry. Measured
  /// (docs/results.md, "NSGS: contacts ordered by load"): piles of 3000 and
  /// 10^4 spheres 1.2-4.4x faster to 1e-6; box stacks, towers and most
  /// shared problems slower (the restart, rows of W read out of order).
  LoadAscending
};

inline constexpr EnumName<ContactOrdering> kContactOrderingNames[] = {
    {ContactOrdering::Natural, "natural"},
    {ContactOrdering::ShuffledOnce, "shuffle"},
    {ContactOrdering::ShuffledEachSweep, "reshuffle"},
    {ContactOrdering::Coloured, "coloured"},
    {ContactOrdering::LoadAscending, "load"}};
constexpr const auto& enum_names(ContactOrdering) { return kContactOrderingNames; }

/// NSGS knobs; `LocalSettings` are the local solver's (e.g.
/// local::Projection<Cone>::Settings). Common ones (tol, max_iter, max_time,
/// record_history, callback) come from SolverSettings.
template <class LocalSettings>
struct NsgsSettings : SolverSettings {
  /// Over-relaxation (PSOR): r^a <- omega r^a_local + (1 - omega) r^a.
  /// omega < 1 helps on FEM problems (Acary et al. 2018, sec. 5.3); (0, 2).
  double omega = 1.0;
  ContactOrdering ordering = ContactOrdering::Natural;
  std::uint32_t seed = 0;  ///< seed of the shuffles
  /// Threads of the Coloured sweep (>= 1). Ignored by the other orderings
  /// and when the library is compiled without OpenMP (serial loop, same
  /// iterates).
  int threads = 1;
  /// When the best full error has not improved by 1% for this many sweeps,
  /// switch to ShuffledEachSweep: exact block Gauss-Seidel in a fixed order
  /// can fall into a cycle that a new order each sweep breaks (Coloured:
  /// the order of the colours is reshuffled instead). 0: never.
  int stall_sweeps = 5000;
  /// After that reshuffle: stop (Stalled) when this many more sweeps have not
  /// improved the best full error by 1%: at that pace one more decade of
  /// error takes 230 times as many sweeps. 0: never (sweep to max_iter or
  /// max_time).
  int give_up_sweeps = 0;
  /// Full FCLIB error at least every `error_every` sweeps; in between, a
  /// cheap test on ||r_{k+1} - r_k|| decides whether a full error is worth
  /// computing. Success is only ever declared on a full error.
  int error_every = 10;
  /// Contact freezing: a contact whose local solution moved by at most
  /// freeze_tol (relative) is skipped for the next `freezing` sweeps
  /// (0: off). A full error over all contacts precedes any success, and
  /// a failed check unfreezes everything. Contacts that took off or stick
  /// stop moving early: on the Capsules problems this halves the time.
  int freezing = 10;
  double freeze_tol = 1e-14;
  /// Aitken extrapolation when three successive sweeps shrink the change
  /// by one factor (nsgs_solver.hpp, Extrapolation), kept only if its full
  /// FCLIB error is below rho times the current estimate (it beats the
  /// sweep it costs): fewer sweeps on a few strongly coupled contacts.
  bool extrapolate = true;
  /// Local (one-contact) solver settings.
  LocalSettings local;
};

}  // namespace fcsolve
