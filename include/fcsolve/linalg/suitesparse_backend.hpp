// SuiteSparse factorisations: CHOLMOD (supernodal Cholesky) for SPD matrices
// and UMFPACK (multifrontal LU) for unsymmetric ones. Needs the
// fcsolve::cholmod CMake target, which defines FCSOLVE_WITH_CHOLMOD.
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/CholmodSupport>
#include <Eigen/UmfPackSupport>

namespace fcsolve {

struct SuiteSparseBackend {
  using SymmetricSolver = Eigen::CholmodSupernodalLLT<SparseMatrix>;
  using GeneralSolver = Eigen::UmfPackLU<SparseMatrix>;
  static constexpr const char* name = "suitesparse";
};

}  // namespace fcsolve
