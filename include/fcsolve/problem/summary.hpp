// A one-look summary of a problem (what `fcsolve info` prints).
#pragma once

#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <string>

namespace fcsolve {

struct ProblemSummary {
  std::string kind;  ///< "local" or "global"
  int d = 3;
  Index nc = 0, n = 0, m = 0, p = 0;  ///< contacts, dofs (global), unknowns, bilateral rows
  /// Stored entries per matrix (explicit zeros included, as scipy's nnz) and
  /// nonzero values (explicit zeros excluded, as shared/data MANIFEST.csv).
  Index nnz_W = 0, nnz_M = 0, nnz_H = 0, nnz_G = 0;
  Index nonzeros_W = 0, nonzeros_M = 0, nonzeros_H = 0, nonzeros_G = 0;
  double mu_min = 0, mu_max = 0;
  double asymmetry = 0;  ///< ||A - A^T||_F / ||A||_F of W (local) or M (global)
  std::string title;
};

namespace detail {
inline Index count_nonzero_values(const SparseMap& A) {
  Index k = 0;
  for (Index e = 0; e < A.nonZeros(); ++e) k += A.valuePtr()[e] != 0.0;
  return k;
}
/// What both kinds report: sizes, the range of mu, the asymmetry of the
/// matrix the solvers factorise or sweep (W for FC/II, M for FC/I).
template <class View>
ProblemSummary common_summary(const char* kind, const View& p, const SparseMap& A) {
  ProblemSummary s;
  s.kind = kind;
  s.d = p.d;
  s.nc = p.num_contacts();
  s.m = p.size();
  s.mu_min = p.mu.size() ? p.mu.minCoeff() : 0.0;
  s.mu_max = p.mu.size() ? p.mu.maxCoeff() : 0.0;
  s.asymmetry = relative_asymmetry(A);
  return s;
}
}  // namespace detail

inline ProblemSummary summarize(const LocalProblemView& p) {
  ProblemSummary s = detail::common_summary("local", p, p.W);
  s.nnz_W = p.W.nonZeros();
  s.nonzeros_W = detail::count_nonzero_values(p.W);
  return s;
}

inline ProblemSummary summarize(const GlobalProblemView& p) {
  ProblemSummary s = detail::common_summary("global", p, p.M);
  s.n = p.num_dofs();
  s.nnz_M = p.M.nonZeros();
  s.nnz_H = p.H.nonZeros();
  s.nonzeros_M = detail::count_nonzero_values(p.M);
  s.nonzeros_H = detail::count_nonzero_values(p.H);
  if (p.G) {
    s.p = p.G->cols();
    s.nnz_G = p.G->nonZeros();
    s.nonzeros_G = detail::count_nonzero_values(*p.G);
  }
  return s;
}

}  // namespace fcsolve
