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
