// Validation of problem data at fcsolve's boundary. Every check throws
// InvalidProblem naming the field and the mismatch; nothing is modified.
// Asymmetry of W or M is *not* an error: real FCLIB data is only nearly
// symmetric (see problem/symmetry.hpp).
#pragma once

#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>

#include <cmath>
#include <sstream>
#include <string>

namespace fcsolve {
namespace detail {

inline std::string shape(Index rows, Index cols) {
  return std::to_string(rows) + " x " + std::to_string(cols);
}

/// Compressed-column structure a Map relies on: monotone column pointers,
/// row indices in range and strictly increasing inside each column.
inline void check_sparse_structure(const SparseMap& A, const std::string& field) {
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  if (A.cols() > 0 && outer == nullptr) throw InvalidProblem(field, "missing column pointers");
  if (A.cols() > 0 && outer[0] != 0) throw InvalidProblem(field, "column pointers must start at 0");
  for (Index j = 0; j < A.outerSize(); ++j) {
    if (outer[j + 1] < outer[j])
      throw InvalidProblem(field, "column pointers decrease at column " + std::to_string(j));
    for (int k = outer[j]; k < outer[j + 1]; ++k) {
      if (inner[k] < 0 || inner[k] >= A.rows())
        throw InvalidProblem(field, "row index " + std::to_string(inner[k]) + " out of range [0, " +
                                        std::to_string(A.rows()) + ") in column " +
                                        std::to_string(j));
      if (k > outer[j] && inner[k] <= inner[k - 1])
        throw InvalidProblem(field, "row indices not strictly increasing in column " +
                                        std::to_string(j));
    }
  }
}

template <class Values>
void check_finite(const Values& x, Index count, const std::string& field) {
  for (Index k = 0; k < count; ++k)
    if (!std::isfinite(x[k]))
      throw InvalidProblem(field, "non-finite entry (" + std::to_string(x[k]) + ") at index " +
                                      std::to_string(k));
}

inline void check_matrix(const SparseMap& A, Index rows, Index cols, const std::string& field,
                         const std::string& expectation) {
  if (A.rows() != rows || A.cols() != cols)
    throw InvalidProblem(field, "expected " + shape(rows, cols) + " (" + expectation + "), got " +
                                    shape(A.rows(), A.cols()));
  check_sparse_structure(A, field);
  check_finite(A.valuePtr(), A.nonZeros(), field);
}

inline void check_vector(const VectorMap& v, Index size, const std::string& field,
                         const std::string& expectation) {
  if (v.size() != size)
    throw InvalidProblem(field, "expected " + std::to_string(size) + " entries (" + expectation +
                                    "), got " + std::to_string(v.size()));
  check_finite(v.data(), v.size(), field);
}

/// The contact dimension, and m = d * nc unknowns (m read from `size_field`).
inline void check_contact_size(int d, Index m, const char* size_field) {
  if (d < 1 || d > 3)
    throw InvalidProblem("spacedim", "contact dimension must be 1, 2 or 3, got " + std::to_string(d));
  if (m == 0) throw InvalidProblem(size_field, "empty problem: no contact unknowns");
  if (m % d != 0)
    throw InvalidProblem(size_field, "size " + std::to_string(m) +
                                         " is not a multiple of the contact dimension " +
                                         std::to_string(d));
}
inline void check_friction(const VectorMap& mu, Index nc) {
  check_vector(mu, nc, "mu", "one friction coefficient per contact, m / d");
  for (Index k = 0; k < mu.size(); ++k)
    if (mu[k] < 0)
      throw InvalidProblem("mu", "negative friction coefficient " + std::to_string(mu[k]) +
                                     " at contact " + std::to_string(k));
}
}  // namespace detail

// The matrices set the sizes (W: m; M: n; H: n x m; G: n x p), so that a
// vector of the wrong length is the one blamed, unless the other two sources
// of the same size agree against the matrix (then the matrix is blamed).
inline void validate(const LocalProblemView& p) {
  Index m = p.W.rows();
  if (p.d >= 1 && p.q.size() == p.d * p.mu.size() && p.q.size() != m) m = p.q.size();
  if (p.W.rows() == m && p.W.cols() != m)
    throw InvalidProblem("W", "expected a square matrix, got " + detail::shape(m, p.W.cols()));
  detail::check_contact_size(p.d, m, "W");
  detail::check_matrix(p.W, m, m, "W", "square, m = size of q = d * size of mu");
  detail::check_vector(p.q, m, "q", "m = rows of W");
  detail::check_friction(p.mu, m / p.d);
}

inline void validate(const GlobalProblemView& p) {
  Index n = p.M.rows(), m = p.H.cols();
  if (p.H.rows() == p.f.size() && p.f.size() != n) n = p.f.size();
  if (p.d >= 1 && p.w.size() == p.d * p.mu.size() && p.w.size() != m) m = p.w.size();
  if (n == 0) throw InvalidProblem("M", "empty problem: no degrees of freedom");
  detail::check_contact_size(p.d, m, "H");
  detail::check_matrix(p.M, n, n, "M", "square, n = rows of H = size of f");
  detail::check_matrix(p.H, n, m, "H", "n = rows of M, m = size of w");
  detail::check_vector(p.f, n, "f", "n = rows of M");
  detail::check_vector(p.w, m, "w", "m = columns of H");
  detail::check_friction(p.mu, m / p.d);
  if (p.G.has_value() != p.b.has_value())
    throw InvalidProblem(p.G ? "b" : "G", "G and b must be given together");
  if (p.G) {
    const Index np = p.b->size();
    detail::check_vector(*p.b, np, "b", "p");
    detail::check_matrix(*p.G, n, np, "G", "n = rows of M, p = size of b");
  }
}

/// A solver compiled for contacts of dimension `solver_d` refuses a problem
/// of another dimension (InvalidProblem on "spacedim").
inline void validate_dimension(int problem_d, int solver_d) {
  if (problem_d != solver_d)
    throw InvalidProblem("spacedim", "this solver is compiled for d = " + std::to_string(solver_d) +
                                         ", the problem has d = " + std::to_string(problem_d));
}

/// p, checked (validate) and of the dimension a solver compiled for
/// solver_d solves: what a solver's compute() stores.
inline const LocalProblemView& validated(const LocalProblemView& p, int solver_d) {
  validate_dimension(p.d, solver_d);
  validate(p);
  return p;
}

inline const GlobalProblemView& validated(const GlobalProblemView& p, int solver_d) {
  validate_dimension(p.d, solver_d);
  validate(p);
  return p;
}

inline void validate(const LocalProblem& p) { validate(LocalProblemView(p)); }
inline void validate(const GlobalProblem& p) { validate(GlobalProblemView(p)); }

}  // namespace fcsolve
