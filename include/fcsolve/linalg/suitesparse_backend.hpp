// SuiteSparse factorisations: CHOLMOD for SPD matrices, UMFPACK
// (multifrontal LU) for unsymmetric ones, and KLU, where CMake found it, for
// the Newton matrices, which keep one pattern through a solve. CHOLMOD runs
// in its automatic mode: supernodal for FEM-like fill, simplicial for the block-diagonal M of rigid
// bodies, where the supernodal solve with many right-hand sides is 10x slower
// (Spheres-i099, n = 12000: 1.1 s against 0.07 s to form W). Needs the
// fcsolve::cholmod CMake target, which defines FCSOLVE_WITH_CHOLMOD.
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

#ifdef FCSOLVE_WITH_LAPACK
#include <fcsolve/linalg/lapack_dense_lu.hpp>
#endif
#ifdef FCSOLVE_WITH_KLU
#include <fcsolve/linalg/klu_pattern_lu.hpp>
#endif

namespace fcsolve {

struct SuiteSparseBackend {
  using SymmetricSolver = Eigen::CholmodDecomposition<SparseMatrix>;
  using GeneralSolver = Eigen::UmfPackLU<SparseMatrix>;
#ifdef FCSOLVE_WITH_LAPACK
  /// For unsymmetric matrices held sparse but at least half full
  /// (newton/linear_solvers.hpp).
  using DenseLU = LapackDenseLU;
#endif
#ifdef FCSOLVE_WITH_KLU
  /// For the Newton matrices: one pattern per solve, refactorised with the
  /// first factorisation's pivot order (newton/linear_solvers.hpp).
  using PatternLU = KluPatternLU;
#endif
  static constexpr const char* name = "suitesparse";
};

}  // namespace fcsolve
