// Helpers shared by the tests: where the FCLIB files are, small problems.
#pragma once

#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/reduction.hpp>

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

namespace fcsolve_test {

/// Set by CMake in the generated test_paths.cpp (tests/test_paths.cpp.in).
namespace paths {
extern const char* const shared_data;   // ../shared/data/fclib beside the checkout
extern const char* const bundled_data;  // examples/data
extern const char* const hostile_data;  // tests/hostile/files
extern const char* const scratch_dir;   // the tests' build folder
}  // namespace paths

/// The shared FCLIB collection: $FCSOLVE_SHARED_DATA when set (CI hides the
/// collection that way to run the tests as a lone clone has them), else
/// ../shared/data/fclib beside the checkout (set by CMake).
inline std::string shared_data_dir() {
  const char* env = std::getenv("FCSOLVE_SHARED_DATA");
  return env && *env ? std::string(env) : std::string(paths::shared_data);
}

inline bool have_shared_data() {
  return std::filesystem::is_directory(std::filesystem::path(shared_data_dir()) / "local");
}

/// The bundled examples/data files of kind `sub` ("local" or "global"), sorted.
inline std::vector<std::string> bundled_files(const std::string& sub) {
  namespace fs = std::filesystem;
  std::vector<std::string> out;
  const auto kind = sub == "local" ? fcsolve::fclib::Kind::Local : fcsolve::fclib::Kind::Global;
  for (const auto& e : fs::directory_iterator(paths::bundled_data))
    if (e.path().extension() == ".hdf5" && fcsolve::fclib::detect_kind(e.path().string()) == kind)
      out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// Every .hdf5 file under `sub` ("local" or "global") of the shared
/// collection, or the bundled examples/data files of that kind when the
/// collection is absent (a fresh clone without ../shared).
inline std::vector<std::string> fclib_files(const std::string& sub) {
  namespace fs = std::filesystem;
  if (!have_shared_data()) return bundled_files(sub);
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(fs::path(shared_data_dir()) / sub))
    if (e.path().extension() == ".hdf5") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// The bundled files of kind `sub`, then the shared collection's (with a
/// warning naming where it was looked for when it is absent).
inline std::vector<std::string> bundled_and_shared_files(const std::string& sub) {
  std::vector<std::string> files = bundled_files(sub);
  if (have_shared_data()) {
    for (const auto& f : fclib_files(sub)) files.push_back(f);
  } else {
    WARN("no shared FCLIB collection at " << shared_data_dir() << ": the bundled " << sub
                                          << " problems only");
  }
  return files;
}

inline std::string hostile(const std::string& name) {
  return std::string(paths::hostile_data) + "/" + name;
}

inline std::string bundled(const std::string& name) {
  return std::string(paths::bundled_data) + "/" + name;
}

/// A per-test scratch file name (ctest -j runs tests in parallel).
inline std::string scratch(const std::string& name) {
  return std::string(paths::scratch_dir) + "/scratch_" + name;
}

/// FC/II from dense data (W stored compressed), for closed-form cases.
inline fcsolve::LocalProblem make_local(int d, const fcsolve::DenseMatrix& W,
                                        const fcsolve::Vector& q, const fcsolve::Vector& mu) {
  fcsolve::LocalProblem p;
  p.d = d;
  p.W = W.sparseView();
  p.W.makeCompressed();
  p.q = q;
  p.mu = mu;
  return p;
}

/// The solver contract's typed errors (docs/architecture.md) for a solver
/// not computed yet: solve() before compute() is a UsageError; mu < 0 in
/// p, a warm start of the wrong size or with a NaN are InvalidProblem.
/// Leaves `solver` computed on p, r and u zero-filled of p's size.
template <class Solver>
void check_contract_errors(Solver& solver, const fcsolve::LocalProblem& p, fcsolve::Vector& r,
                           fcsolve::Vector& u) {
  r = fcsolve::Vector::Zero(p.size());
  u = fcsolve::Vector::Zero(p.size());
  CHECK_THROWS_AS(solver.solve(r, u), fcsolve::UsageError);  // before compute()
  fcsolve::LocalProblem bad = p;
  bad.mu[bad.mu.size() - 1] = -1;
  CHECK_THROWS_AS(solver.compute(bad), fcsolve::InvalidProblem);
  solver.compute(p);
  fcsolve::Vector short_r = fcsolve::Vector::Zero(p.size() - 1);
  CHECK_THROWS_AS(solver.solve(short_r, u), fcsolve::InvalidProblem);
  r[0] = std::nan("");
  CHECK_THROWS_AS(solver.solve(r, u), fcsolve::InvalidProblem);
  r.setZero();
}

/// Solves p from r = 0 (or r0) with a compute()/solve() solver and checks
/// what every solve must: the reported error is the independent one,
/// u = W r + q, r finite. Returns r. (The margin: near 1e-9 the two errors,
/// from u = W r + q summed in different orders, differ by rounding, 1e-15.)
template <class Solver>
fcsolve::Vector solve_checked(Solver& solver, const fcsolve::LocalProblem& p,
                              fcsolve::Vector r0 = fcsolve::Vector()) {
  using fcsolve::Vector;
  solver.compute(p);
  Vector r = r0.size() ? r0 : Vector(Vector::Zero(p.size())), u(p.size());
  solver.solve(r, u);
  CHECK(r.allFinite());
  CHECK(solver.info().error ==
        Approx(fcsolve::local_error(p, r)).epsilon(1e-6).margin(1e-13));
  CHECK((u - (fcsolve::SparseMatrix(p.W) * r + p.q)).norm() <= 1e-12 * (1 + u.norm()));
  return r;
}

/// The FCLIB error of (r, v [, lambda]) on g, its scale from a factorisation
/// of its own (independent of the solver's).
inline double independent_global_error(const fcsolve::GlobalProblem& g, const fcsolve::Vector& r,
                                       const fcsolve::Vector& v,
                                       const fcsolve::Vector& lambda = fcsolve::Vector()) {
  const fcsolve::GlobalReduction<> reduction{fcsolve::GlobalProblemView(g), /*form_W=*/false};
  return fcsolve::global_error_report(g, reduction.free_velocity_norm(), r, v, lambda).error;
}

}  // namespace fcsolve_test
