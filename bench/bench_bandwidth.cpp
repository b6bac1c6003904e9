// Memory bandwidth of this machine (STREAM-like: Copy a[i] = b[i] and a
// read-only Sum over arrays far larger than the caches), with 1 and 2
// OpenMP threads: the ceiling for the NSGS sweep, which streams W's blocks
// once per sweep (docs/results.md, "Parallel NSGS").
//   ./build/bench/bench_bandwidth --benchmark_repetitions=3
// bytes_per_second counts what the kernel moves: 16 bytes an element for
// Copy (read + write, STREAM's convention), 8 for Sum.
// Built without OpenMP, the 2-thread runs use one thread.
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

namespace {

constexpr std::size_t kElements = std::size_t(1) << 25;  // 256 MiB of doubles an array

void BM_Copy(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> a(kElements, 0.0), b(kElements, 1.0);
  const long n = static_cast<long>(kElements);
  for (auto _ : state) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < n; ++i) a[i] = b[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  state.SetBytesProcessed(state.iterations() * int64_t(kElements) * 16);
}

void BM_Sum(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  std::vector<double> b(kElements, 1.0);
  const long n = static_cast<long>(kElements);
  for (auto _ : state) {
    double sum = 0;
    // 8 independent partial sums: one chain of dependent additions would
    // measure the adder's latency, not the memory.
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : sum)
    for (long i = 0; i < n; i += 8) {
      double part[8];
      for (int k = 0; k < 8; ++k) part[k] = b[i + k];
      sum += ((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7]));
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(state.iterations() * int64_t(kElements) * 8);
}

}  // namespace

// One thread on CPU time (what the kernel gets while it runs, on a shared
// machine), and 1 and 2 threads on wall time.
BENCHMARK(BM_Copy)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Copy)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Sum)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Sum)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
