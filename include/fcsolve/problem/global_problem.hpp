// The global problem FC/I(M, H, f, w, mu) (Acary, Bremond & Huber 2018, eq. 8)
// and FCLIB's GM3DFC with bilateral constraints (G, b):
//   M v = H r + G lambda + f,   G^T v + b = 0,   u = H^T v + w,
//   u~ = u + g(u),   K* ∋ u~ ⊥ r ∈ K.
// M is n x n, H is n x m (m = d nc), G is n x p. Without G, p = 0.
#pragma once

#include <fcsolve/problem/local_problem.hpp>

#include <optional>

namespace fcsolve {

struct GlobalProblem {
  int d = 3;
  SparseMatrix M;  ///< n x n (FCLIB says SPD; real files are only nearly symmetric)
  SparseMatrix H;  ///< n x m
  SparseMatrix G;  ///< n x p bilateral constraints; empty (0 columns) when absent
  Vector f;        ///< n
  Vector w;        ///< m
  Vector b;        ///< p
  Vector mu;       ///< nc
  ProblemText text;

  Index num_dofs() const { return f.size(); }
  Index size() const { return w.size(); }
  Index num_contacts() const { return mu.size(); }
  bool has_bilateral() const { return G.cols() > 0; }
};

/// A non-owning view of FC/I data (see LocalProblemView for lifetimes).
class GlobalProblemView {
 public:
  GlobalProblemView(const GlobalProblem& p)  // NOLINT: implicit
      : d(p.d), M(detail::map_compressed(p.M, "M")), H(detail::map_compressed(p.H, "H")),
        f(detail::map_vector(p.f)), w(detail::map_vector(p.w)), mu(detail::map_vector(p.mu)) {
    if (p.G.cols() > 0 || p.b.size() > 0) {
      G.emplace(detail::map_compressed(p.G, "G"));
      b.emplace(detail::map_vector(p.b));
    }
  }
  GlobalProblemView(int d, const SparseMap& M, const SparseMap& H, const VectorMap& f,
                    const VectorMap& w, const VectorMap& mu)
      : d(d), M(M), H(H), f(f), w(w), mu(mu) {}

  int d;
  SparseMap M, H;
  VectorMap f, w, mu;
  std::optional<SparseMap> G;  ///< set together with b
  std::optional<VectorMap> b;

  Index num_dofs() const { return f.size(); }
  Index size() const { return w.size(); }
  Index num_contacts() const { return mu.size(); }
  bool has_bilateral() const { return G.has_value(); }
};

}  // namespace fcsolve
