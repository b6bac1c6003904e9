// The names every storage policy of W declares (checked by is_storage in
// storage.hpp): scalar, block dimension, whether it offers block-row products,
// and its block, block-vector and vector types.
//
// A macro, as Eigen's EIGEN_DENSE_PUBLIC_INTERFACE: a class template does not
// see the names of a dependent base class, so a base that declared them would
// still need every one re-declared in each storage.
#pragma once

#include <fcsolve/core/types.hpp>

#define FCSOLVE_STORAGE_TYPES(D, ScalarType, RowAccess)              \
  using Scalar = ScalarType;                                         \
  static constexpr int block_dim = D;                                \
  static constexpr bool row_access = RowAccess;                      \
  using Block = SmallMatrix<D, Scalar>;                              \
  using BlockVector = SmallVector<D, Scalar>;                        \
  using VectorType = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>
