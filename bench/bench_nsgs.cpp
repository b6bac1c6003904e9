// The NSGS family: whole solves (setup once, then solve from r = 0) of the
// variants on FCLIB problems, and the local solvers on random contacts.
// Counters: sweeps of one solve, final FCLIB error, sweeps/s and
// contacts/s (local solves per second), converged (1/0).
//   ./build/bench/bench_nsgs --benchmark_min_time=0.01
// Set FCSOLVE_BENCH_DATA=../shared/data/fclib/local for the shared problems
// (same names). Compare ratios within one run (the machine is shared).
#include "bench_support.hpp"

#include <fcsolve/nsgs.hpp>
#include <fcsolve/problem/reduction.hpp>

#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace fcsolve;
using fcsolve_bench::local_problem;
using fcsolve_bench::rate;

template <class Cone>
using DefaultLocal = local::Enumerative<Cone>;

/// One NSGS variant: local solver, storage and how its settings differ.
template <template <class> class Local, class Storage, class Tweak>
void solve_problem(benchmark::State& state, const LocalProblem& p, double tol, Tweak tweak) {
  Nsgs<Coulomb3D, Storage, Local<Coulomb3D>> nsgs;
  nsgs.settings().tol = tol;
  nsgs.settings().max_iter = 1000000;
  nsgs.settings().max_time = 20;
  tweak(nsgs.settings());
  nsgs.compute(p);
  Vector r(p.size()), u(p.size());
  for (auto _ : state) {
    r.setZero();
    nsgs.solve(r, u);
    benchmark::DoNotOptimize(r.data());
  }
  const SolverInfo& info = nsgs.info();
  state.counters["sweeps"] = info.iterations;
  state.counters["error"] = info.error;
  state.counters["converged"] = info.converged();
  rate(state, "sweeps/s", info.iterations);
  rate(state, "contacts/s", double(info.iterations) * double(p.num_contacts()));
}

const auto as_is = [](auto&) {};
const auto reshuffle = [](auto& s) { s.ordering = ContactOrdering::ShuffledEachSweep; };
const auto over_relaxed = [](auto& s) { s.omega = 1.3; };
const auto freezing = [](auto& s) { s.freezing = 10; };

template <template <class> class Local, class Tweak = decltype(as_is)>
void BM_Nsgs(benchmark::State& state, const char* problem, double tol, Tweak tweak = as_is) {
  const LocalProblem& p = local_problem(problem);
  if (p.num_contacts() <= kDenseStorageMaxContacts)
    solve_problem<Local, DenseStorage<3>>(state, p, tol, tweak);
  else
    solve_problem<Local, BlockSparseStorage<3>>(state, p, tol, tweak);
}

/// Storage comparison on one problem (default local solver).
template <class Storage>
void BM_NsgsStorage(benchmark::State& state, const char* problem) {
  solve_problem<DefaultLocal, Storage>(state, local_problem(problem), 1e-8, as_is);
}

/// NSGS on the reduction of a global problem (the reduction is not timed).
void BM_NsgsGlobalReduced(benchmark::State& state, const char* problem) {
  static std::vector<std::unique_ptr<GlobalReduction<>>> keep;
  keep.push_back(std::make_unique<GlobalReduction<>>(fcsolve_bench::global_problem(problem)));
  const LocalProblem& p = keep.back()->local();
  if (p.num_contacts() <= kDenseStorageMaxContacts)
    solve_problem<DefaultLocal, DenseStorage<3>>(state, p, 1e-8, as_is);
  else
    solve_problem<DefaultLocal, BlockSparseStorage<3>>(state, p, 1e-8, as_is);
}

/// Every variant on problems of 4 contacts (dense storage), 23 and 225
/// (block-sparse), registered as nsgs/<problem>/<variant>.
const int kVariantsRegistered = [] {
  struct Problem {
    const char* name;
    benchmark::TimeUnit unit;
  };
  for (const Problem pb : {Problem{"Rover1039", benchmark::kMicrosecond},
                           Problem{"OneObject-i1028-138", benchmark::kMillisecond},
                           Problem{"Capsules-i101-404", benchmark::kMillisecond}}) {
    const std::string prefix = std::string("nsgs/") + pb.name + "/";
    const char* name = pb.name;
    const auto add = [&](const char* variant, auto body) {
      benchmark::RegisterBenchmark((prefix + variant).c_str(), body)->Unit(pb.unit);
    };
    add("exact", [name](benchmark::State& s) { BM_Nsgs<local::Enumerative>(s, name, 1e-8); });
    add("exact-reshuffle",
        [name](benchmark::State& s) { BM_Nsgs<local::Enumerative>(s, name, 1e-8, reshuffle); });
    add("exact-omega1.3",
        [name](benchmark::State& s) { BM_Nsgs<local::Enumerative>(s, name, 1e-8, over_relaxed); });
    add("exact-freezing",
        [name](benchmark::State& s) { BM_Nsgs<local::Enumerative>(s, name, 1e-8, freezing); });
    add("projection", [name](benchmark::State& s) { BM_Nsgs<local::Projection>(s, name, 1e-8); });
    add("projection-iterative",
        [name](benchmark::State& s) { BM_Nsgs<local::ProjectionIterative>(s, name, 1e-8); });
    add("alart-curnier",
        [name](benchmark::State& s) { BM_Nsgs<local::AlartCurnierNewton>(s, name, 1e-8); });
    add("fischer-burmeister",
        [name](benchmark::State& s) { BM_Nsgs<local::FischerBurmeisterNewton>(s, name, 1e-8); });
    add("hybrid", [name](benchmark::State& s) { BM_Nsgs<local::Hybrid>(s, name, 1e-8); });
  }
  return 0;
}();

/// Storages on one problem, and NSGS on reduced global problems.
const int kStoragesRegistered = [] {
  const auto ms = benchmark::kMillisecond;
  benchmark::RegisterBenchmark("nsgs-storage/Capsules-i101-404/dense", [](benchmark::State& s) {
    BM_NsgsStorage<DenseStorage<3>>(s, "Capsules-i101-404");
  })->Unit(ms);
  benchmark::RegisterBenchmark("nsgs-storage/Capsules-i101-404/block-sparse",
                               [](benchmark::State& s) {
                                 BM_NsgsStorage<BlockSparseStorage<3>>(s, "Capsules-i101-404");
                               })->Unit(ms);
  benchmark::RegisterBenchmark("nsgs-storage/Capsules-i101-404/sparse", [](benchmark::State& s) {
    BM_NsgsStorage<SparseStorage<3>>(s, "Capsules-i101-404");
  })->Unit(ms);
  for (const char* problem : {"Box_Stacks-i0035-31-0", "LMGC_GlobalFrictionContactProblem00046"})
    benchmark::RegisterBenchmark((std::string("nsgs-global-reduced/") + problem).c_str(),
                                 [problem](benchmark::State& s) { BM_NsgsGlobalReduced(s, problem); })
        ->Unit(ms);
  return 0;
}();

// ------------------------------------------------------- small scenes, hot
// The resting cube of bench_support.hpp: the cost of one whole solve, setup
// excluded, in a hot loop: what a real-time engine pays per step for a small
// scene (issue 13: <= 2 us for 3 contacts).
void BM_NsgsSmall(benchmark::State& state, int contacts) {
  static std::vector<std::unique_ptr<LocalProblem>> keep;  // the solver views it
  keep.push_back(std::make_unique<LocalProblem>(fcsolve_bench::resting_cube(contacts)));
  solve_problem<DefaultLocal, DenseStorage<3>>(state, *keep.back(), 1e-8, as_is);
}

const int kSmallRegistered = [] {
  for (const int contacts : {1, 3, 4})
    benchmark::RegisterBenchmark(("nsgs-small/cube-" + std::to_string(contacts) + "-contacts").c_str(),
                                 [contacts](benchmark::State& s) { BM_NsgsSmall(s, contacts); })
        ->Unit(benchmark::kMicrosecond);
  return 0;
}();

// ------------------------------------------------------------ local solvers

struct Contact {
  Eigen::Matrix3d W;
  Eigen::Vector3d q;
  double mu;
};

/// 1024 random contacts: W = A A^T + eps I, q_N mostly negative, mu in [0, 1].
const std::vector<Contact>& random_contacts() {
  static const std::vector<Contact> contacts = [] {
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> uni(-1, 1), pos(0, 1);
    std::vector<Contact> out(1024);
    for (auto& c : out) {
      Eigen::Matrix3d A;
      for (int i = 0; i < 9; ++i) A(i / 3, i % 3) = uni(gen);
      c.W = A * A.transpose() + 0.1 * Eigen::Matrix3d::Identity();
      c.q = Eigen::Vector3d(uni(gen) - 0.3, uni(gen), uni(gen));
      c.mu = pos(gen);
    }
    return out;
  }();
  return contacts;
}

/// Local solves from r = 0 (prepare() not timed).
template <class Local>
void BM_LocalSolver(benchmark::State& state) {
  const auto& contacts = random_contacts();
  typename Local::Settings s;
  std::vector<typename Local::Data, Eigen::aligned_allocator<typename Local::Data>> data;
  for (const auto& c : contacts) data.push_back(Local::prepare(c.W, c.mu, s));
  long long iterations = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      Eigen::Vector3d r = Eigen::Vector3d::Zero();
      iterations += Local::solve(data[k], contacts[k].q, r, s).iterations;
      benchmark::DoNotOptimize(r.data());
    }
  }
  rate(state, "contacts/s", double(contacts.size()));
  state.counters["iterations/contact"] =
      double(iterations) / double(contacts.size()) / double(state.iterations());
}
BENCHMARK_TEMPLATE(BM_LocalSolver, local::Enumerative<Coulomb3D>);
BENCHMARK_TEMPLATE(BM_LocalSolver, local::Projection<Coulomb3D>);
BENCHMARK_TEMPLATE(BM_LocalSolver, local::ProjectionIterative<Coulomb3D>);
BENCHMARK_TEMPLATE(BM_LocalSolver, local::AlartCurnierNewton<Coulomb3D>);
BENCHMARK_TEMPLATE(BM_LocalSolver, local::FischerBurmeisterNewton<Coulomb3D>);
BENCHMARK_TEMPLATE(BM_LocalSolver, local::Hybrid<Coulomb3D>);

}  // namespace

BENCHMARK_MAIN();
