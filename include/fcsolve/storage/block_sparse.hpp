// d x d block-sparse row storage (BSR) of W: the natural layout for
// Gauss-Seidel sweeps. Block row a lists its nonzero blocks contiguously,
// the diagonal block is directly addressable, and a block-row product
// touches only the blocks of that row, without allocation.
#pragma once

#include <fcsolve/core/compiler.hpp>
#include <fcsolve/core/small_product.hpp>
#include <fcsolve/storage/storage_types.hpp>

#include <vector>

namespace fcsolve {

template <int D, class Scalar_ = double>
class BlockSparseStorage {
 public:
  FCSOLVE_STORAGE_TYPES(D, Scalar_, true);

  BlockSparseStorage() = default;
  template <class Sparse>
  explicit BlockSparseStorage(const Sparse& W) { compute(W); }

  /// Builds the BSR structure of W (m x m, m a multiple of D). A block that
  /// holds any stored entry is kept whole; missing diagonal blocks are zero.
  template <class Sparse>
  void compute(const Sparse& W) {
    const Eigen::SparseMatrix<Scalar, Eigen::RowMajor, int> Wr = W.template cast<Scalar>();
    size_ = Wr.rows();
    const Index nb = size_ / D;
    row_start_.assign(static_cast<std::size_t>(nb + 1), 0);
    column_.clear();
    blocks_.clear();
    diagonal_.assign(static_cast<std::size_t>(nb), Block::Zero());
    diagonal_at_.assign(static_cast<std::size_t>(nb), 0);
    std::vector<Index> slot(static_cast<std::size_t>(nb), -1);  // block column -> position in row
    for (Index a = 0; a < nb; ++a) {
      const Index first = static_cast<Index>(blocks_.size());
      for (int k = 0; k < D; ++k) {
        const Index i = a * D + k;
        for (typename decltype(Wr)::InnerIterator it(Wr, i); it; ++it) {
          const Index b = it.col() / D;
          if (slot[b] < 0) {
            slot[b] = static_cast<Index>(blocks_.size());
            blocks_.push_back(Block::Zero());
            column_.push_back(b);
          }
          blocks_[slot[b]](k, it.col() - b * D) = it.value();
        }
      }
      diagonal_at_[static_cast<std::size_t>(a)] = static_cast<Index>(blocks_.size());  // none stored
      for (Index p = first; p < static_cast<Index>(blocks_.size()); ++p) {
        if (column_[p] == a) {
          diagonal_[a] = blocks_[p];
          diagonal_at_[static_cast<std::size_t>(a)] = p;
        }
        slot[column_[p]] = -1;
      }
      row_start_[a + 1] = static_cast<Index>(blocks_.size());
    }
  }

  Index size() const { return size_; }
  Index num_blocks() const { return size_ / D; }
  Index num_stored_blocks() const { return static_cast<Index>(blocks_.size()); }
  const Block& diagonal_block(Index a) const { return diagonal_[static_cast<std::size_t>(a)]; }

  /// (W x)^a = sum_b W^{ab} x^b over the stored blocks of row a.
  BlockVector block_row_product(Index a, const Eigen::Ref<const VectorType>& x) const {
    BlockVector acc = BlockVector::Zero();
    for (Index p = row_start_[a]; p < row_start_[a + 1]; ++p)
      acc.noalias() += blocks_[p] * x.template segment<D>(column_[p] * D);
    return acc;
  }
  /// (W x)^a - W^{aa} x^a over the stored blocks of row a (a Gauss-Seidel
  /// visit's right-hand side).
  /// Two loops around the diagonal's position instead of a test of every
  /// block's column: the same sum in the same order, without a branch per
  /// block whose outcome moves from row to row (sphere pile of 10^4
  /// contacts: a sweep 12-16% faster, docs/results.md).
  ///
  /// Written out in scalars, inlined, templated on x (the sweep passes a
  /// Ref<Vector>). Through Eigen's product and out of line, a visit built a
  /// Ref<const Vector> for the call (a constructor call, a free() of its
  /// empty copy), kept the sum in the returned vector's memory (a store and
  /// a reload a block) and was read back through a store-forwarding stall:
  /// a fifth of a sweep on the pile (perf); inlined through Eigen, the
  /// block products went out of line in a large translation unit. Each
  /// block's entries are summed as Eigen's product sums them, then added
  /// (product_row(), core/small_product.hpp): the same bits.
  template <class XVector>
  FCSOLVE_ALWAYS_INLINE BlockVector off_diagonal_row_product(Index a, const Eigen::MatrixBase<XVector>& x) const {
    Scalar sum[D] = {};
    const Index diagonal = diagonal_at_[static_cast<std::size_t>(a)];
    for (Index p = row_start_[a]; p < diagonal; ++p)
      for (int i = 0; i < D; ++i) sum[i] += product_row(blocks_[p], i, x, column_[p] * D);
    for (Index p = diagonal + 1; p < row_start_[a + 1]; ++p)
      for (int i = 0; i < D; ++i) sum[i] += product_row(blocks_[p], i, x, column_[p] * D);
    BlockVector acc;
    for (int i = 0; i < D; ++i) acc[i] = sum[i];
    return acc;
  }
  /// Asks the caches for row a's first blocks and block columns, a few
  /// contacts ahead of the sweep's visit (nsgs/nsgs_solver.hpp,
  /// ordered_sweep): as many lines as a row of 10 blocks holds (a sphere
  /// pile's rows hold 8 on average). A longer row's tail is left to the
  /// hardware prefetcher, which sees it as the stream it is.
  FCSOLVE_ALWAYS_INLINE void prefetch_row(Index a) const {
    constexpr int kBlockLines = cache_lines_spanned(10 * sizeof(Block));
    constexpr int kColumnLines = cache_lines_spanned(10 * sizeof(Index));
    const auto first = static_cast<std::size_t>(row_start_[static_cast<std::size_t>(a)]);
    prefetch_lines<kBlockLines>(blocks_.data() + first);
    prefetch_lines<kColumnLines>(column_.data() + first);
  }
  void multiply(const Eigen::Ref<const VectorType>& x, Eigen::Ref<VectorType> y) const {
    for (Index a = 0; a < num_blocks(); ++a) y.template segment<D>(a * D) = block_row_product(a, x);
  }
  /// y += W^{.a} dx: needs a column scan of the BSR rows, so it is slow;
  /// present for completeness (Gauss-Seidel uses block_row_product here).
  void add_block_column(Index a, const BlockVector& dx, Eigen::Ref<VectorType> y) const {
    for (Index b = 0; b < num_blocks(); ++b)
      for (Index p = row_start_[b]; p < row_start_[b + 1]; ++p)
        if (column_[p] == a) y.template segment<D>(b * D) += blocks_[p] * dx;
  }

  // Raw BSR arrays (for assembling Jacobians with W's block pattern).
  const std::vector<Index>& row_start() const { return row_start_; }
  const std::vector<Index>& block_column() const { return column_; }
  const Block& block(Index p) const { return blocks_[static_cast<std::size_t>(p)]; }

 private:
  Index size_ = 0;
  std::vector<Index> row_start_, column_;
  std::vector<Index> diagonal_at_;  ///< position of row a's diagonal block, or its row's end if none
  std::vector<Block, Eigen::aligned_allocator<Block>> blocks_, diagonal_;
};

}  // namespace fcsolve
