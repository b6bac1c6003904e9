// libFuzzer target: bytes -> a file -> the FCLIB reader -> (global) the
// reduction -> a few NSGS sweeps on what was read (issue 15). A file is
// untrusted input: every outcome must be a value or one of fcsolve's
// exceptions (IoError, InvalidProblem, UsageError); anything else (a signal,
// a sanitizer report, another exception) is a bug the fuzzer reports.
//
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DFCSOLVE_BUILD_FUZZ=ON
//   build-fuzz/fuzz/fuzz_fclib -max_len=200000 fuzz/corpus fuzz/seeds
#include <fcsolve/problem/error.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/nsgs.hpp>
#include <fcsolve/problem/reduction.hpp>

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace {

/// One scratch file per process, rewritten for every input.
const std::string& scratch_path() {
  static const std::string path = "/tmp/fcsolve-fuzz-" + std::to_string(getpid()) + ".hdf5";
  return path;
}

void solve_a_little(const fcsolve::LocalProblemView& p) {
  if (p.size() > 3000) return;  // keep each input fast; the reader is the target
  fcsolve::Vector r = fcsolve::Vector::Zero(p.size()), u(p.size());
  fcsolve::dispatch_cone(p.d, [&](auto cone) {
    using Cone = decltype(cone);
    fcsolve::Nsgs<Cone, fcsolve::BlockSparseStorage<Cone::dim>> nsgs;
    nsgs.settings().max_iter = 3;
    nsgs.compute(p);
    nsgs.solve(r, u);
    return 0;
  });
  (void)fcsolve::local_error(p, r);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = scratch_path();
  if (std::FILE* f = std::fopen(path.c_str(), "wb")) {
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  try {
    const fcsolve::fclib::Problem problem = fcsolve::fclib::read_problem(path);
    if (const auto* local = std::get_if<fcsolve::LocalProblem>(&problem)) {
      solve_a_little(fcsolve::LocalProblemView(*local));
    } else {
      const auto& global = std::get<fcsolve::GlobalProblem>(problem);
      if (global.num_dofs() <= 3000) {
        fcsolve::GlobalReduction<> reduction{fcsolve::GlobalProblemView(global)};
        solve_a_little(reduction.local());
      }
    }
    (void)fcsolve::fclib::read_guesses(path);
    (void)fcsolve::fclib::read_solution(path);
  } catch (const fcsolve::IoError&) {
  } catch (const fcsolve::InvalidProblem&) {
  } catch (const fcsolve::UsageError&) {
  }
  return 0;
}
