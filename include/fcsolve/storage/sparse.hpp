// Eigen compressed-column storage of W, viewed without copying the user's
// matrix. Columns are cheap and rows are not, so Gauss-Seidel on this storage
// keeps u = W r + q up to date with column updates (add_block_column)
// instead of recomputing block rows.
#pragma once

#include <fcsolve/storage/storage_types.hpp>

#include <optional>
#include <vector>

namespace fcsolve {

template <int D>
class SparseStorage {
 public:
  FCSOLVE_STORAGE_TYPES(D, double, false);  // no row access: provides add_block_column only

  SparseStorage() = default;
  /// Views W: it must outlive this storage (as with Eigen's solvers).
  explicit SparseStorage(const SparseMap& W) { compute(W); }

  void compute(const SparseMap& W) {
    W_.emplace(W);  // Map has no assignment: re-seat the view
    const Index nb = W.cols() / D;
    diagonal_.assign(static_cast<std::size_t>(nb), Block::Zero());
    for (Index j = 0; j < W.cols(); ++j) {
      const Index a = j / D;
      for (SparseMap::InnerIterator it(W, j); it; ++it)
        if (it.row() / D == a) diagonal_[a](it.row() - a * D, j - a * D) = it.value();
    }
  }

  Index size() const { return W_ ? W_->rows() : 0; }
  Index num_blocks() const { return size() / D; }
  const Block& diagonal_block(Index a) const { return diagonal_[static_cast<std::size_t>(a)]; }

  void multiply(const Eigen::Ref<const Vector>& x, Eigen::Ref<Vector> y) const {
    y.noalias() = *W_ * x;
  }
  /// y += W^{.a} dx
  void add_block_column(Index a, const BlockVector& dx, Eigen::Ref<Vector> y) const {
    const int* outer = W_->outerIndexPtr();
    const int* inner = W_->innerIndexPtr();
    const double* values = W_->valuePtr();
    for (int k = 0; k < D; ++k) {
      const Index j = a * D + k;
      const double s = dx[k];
      if (s == 0) continue;
      for (int p = outer[j]; p < outer[j + 1]; ++p) y[inner[p]] += values[p] * s;
    }
  }

  const SparseMap& matrix() const { return *W_; }

 private:
  std::optional<SparseMap> W_;
  std::vector<Block, Eigen::aligned_allocator<Block>> diagonal_;
};

}  // namespace fcsolve
