// What forming W = H^T M^-1 H of an FC/I problem would cost, estimated from
// the sparsity patterns alone, before anything is factorised.
//
// M^-1 couples two degrees of freedom exactly when they lie in one connected
// component of M's graph (of the saddle-point matrix [M -G; G^T 0] with
// bilateral constraints). Column j of M^-1 H is therefore non-zero on every
// dof of every component that column j of H touches:
//   nnz(M^-1 H) = sum over columns j of H of the sizes of those components.
// Rigid bodies: a component is one body (<= 6 dofs) and H already fills its
// block, so nnz(M^-1 H) = nnz(H) (measured: exactly, on every rigid scene).
// An elastic body is one component: M^-1 H is dense (n x m), and so is W.
// The estimate costs O(nnz(M) + nnz(H) + nnz(G)) (a union-find over dofs).
#pragma once

#include <fcsolve/problem/global_problem.hpp>

#include <algorithm>
#include <numeric>
#include <vector>

namespace fcsolve {

namespace detail {

/// Disjoint sets over 0..n-1 with path halving and union by size.
class DisjointSets {
 public:
  explicit DisjointSets(Index n) : parent_(static_cast<std::size_t>(n)), size_(parent_.size(), 1) {
    std::iota(parent_.begin(), parent_.end(), Index(0));
  }
  Index find(Index i) {
    while (parent_[std::size_t(i)] != i) {
      parent_[std::size_t(i)] = parent_[std::size_t(parent_[std::size_t(i)])];
      i = parent_[std::size_t(i)];
    }
    return i;
  }
  /// Size of the set whose root is `root`.
  Index size(Index root) const { return size_[std::size_t(root)]; }
  void join(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[std::size_t(a)] < size_[std::size_t(b)]) std::swap(a, b);
    parent_[std::size_t(b)] = a;
    size_[std::size_t(a)] += size_[std::size_t(b)];
  }

 private:
  std::vector<Index> parent_, size_;
};

}  // namespace detail

/// nnz(M^-1 H) as above (a double: n m overflows int quickly).
inline double inverse_mass_times_h_nonzeros(const GlobalProblemView& p) {
  const Index n = p.num_dofs();
  if (n == 0 || p.num_contacts() == 0) return 0;
  detail::DisjointSets dofs(n);
  for (Index j = 0; j < p.M.outerSize(); ++j)
    for (SparseMap::InnerIterator it(p.M, j); it; ++it) dofs.join(it.row(), j);
  if (p.has_bilateral()) {
    // A bilateral constraint couples every dof of its column of G.
    for (Index j = 0; j < p.G->outerSize(); ++j) {
      Index first = -1;
      for (SparseMap::InnerIterator it(*p.G, j); it; ++it) {
        if (first < 0) first = it.row();
        else dofs.join(first, it.row());
      }
    }
  }
  std::vector<Index> seen_in_column(static_cast<std::size_t>(n), -1);
  double nonzeros = 0;
  for (Index j = 0; j < p.H.outerSize(); ++j)
    for (SparseMap::InnerIterator it(p.H, j); it; ++it) {
      const Index root = dofs.find(it.row());
      if (seen_in_column[std::size_t(root)] == j) continue;
      seen_in_column[std::size_t(root)] = j;
      nonzeros += double(dofs.size(root));
    }
  return nonzeros;
}

}  // namespace fcsolve
