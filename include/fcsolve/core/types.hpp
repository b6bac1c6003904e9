// Common Eigen aliases used across fcsolve.
#pragma once

#include <fcsolve/config.hpp>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace fcsolve {

using Index = Eigen::Index;
using Vector = Eigen::VectorXd;
using DenseMatrix = Eigen::MatrixXd;
/// Every sparse matrix fcsolve stores or views: compressed column, int indices
/// (the FCLIB and CHOLMOD/UMFPACK layout, so it maps without copies).
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
using SparseMap = Eigen::Map<const SparseMatrix>;
using VectorMap = Eigen::Map<const Vector>;

template <int D, class Scalar = double>
using SmallVector = Eigen::Matrix<Scalar, D, 1>;
template <int D, class Scalar = double>
using SmallMatrix = Eigen::Matrix<Scalar, D, D>;

}  // namespace fcsolve
