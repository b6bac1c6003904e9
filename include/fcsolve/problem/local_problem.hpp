// The reduced problem FC/II(W, q, mu) (Acary, Bremond & Huber 2018, eq. 9):
// find r, u in R^m, m = d nc, with
//   u = W r + q,   u~ = u + g(u),   K* ∋ u~ ⊥ r ∈ K   contact by contact,
// g(u)^a = (mu^a ||u_T^a||, 0, 0) and K^a = {||r_T|| <= mu^a r_N}.
//
// LocalProblem owns its data; LocalProblemView maps someone else's (a
// LocalProblem, Eigen objects, raw CSC arrays from Python) without copying.
// Solvers take views.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/types.hpp>
#include <fcsolve/problem/problem_text.hpp>

namespace fcsolve {

struct LocalProblem {
  int d = 3;       ///< contact dimension: 3 (3D Coulomb), 2 (2D Coulomb), 1 (frictionless)
  SparseMatrix W;  ///< m x m Delassus operator, compressed column
  Vector q;        ///< m, free velocity
  Vector mu;       ///< nc, friction coefficients (ignored when d = 1)
  ProblemText text;

  Index size() const { return q.size(); }
  Index num_contacts() const { return mu.size(); }
};

namespace detail {
/// A compressed sparse matrix as a Map (throws if `A` is not compressed:
/// an uncompressed Eigen matrix has gaps a plain CSC map cannot describe).
inline SparseMap map_compressed(const SparseMatrix& A, const char* field) {
  if (!A.isCompressed())
    throw InvalidProblem(field, "sparse matrix must be compressed (call makeCompressed())");
  return SparseMap(A.rows(), A.cols(), A.nonZeros(), A.outerIndexPtr(), A.innerIndexPtr(),
                   A.valuePtr());
}
inline VectorMap map_vector(const Vector& v) { return VectorMap(v.data(), v.size()); }
}  // namespace detail

/// A non-owning view of FC/II data. The viewed arrays must outlive the view
/// and every solver that was compute()d with it.
class LocalProblemView {
 public:
  LocalProblemView(const LocalProblem& p)  // NOLINT: implicit, a problem is a view of itself
      : LocalProblemView(p.d, p.W, p.q, p.mu) {}
  LocalProblemView(int d, const SparseMatrix& W, const Vector& q, const Vector& mu)
      : d(d), W(detail::map_compressed(W, "W")), q(detail::map_vector(q)),
        mu(detail::map_vector(mu)) {}
  LocalProblemView(int d, const SparseMap& W, const VectorMap& q, const VectorMap& mu)
      : d(d), W(W), q(q), mu(mu) {}

  int d;
  SparseMap W;
  VectorMap q;
  VectorMap mu;

  Index size() const { return q.size(); }
  Index num_contacts() const { return mu.size(); }
};

}  // namespace fcsolve
