// What a linear-algebra backend offers beyond its SymmetricSolver and
// GeneralSolver (linalg/*_backend.hpp), and when the factorisations of a
// fixed-pattern matrix use it:
//   B::PatternLU  an LU that refactorises matrices of one pattern with the
//                 first factorisation's pivot order (KLU)
//   B::DenseLU    a dense LU for a (nearly) full matrix held sparse (LAPACK)
// Without them, has_*::type is an empty stand-in, so a member of that type
// costs nothing.
#pragma once

#include <type_traits>

namespace fcsolve {

template <class B, class = void>
struct has_pattern_lu : std::false_type {
  struct type {};
};
template <class B>
struct has_pattern_lu<B, std::void_t<typename B::PatternLU>> : std::true_type {
  using type = typename B::PatternLU;
};

template <class B, class = void>
struct has_dense_lu : std::false_type {
  struct type {};
};
template <class B>
struct has_dense_lu<B, std::void_t<typename B::DenseLU>> : std::true_type {
  using type = typename B::DenseLU;
};

/// Largest mean dense-update length (the symbolic analysis' flops per
/// entry of L and U) at which an unsymmetric matrix of fixed pattern goes
/// to the backend's PatternLU rather than its multifrontal GeneralSolver.
/// nsn-ac and nsn-ac-global to 1e-8, KLU (refactorising) against UMFPACK,
/// whole solves (docs/results.md): rigid bodies' Newton matrices measure 2
/// to 47 and KLU is 2 to 6x faster; walls and towers of 100 to 1000
/// contacts on W, 85 to 91: even; elastic bodies on FC/I, 55 to 72: even,
/// 135 to 630: UMFPACK 1.4 to 8x faster (its dense fronts run in BLAS).
inline constexpr double kPatternLuMaxFlopsPerEntry = 64;

/// Analyses A's pattern with `lu` (a backend's PatternLU) and says whether
/// A goes to it: the analysis succeeded and its flops per factor entry are
/// at most kPatternLuMaxFlopsPerEntry. The one rule of the Newton and the
/// interior-point systems.
template <class PatternLU, class Sparse>
bool pattern_lu_suits(PatternLU& lu, const Sparse& A) {
  return lu.analyse(A) && lu.flops_per_factor_entry() <= kPatternLuMaxFlopsPerEntry;
}

}  // namespace fcsolve
