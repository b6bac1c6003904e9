// The Newton matrix of the reduced problem, J = A W + B, with A, B block
// diagonal (one d x d pair per contact, from the formulation):
//   J^{ab} = A^a W^{ab}  (a != b),   J^{aa} = A^a W^{aa} + B^a.
// Its pattern is W's d x d block pattern plus the diagonal blocks, each block
// stored whole, fixed once by compute(): an iteration only rewrites values,
// through positions precomputed here, without allocation. Assembles into a
// compressed-column SparseMatrix (sparse LU) or a DenseMatrix (dense LU).
#pragma once

#include <fcsolve/core/types.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace fcsolve {
namespace detail {

/// Index into A.valuePtr() of the stored entry (row, col); -1 if absent.
inline Index stored_position(const SparseMatrix& A, Index row, Index col) {
  const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[col];
  const int* end = A.innerIndexPtr() + A.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, static_cast<int>(row));
  return (it != end && *it == row) ? static_cast<Index>(it - A.innerIndexPtr()) : -1;
}

}  // namespace detail

template <int D>
class ReducedJacobian {
 public:
  using Block = SmallMatrix<D>;
  using BlockList = std::vector<Block, Eigen::aligned_allocator<Block>>;

  /// Reads W's blocks and fixes the pattern of J.
  void compute(const SparseMap& W) {
    const Index nb = W.cols() / D;
    // block (a, b) keys, sorted by block column then block row, plus the diagonal
    std::vector<std::pair<Index, Index>> keys;  // (b, a)
    for (Index j = 0; j < W.cols(); ++j)
      for (SparseMap::InnerIterator it(W, j); it; ++it) keys.emplace_back(j / D, it.row() / D);
    for (Index a = 0; a < nb; ++a) keys.emplace_back(a, a);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    row_.resize(keys.size());
    col_.resize(keys.size());
    for (std::size_t p = 0; p < keys.size(); ++p) {
      col_[p] = keys[p].first;
      row_[p] = keys[p].second;
    }
    column_start_.assign(nb + 1, Index(keys.size()));
    for (std::size_t p = keys.size(); p-- > 0;) column_start_[col_[p]] = Index(p);
    for (Index b = nb; b-- > 0;) column_start_[b] = std::min(column_start_[b], column_start_[b + 1]);
    w_.assign(keys.size(), Block::Zero());
    w_outer_.assign(W.outerIndexPtr(), W.outerIndexPtr() + W.cols() + 1);
    w_inner_.assign(W.innerIndexPtr(), W.innerIndexPtr() + W.nonZeros());
    read_values(W);
    // the sparse pattern, then where each block column segment lives in it
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(keys.size() * D * D);
    for (std::size_t p = 0; p < keys.size(); ++p)
      for (int k = 0; k < D; ++k)
        for (int i = 0; i < D; ++i) t.emplace_back(int(row_[p] * D + i), int(col_[p] * D + k), 0.0);
    pattern_.resize(nb * D, nb * D);
    pattern_.setFromTriplets(t.begin(), t.end());
    pattern_.makeCompressed();
    position_.resize(keys.size() * D);
    for (std::size_t p = 0; p < keys.size(); ++p)
      for (int k = 0; k < D; ++k)
        position_[p * D + k] = detail::stored_position(pattern_, row_[p] * D, col_[p] * D + k);
    diagonal_.resize(nb * D);
    for (Index i = 0; i < nb * D; ++i) diagonal_[i] = detail::stored_position(pattern_, i, i);
  }

  /// True when W (compressed) has the entries of the W of the last
  /// compute(): then update_values() may replace compute(), and J's pattern,
  /// hence a linear solver's symbolic analysis, stays valid.
  bool same_pattern(const SparseMap& W) const {
    if (!W.isCompressed() || Index(w_outer_.size()) != W.cols() + 1 ||
        Index(w_inner_.size()) != W.nonZeros())
      return false;
    return std::equal(w_outer_.begin(), w_outer_.end(), W.outerIndexPtr()) &&
           std::equal(w_inner_.begin(), w_inner_.end(), W.innerIndexPtr());
  }

  /// Rereads W's values (W has the pattern of the last compute(): see
  /// same_pattern()). Allocates nothing.
  void update_values(const SparseMap& W) {
    for (Block& b : w_) b.setZero();
    read_values(W);
  }

  /// A matrix with J's pattern (sparse) or J's size (dense), values zero.
  void initialise(SparseMatrix& J) const { J = pattern_; }
  void initialise(DenseMatrix& J) const { J.setZero(pattern_.rows(), pattern_.cols()); }

  /// J = A W + B, values only (J from initialise()).
  void assemble(const BlockList& A, const BlockList& B, SparseMatrix& J) const {
    double* values = J.valuePtr();
    for (std::size_t p = 0; p < w_.size(); ++p) {
      Block Jab = A[row_[p]] * w_[p];
      if (row_[p] == col_[p]) Jab += B[row_[p]];
      for (int k = 0; k < D; ++k)
        Eigen::Map<SmallVector<D>>(values + position_[p * D + k]) = Jab.col(k);
    }
  }
  void assemble(const BlockList& A, const BlockList& B, DenseMatrix& J) const {
    for (std::size_t p = 0; p < w_.size(); ++p) {
      auto Jab = J.template block<D, D>(row_[p] * D, col_[p] * D);
      Jab.noalias() = A[row_[p]] * w_[p];
      if (row_[p] == col_[p]) Jab += B[row_[p]];
    }
  }

  /// J += delta I (regularisation of a singular system).
  void add_to_diagonal(double delta, SparseMatrix& J) const {
    for (Index i = 0; i < Index(diagonal_.size()); ++i) J.valuePtr()[diagonal_[i]] += delta;
  }
  void add_to_diagonal(double delta, DenseMatrix& J) const {
    J.diagonal().array() += delta;
  }

  /// max(1, max |J_ii|): the scale of the regularisation shift.
  double diagonal_scale(const SparseMatrix& J) const {
    double s = 1;
    for (const Index p : diagonal_) s = std::max(s, std::abs(J.valuePtr()[p]));
    return s;
  }
  double diagonal_scale(const DenseMatrix& J) const {
    return std::max(1.0, J.diagonal().cwiseAbs().maxCoeff());
  }

  Index num_stored_blocks() const { return Index(w_.size()); }
  Index nonzeros() const { return pattern_.nonZeros(); }

 private:
  // One merge walk per column: W's rows and the stored blocks of a block
  // column are both sorted, so reading W is O(nnz(W)) (a binary search per
  // entry was a fifth of ppa's time on a dense 3072 x 3072 W).
  void read_values(const SparseMap& W) {
    for (Index j = 0; j < W.cols(); ++j) {
      Index p = column_start_[j / D];
      for (SparseMap::InnerIterator it(W, j); it; ++it) {
        const Index a = it.row() / D;
        while (row_[p] < a) ++p;
        w_[p](it.row() % D, j % D) = it.value();
      }
    }
  }

  std::vector<Index> row_, col_;  // block coordinates, sorted by (col, row)
  std::vector<Index> column_start_;  // first stored block of each block column
  BlockList w_;                   // W^{ab}
  SparseMatrix pattern_;
  std::vector<Index> position_;  // value index of entry (a D, b D + k) of block p: [p D + k]
  std::vector<Index> diagonal_;
  std::vector<int> w_outer_, w_inner_;  // W's pattern at compute(), for same_pattern()
};

}  // namespace fcsolve
