// The storage policies of W and their compile-time check.
//   DenseStorage<D>        small scenes: no index arrays
//   SparseStorage<D>       Eigen CSC, views the user's matrix (column updates)
//   BlockSparseStorage<D>  d x d block rows (row products, Gauss-Seidel)
#pragma once

#include <fcsolve/storage/block_sparse.hpp>
#include <fcsolve/storage/dense.hpp>
#include <fcsolve/storage/sparse.hpp>

#include <type_traits>

namespace fcsolve {

template <class S, class = void>
struct is_storage : std::false_type {};
template <class S>
struct is_storage<S, std::void_t<decltype(S::block_dim), decltype(S::row_access),
                                 decltype(std::declval<const S&>().diagonal_block(Index())),
                                 decltype(std::declval<const S&>().num_blocks())>>
    : std::true_type {};
template <class S>
inline constexpr bool is_storage_v = is_storage<S>::value;

/// Below this many contacts, dense storage beats any sparse layout.
inline constexpr Index kDenseStorageMaxContacts = 16;

}  // namespace fcsolve

namespace fcsolve {

/// The same storage kind with blocks of dimension D: the subproblems of a
/// splitting of the contact law (fixed_point/panagiotopoulos.hpp: normal
/// blocks 1 x 1, tangential blocks (d-1) x (d-1)).
template <class S, int D>
struct rebind_block_dim;
template <int D0, int D>
struct rebind_block_dim<SparseStorage<D0>, D> {
  using type = SparseStorage<D>;
};
template <int D0, class Scalar, int D>
struct rebind_block_dim<DenseStorage<D0, Scalar>, D> {
  using type = DenseStorage<D, Scalar>;
};
template <int D0, class Scalar, int D>
struct rebind_block_dim<BlockSparseStorage<D0, Scalar>, D> {
  using type = BlockSparseStorage<D, Scalar>;
};
template <class S, int D>
using rebind_block_dim_t = typename rebind_block_dim<S, D>::type;

}  // namespace fcsolve
