// Dense storage of W for small scenes: a few contacts pay for no index
// arrays at all. Column-major: a fixed d x d block times a d-vector is then
// d column updates of packets, where a row-major block's row dot products
// ended in horizontal adds (callgrind, bench_nsgs nsgs-small/cube-3: 2% fewer
// instructions a solve, 6% less time).
#pragma once

#include <fcsolve/core/compiler.hpp>
#include <fcsolve/core/small_product.hpp>
#include <fcsolve/storage/storage_types.hpp>

#include <vector>

namespace fcsolve {

template <int D, class Scalar_ = double>
class DenseStorage {
 public:
  FCSOLVE_STORAGE_TYPES(D, Scalar_, true);  // row_access: provides block_row_product

  DenseStorage() = default;
  template <class Sparse>
  explicit DenseStorage(const Sparse& W) { compute(W); }

  template <class Sparse>
  void compute(const Sparse& W) {
    W_ = W.template cast<Scalar>().toDense();
    const Index nb = W_.rows() / D;
    diagonal_.resize(static_cast<std::size_t>(nb));
    for (Index a = 0; a < nb; ++a) diagonal_[a] = W_.template block<D, D>(a * D, a * D);
  }

  Index size() const { return W_.rows(); }
  Index num_blocks() const { return W_.rows() / D; }
  const Block& diagonal_block(Index a) const { return diagonal_[static_cast<std::size_t>(a)]; }

  /// y = W x. A few contacts go block row by block row: Eigen's dynamic
  /// product spent about 430 instructions on 9 x 9 (a third of each FCLIB
  /// error evaluation on 3 contacts: callgrind, bench_nsgs nsgs-small).
  void multiply(const Eigen::Ref<const VectorType>& x, Eigen::Ref<VectorType> y) const {
    if (num_blocks() > kBlockwiseMaxBlocks) {
      y.noalias() = W_ * x;
      return;
    }
    for (Index a = 0; a < num_blocks(); ++a) y.template segment<D>(a * D) = block_row_product(a, x);
  }
  /// (W x)^a = sum_b W^{ab} x^b, block by block: the fixed-size D x D
  /// products unroll, where the D x n row product ran Eigen's dynamic-length
  /// dot products (about 50 more instructions a contact visit on 3 contacts,
  /// 6% of the solve: callgrind, bench_nsgs nsgs-small).
  BlockVector block_row_product(Index a, const Eigen::Ref<const VectorType>& x) const {
    BlockVector y = BlockVector::Zero();
    for (Index b = 0; b < num_blocks(); ++b)
      y.noalias() += W_.template block<D, D>(a * D, b * D) * x.template segment<D>(b * D);
    return y;
  }
  /// (W x)^a - W^{aa} x^a: what a Gauss-Seidel visit of contact a needs,
  /// without multiplying the diagonal block in and out again (two of the
  /// visit's four 3 x 3 products on 3 contacts). Written out, inlined and
  /// templated on x for the reasons of
  /// BlockSparseStorage::off_diagonal_row_product (out of line, its call
  /// and stall put a 3-contact solve back from 1.96 to 2.15 us, bench_nsgs
  /// nsgs-small), with Eigen's bits (product_row()).
  template <class XVector>
  FCSOLVE_ALWAYS_INLINE BlockVector off_diagonal_row_product(Index a, const Eigen::MatrixBase<XVector>& x) const {
    Scalar sum[D] = {};
    for (Index b = 0; b < num_blocks(); ++b) {
      if (b == a) continue;
      const auto block = W_.template block<D, D>(a * D, b * D);
      for (int i = 0; i < D; ++i) sum[i] += product_row(block, i, x, b * D);
    }
    BlockVector y;
    for (int i = 0; i < D; ++i) y[i] = sum[i];
    return y;
  }
  /// y += W^{.a} dx (column block a times dx)
  void add_block_column(Index a, const BlockVector& dx, Eigen::Ref<VectorType> y) const {
    y.noalias() += W_.template middleCols<D>(a * D) * dx;
  }

  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>& matrix() const {
    return W_;
  }

 private:
  static constexpr Index kBlockwiseMaxBlocks = 16;  // the dispatch's dense limit (storage.hpp)
  Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic> W_;
  std::vector<Block, Eigen::aligned_allocator<Block>> diagonal_;
};

}  // namespace fcsolve
