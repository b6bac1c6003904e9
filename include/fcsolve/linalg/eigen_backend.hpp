// Dependency-free sparse factorisations (Eigen only): the fallback linear
// algebra policy. A policy names a SymmetricSolver (SPD matrices) and a
// GeneralSolver (unsymmetric LU); both follow Eigen's compute/solve/info API.
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

namespace fcsolve {

struct EigenBackend {
  using SymmetricSolver = Eigen::SimplicialLDLT<SparseMatrix>;
  using GeneralSolver = Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>>;
  static constexpr const char* name = "eigen";
};

}  // namespace fcsolve
