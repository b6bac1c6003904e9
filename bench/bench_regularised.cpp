// The regularised and splitting families against semismooth Newton: time
// to 1e-8 from r = 0 (compute() and solve(): what a user pays per problem)
// of the proximal point (ppa: inner Newton-AC; ppa-nsgs: inner NSGS), ADMM,
// and the fixed points fp-ds (De Saxce, fixed rho), tresca and pana, with
// nsn-ac (Newton, Alart-Curnier) as the baseline in the same run. The class
// templates are used directly, with the storages and defaults of their
// catalogue entries (solvers/*_entries.hpp): dense W up to
// kDenseStorageMaxContacts contacts, else the entry's sparse storage.
// Counters: outer iterations, the final FCLIB error, and ADMM's
// factorisations of W_s + rho I. (ppa's inner Newton steps and the inner
// sweeps of tresca / pana are only in info().message, not counted here.)
// A solve that does not reach 1e-8 is reported as an error with its status.
//   ./build/bench/bench_regularised --benchmark_min_time=0.05
//   FCSOLVE_BENCH_DATA=DIR ./build/bench/bench_regularised   (problems of the same names elsewhere)
// Compare ratios within one run (the machine is shared and noisy).
#include "bench_support.hpp"

#include <fcsolve/admm.hpp>
#include <fcsolve/fixed_point.hpp>
#include <fcsolve/newton.hpp>
#include <fcsolve/ppa.hpp>

#include <string>

namespace {

using namespace fcsolve;
using fcsolve_bench::local_problem;

// Rigid multibody: 4 contacts (small), 23 (one object), 225 (a pile of
// capsules, rank-deficient W); FEM (full rank): 54. bench_newton's
// BoxesStack1-i100000-32 is left out: fp-ds does not reach 1e-8 there in
// 10 s, and ppa-nsgs (6.6 s), tresca (3.8 s) and pana (1.2 s) are slow.
const char* const kRover = "Rover1039";
const char* const kOneObject = "OneObject-i1028-138";
const char* const kCapsules = "Capsules-i101-404";
const char* const kConfeti = "Confeti-ex03-Fc3D-SBM";

/// Time to tolerance: no iteration cap (as bench/compare_siconos.py runs
/// fcsolve), a runaway solve costs at most kMaxSeconds per benchmark iteration.
constexpr int kMaxIterations = 1000000000;
constexpr double kMaxSeconds = 10;

// Each family on the storage S (the cone is Coulomb3D throughout).
template <class S>
using NsnAc = Newton<AlartCurnierFunction, Coulomb3D, S>;
template <class S>
using PpaNewton = ProximalPoint<Coulomb3D, Newton<AlartCurnierFunction, Coulomb3D, S>>;
template <class S>
using PpaNsgs = ProximalPoint<Coulomb3D, Nsgs<Coulomb3D, S>>;
template <class S>
using AdmmOn = Admm<Coulomb3D, S>;
template <class S>
using FpDs = ProjectedFixedPoint<Coulomb3D, S>;
template <class S>
using Tresca = TrescaFixedPoint<Coulomb3D, S>;
template <class S>
using Pana = Panagiotopoulos<Coulomb3D, S>;

/// compute() + solve() from r = 0 per benchmark iteration; Configure
/// adjusts the settings once, Extra adds a family's own counters.
template <class Solver, class Configure, class Extra>
void time_solve(benchmark::State& state, const LocalProblem& p) {
  Solver solver;
  solver.settings().max_iter = kMaxIterations;
  solver.settings().max_time = kMaxSeconds;
  Configure{}(solver.settings());
  Vector r(p.size()), u(p.size());
  for (auto _ : state) {
    r.setZero();
    solver.compute(p);
    solver.solve(r, u);
    benchmark::DoNotOptimize(r.data());
  }
  const SolverInfo& info = solver.info();
  state.counters["iterations"] = info.iterations;
  state.counters["error"] = info.error;
  Extra{}(state, solver);
  if (!info.converged()) state.SkipWithError(to_string(info.status));
}

struct CatalogueDefaults {
  template <class Settings>
  void operator()(Settings&) const {}
};
/// De Saxce's fixed point: the projected fixed point with a constant rho
/// (fixed_point_entries.hpp).
struct FpDsSettings {
  void operator()(ProjectedFixedPointSettings& s) const {
    s.variant = ProjectionVariant::FixedPoint;
    s.step = StepRule::Fixed;
  }
};
struct NoExtra {
  template <class Solver>
  void operator()(benchmark::State&, const Solver&) const {}
};
struct AdmmFactorisations {
  template <class Solver>
  void operator()(benchmark::State& state, const Solver& admm) const {
    state.counters["factorisations"] = admm.factorizations();
  }
};

/// Registers <solver>/<problem>: Solver<DenseStorage<3>> on small scenes,
/// Solver<Sparse<3>> beyond, as the catalogue's dispatch chooses
/// (solvers/dispatch.hpp).
template <template <class> class Solver, template <int> class Sparse,
          class Configure = CatalogueDefaults, class Extra = NoExtra>
void add(const char* solver, const char* problem) {
  const auto unit = std::string(problem) == kRover ? benchmark::kMicrosecond : benchmark::kMillisecond;
  benchmark::RegisterBenchmark((std::string(solver) + "/" + problem).c_str(),
                               [problem](benchmark::State& state) {
                                 const LocalProblem& p = local_problem(problem);
                                 if (p.num_contacts() <= kDenseStorageMaxContacts)
                                   time_solve<Solver<DenseStorage<3>>, Configure, Extra>(state, p);
                                 else
                                   time_solve<Solver<Sparse<3>>, Configure, Extra>(state, p);
                               })
      ->Unit(unit);
}

/// The baseline nsn-ac first on each problem.
const int kRegistered = [] {
  for (const char* name : {kRover, kOneObject, kConfeti, kCapsules}) {
    add<NsnAc, SparseStorage>("nsn-ac", name);
    add<PpaNewton, SparseStorage>("ppa", name);
    add<PpaNsgs, BlockSparseStorage>("ppa-nsgs", name);
    add<AdmmOn, SparseStorage, CatalogueDefaults, AdmmFactorisations>("admm", name);
    add<FpDs, BlockSparseStorage, FpDsSettings>("fp-ds", name);
    add<Tresca, BlockSparseStorage>("tresca", name);
    add<Pana, BlockSparseStorage>("pana", name);
  }
  return 0;
}();

}  // namespace

BENCHMARK_MAIN();
