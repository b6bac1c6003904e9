// Kernels under every solver: cone projections, products with W in the three
// storages (whole product, the block row of Gauss-Seidel on row storage, the
// block column update on column storage), the full FCLIB error, and the
// reduction of FC/I to FC/II with both linear-algebra backends.
//   ./build/bench/bench_kernels --benchmark_min_time=0.01
// Compare ratios within one run (the machine is shared and noisy).
#include "bench_support.hpp"

#include <fcsolve/problem/error.hpp>
#include <fcsolve/linalg/eigen_backend.hpp>
#include <fcsolve/linalg/suitesparse_backend.hpp>
#include <fcsolve/problem/reduction.hpp>
#include <fcsolve/storage/storage.hpp>

#include <string>
#include <utility>

namespace {

using namespace fcsolve;
using fcsolve_bench::local_problem;
using fcsolve_bench::random_vector;
using fcsolve_bench::rate;

// Local problems of increasing size: 4 contacts (dense territory), 52 and 225.
const char* const kSmall = "Rover1039";
const char* const kMedium = "BoxesStack1-i100000-32";
const char* const kLarge = "Capsules-i101-404";

// ------------------------------------------------------------ cone projections

/// Projection of 1024 random points (inside, polar and boundary cases mixed).
template <class Cone>
void BM_ConeProjection(benchmark::State& state) {
  constexpr int d = Cone::dim;
  const Index n = 1024;
  const Vector z = random_vector(n * d, 3);
  Vector out(n * d);
  for (auto _ : state) {
    for (Index a = 0; a < n; ++a)
      out.template segment<d>(a * d) =
          Cone::project(typename Cone::Vec(z.template segment<d>(a * d)), 0.7);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  rate(state, "contacts/s", double(n));
}
BENCHMARK_TEMPLATE(BM_ConeProjection, Coulomb3D);
BENCHMARK_TEMPLATE(BM_ConeProjection, Coulomb2D);

/// Natural map of one contact, r - P_K(r - u~): the per-contact error kernel.
void BM_NaturalMapContact(benchmark::State& state) {
  const Index n = 1024;
  const Vector r = random_vector(3 * n, 4), u = random_vector(3 * n, 5);
  double sum = 0;
  for (auto _ : state) {
    for (Index a = 0; a < n; ++a)
      sum += natural_map<Coulomb3D>(Coulomb3D::Vec(r.segment<3>(3 * a)),
                                    Coulomb3D::Vec(u.segment<3>(3 * a)), 0.7).squaredNorm();
    benchmark::DoNotOptimize(sum);
  }
  rate(state, "contacts/s", double(n));
}
BENCHMARK(BM_NaturalMapContact);

// ------------------------------------------------------------ products with W

template <class Storage>
Storage make_storage(const LocalProblem& p) {
  if constexpr (std::is_same_v<Storage, SparseStorage<3>>) return Storage(LocalProblemView(p).W);
  else return Storage(p.W);
}

/// y = W x over the whole matrix.
template <class Storage>
void BM_StorageMultiply(benchmark::State& state, const char* name) {
  const LocalProblem& p = local_problem(name);
  const Storage W = make_storage<Storage>(p);
  const Vector x = random_vector(p.size());
  Vector y(p.size());
  for (auto _ : state) {
    W.multiply(x, y);
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  state.counters["nc"] = double(p.num_contacts());
  rate(state, "nnz/s", double(p.W.nonZeros()));
}

/// One Gauss-Seidel access sweep: every block row W_a. x (row storages).
template <class Storage>
void BM_StorageBlockRows(benchmark::State& state, const char* name) {
  const LocalProblem& p = local_problem(name);
  const Storage W = make_storage<Storage>(p);
  const Vector x = random_vector(p.size());
  typename Storage::BlockVector acc;
  for (auto _ : state) {
    acc.setZero();
    for (Index a = 0; a < W.num_blocks(); ++a) acc += W.block_row_product(a, x);
    benchmark::DoNotOptimize(acc.data());
  }
  rate(state, "contacts/s", double(p.num_contacts()));
}

/// One Gauss-Seidel update sweep on column access: y += W_.a dx for every a.
template <class Storage>
void BM_StorageBlockColumns(benchmark::State& state, const char* name) {
  const LocalProblem& p = local_problem(name);
  const Storage W = make_storage<Storage>(p);
  Vector y = Vector::Zero(p.size());
  const typename Storage::BlockVector dx(1e-3, -2e-3, 5e-4);
  for (auto _ : state) {
    for (Index a = 0; a < W.num_blocks(); ++a) W.add_block_column(a, dx, y);
    benchmark::DoNotOptimize(y.data());
    benchmark::ClobberMemory();
  }
  rate(state, "contacts/s", double(p.num_contacts()));
}

/// Registers the product benchmarks of one storage (named at run time: the
/// BENCHMARK_* macros take no template arguments with captures).
template <class Storage>
bool register_storage(const std::string& storage) {
  const std::pair<const char*, const char*> sizes[] = {
      {"small", kSmall}, {"medium", kMedium}, {"large", kLarge}};
  for (const auto& [label, name] : sizes) {
    benchmark::RegisterBenchmark(("BM_StorageMultiply/" + storage + "/" + label).c_str(),
                                 BM_StorageMultiply<Storage>, name);
    benchmark::RegisterBenchmark(("BM_StorageBlockColumns/" + storage + "/" + label).c_str(),
                                 BM_StorageBlockColumns<Storage>, name);
    if constexpr (Storage::row_access)
      benchmark::RegisterBenchmark(("BM_StorageBlockRows/" + storage + "/" + label).c_str(),
                                   BM_StorageBlockRows<Storage>, name);
  }
  return true;
}
const bool kStoragesRegistered = register_storage<DenseStorage<3>>("dense") &&
                                 register_storage<SparseStorage<3>>("sparse") &&
                                 register_storage<BlockSparseStorage<3>>("block_sparse");

// ------------------------------------------------------------ the FCLIB error

/// Full error of a reaction (u = W r + q, natural map, norm), allocation-free.
void BM_LocalError(benchmark::State& state, const char* name) {
  const LocalProblem& p = local_problem(name);
  LocalErrorEvaluator<Coulomb3D> error{LocalProblemView(p)};
  const Vector r = random_vector(p.size(), 2).cwiseAbs();
  double e = 0;
  for (auto _ : state) benchmark::DoNotOptimize(e += error(r));
  rate(state, "contacts/s", double(p.num_contacts()));
}
BENCHMARK_CAPTURE(BM_LocalError, small, kSmall);
BENCHMARK_CAPTURE(BM_LocalError, large, kLarge);

// ------------------------------------------------------------ reduction FC/I -> FC/II

/// Factorise M and form W = H^T M^-1 H, q (Box_Stacks: block-diagonal SPD M,
/// 450 dofs; LMGC: unsymmetric FEM M, LU).
template <class Backend>
void BM_GlobalReduction(benchmark::State& state, const char* name) {
  const GlobalProblem& p = fcsolve_bench::global_problem(name);
  for (auto _ : state) {
    GlobalReduction<Backend> reduction(p);
    benchmark::DoNotOptimize(reduction.free_velocity_norm());
  }
  state.counters["n"] = double(p.num_dofs());
  state.counters["m"] = double(p.size());
}
bool register_reductions() {
  const std::pair<const char*, const char*> problems[] = {
      {"box_stacks", "Box_Stacks-i0035-31-0"}, {"lmgc", "LMGC_GlobalFrictionContactProblem00046"}};
  for (const auto& [label, name] : problems) {
    benchmark::RegisterBenchmark((std::string("BM_GlobalReduction/eigen/") + label).c_str(),
                                 BM_GlobalReduction<EigenBackend>, name);
    benchmark::RegisterBenchmark((std::string("BM_GlobalReduction/suitesparse/") + label).c_str(),
                                 BM_GlobalReduction<SuiteSparseBackend>, name);
  }
  return true;
}
const bool kReductionsRegistered = register_reductions();

}  // namespace

BENCHMARK_MAIN();
