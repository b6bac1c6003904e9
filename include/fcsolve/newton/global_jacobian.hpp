// The Newton matrix of the global form of FC/I in the unknowns (v, r):
//   K = [ M      -H ]   rows: M v - H r - f = 0          (n)
//       [ A H^T   B ]         G(r, H^T v + w) = 0        (m = d nc)
// (B + c A with a contact compliance c, u = H^T v + w + c r: the proximal
// subproblem of ppa/proximal_point_global.hpp).
// (A, B block diagonal from the formulation). M and H are copied into the
// pattern once; an iteration rewrites only the A H^T and B blocks, through
// positions precomputed here. In column i (a degree of freedom) the rows of
// contact a that touch i are d consecutive entries, so A^a h_{a,i} (h_{a,i}
// = row i of H restricted to contact a) is written as one d-vector.
#pragma once

#include <fcsolve/newton/reduced_jacobian.hpp>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace fcsolve {

template <int D>
class GlobalJacobian {
 public:
  using Block = SmallMatrix<D>;
  using BlockList = std::vector<Block, Eigen::aligned_allocator<Block>>;

  void compute(const SparseMap& M, const SparseMap& H) {
    const Index n = M.rows(), m = H.cols(), nc = m / D;
    // (contact, dof, component, H value), grouped by (contact, dof)
    std::vector<std::tuple<Index, Index, int, double>> entries;
    for (Index c = 0; c < m; ++c)
      for (SparseMap::InnerIterator it(H, c); it; ++it)
        entries.emplace_back(c / D, it.row(), int(c % D), it.value());
    std::sort(entries.begin(), entries.end());
    contact_.clear();
    dof_.clear();
    h_.clear();
    for (const auto& [a, i, k, x] : entries) {
      if (contact_.empty() || contact_.back() != a || dof_.back() != i) {
        contact_.push_back(a);
        dof_.push_back(i);
        h_.push_back(SmallVector<D>::Zero());
      }
      h_.back()[k] = x;
    }
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(std::size_t(M.nonZeros() + H.nonZeros()) + h_.size() * D + std::size_t(nc) * D * D);
    for (Index j = 0; j < n; ++j)
      for (SparseMap::InnerIterator it(M, j); it; ++it) t.emplace_back(int(it.row()), int(j), it.value());
    for (Index c = 0; c < m; ++c)
      for (SparseMap::InnerIterator it(H, c); it; ++it) t.emplace_back(int(it.row()), int(n + c), -it.value());
    for (std::size_t p = 0; p < h_.size(); ++p)
      for (int k = 0; k < D; ++k) t.emplace_back(int(n + contact_[p] * D + k), int(dof_[p]), 0.0);
    for (Index a = 0; a < nc; ++a)
      for (int k = 0; k < D; ++k)
        for (int i = 0; i < D; ++i) t.emplace_back(int(n + a * D + i), int(n + a * D + k), 0.0);
    pattern_.resize(n + m, n + m);
    pattern_.setFromTriplets(t.begin(), t.end());
    pattern_.makeCompressed();
    coupling_position_.resize(h_.size());
    for (std::size_t p = 0; p < h_.size(); ++p)
      coupling_position_[p] = detail::stored_position(pattern_, n + contact_[p] * D, dof_[p]);
    block_position_.resize(m);
    for (Index a = 0; a < nc; ++a)
      for (int k = 0; k < D; ++k)
        block_position_[a * D + k] = detail::stored_position(pattern_, n + a * D, n + a * D + k);
  }

  /// K with M and -H in place, the contact rows zero.
  void initialise(SparseMatrix& K) const { K = pattern_; }

  /// Writes A H^T and B into K (values only); with a contact compliance c
  /// (u = H^T v + w + c r) the r-block is B + c A, as dG/dr = A du/dr + B.
  void assemble(const BlockList& A, const BlockList& B, SparseMatrix& K, double compliance = 0) const {
    double* values = K.valuePtr();
    for (std::size_t p = 0; p < h_.size(); ++p)
      Eigen::Map<SmallVector<D>>(values + coupling_position_[p]) = A[contact_[p]] * h_[p];
    auto write = [&](std::size_t a, const Block& block) {
      for (int k = 0; k < D; ++k)
        Eigen::Map<SmallVector<D>>(values + block_position_[a * D + k]) = block.col(k);
    };
    if (compliance == 0) {
      for (std::size_t a = 0; a < B.size(); ++a) write(a, B[a]);
    } else {
      for (std::size_t a = 0; a < B.size(); ++a) write(a, B[a] + compliance * A[a]);
    }
  }

  /// B += delta I: the shift acts on the contact rows only (on the reduced
  /// system it is J + delta I, as in the reduced form).
  void add_to_diagonal(double delta, SparseMatrix& K) const {
    for (std::size_t c = 0; c < block_position_.size(); ++c)
      K.valuePtr()[block_position_[c] + Index(c % D)] += delta;
  }
  /// max(1, max |B_ii|) over the contact rows.
  double diagonal_scale(const SparseMatrix& K) const {
    double s = 1;
    for (std::size_t c = 0; c < block_position_.size(); ++c)
      s = std::max(s, std::abs(K.valuePtr()[block_position_[c] + Index(c % D)]));
    return s;
  }

  Index nonzeros() const { return pattern_.nonZeros(); }

 private:
  std::vector<Index> contact_, dof_;  // (contact, dof) pairs with H(dof, contact) != 0
  std::vector<SmallVector<D>, Eigen::aligned_allocator<SmallVector<D>>> h_;
  SparseMatrix pattern_;
  std::vector<Index> coupling_position_, block_position_;
};

}  // namespace fcsolve
