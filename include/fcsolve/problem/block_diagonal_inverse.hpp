// M^-1 of a block-diagonal M (rigid bodies: one small block per body), formed
// block by block, so that W = H^T M^-1 H costs two sparse products.
//
// Forming M^-1 H through a sparse factorisation solves one right-hand side
// per column of H: O(n) each, O(n m) in all, quadratic in the number of
// contacts (measured: 15-20 s at 10^4 contacts). When M's graph falls apart
// into small connected components (problem/reduced_density.hpp), M^-1 is
// block-diagonal with the same blocks and each block is inverted densely:
// O(sum of s^3) over blocks of size s, linear in the number of bodies.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/problem/reduced_density.hpp>

#include <Eigen/Dense>

#include <optional>
#include <vector>

namespace fcsolve {

/// Largest connected component of M's graph inverted as a dense block: a
/// rigid body has 6 dofs (3 in 2D); larger components are elastic bodies,
/// for which M^-1 is dense and the factorisation is the right tool.
inline constexpr Index kMaxDenseInverseBlock = 24;

/// M^-1 as a sparse matrix when M is block-diagonal with blocks of at most
/// kMaxDenseInverseBlock dofs (in any dof order), std::nullopt otherwise or
/// when a block is singular (the caller's factorisation then reports it).
/// `symmetric`: M is symmetric up to rounding; each block is then inverted
/// by Cholesky (LDL^T) and the inverse symmetrised, so that W stays symmetric.
inline std::optional<SparseMatrix> block_diagonal_inverse(const SparseMap& M, bool symmetric) {
  const Index n = M.cols();
  if (n == 0 || M.rows() != n) return std::nullopt;
  detail::DisjointSets dofs(n);
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMap::InnerIterator it(M, j); it; ++it) dofs.join(it.row(), j);

  // Number the components and the dofs inside each one.
  const std::size_t dof_count = static_cast<std::size_t>(n);
  std::vector<Index> block_of(dof_count, -1), position(dof_count, 0);
  std::vector<std::vector<Index>> members;
  std::vector<Index> block_of_root(dof_count, -1);
  for (Index i = 0; i < n; ++i) {
    Index& b = block_of_root[std::size_t(dofs.find(i))];
    if (b < 0) {
      b = Index(members.size());
      members.emplace_back();
    }
    block_of[std::size_t(i)] = b;
    position[std::size_t(i)] = Index(members[std::size_t(b)].size());
    members[std::size_t(b)].push_back(i);
    if (Index(members[std::size_t(b)].size()) > kMaxDenseInverseBlock) return std::nullopt;
  }

  std::vector<Eigen::MatrixXd> blocks(members.size());
  for (std::size_t b = 0; b < members.size(); ++b) {
    const Index s = Index(members[b].size());
    blocks[b].setZero(s, s);
  }
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SparseMap::InnerIterator it(M, j); it; ++it) {
      const std::size_t b = std::size_t(block_of[std::size_t(j)]);
      blocks[b](position[std::size_t(it.row())], position[std::size_t(j)]) += it.value();
    }

  std::vector<Eigen::Triplet<double, int>> entries;
  std::size_t count = 0;
  for (const auto& m : members) count += m.size() * m.size();
  entries.reserve(count);
  Eigen::MatrixXd inverse;
  for (std::size_t b = 0; b < members.size(); ++b) {
    const Eigen::MatrixXd& block = blocks[b];
    const Index s = block.rows();
    const Eigen::MatrixXd identity = Eigen::MatrixXd::Identity(s, s);
    if (symmetric) {
      Eigen::LDLT<Eigen::MatrixXd> ldlt(block);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive() || ldlt.rcond() < 1e-14)
        return std::nullopt;
      inverse = ldlt.solve(identity);
      inverse = 0.5 * (inverse + inverse.transpose()).eval();
    } else {
      Eigen::PartialPivLU<Eigen::MatrixXd> lu(block);
      if (!(lu.rcond() >= 1e-14)) return std::nullopt;
      inverse = lu.solve(identity);
    }
    if (!inverse.allFinite()) return std::nullopt;
    for (Index c = 0; c < s; ++c)
      for (Index r = 0; r < s; ++r)
        if (inverse(r, c) != 0.0)  // a diagonal M keeps a diagonal inverse
          entries.emplace_back(int(members[b][std::size_t(r)]), int(members[b][std::size_t(c)]),
                             inverse(r, c));
  }
  SparseMatrix Minv(n, n);
  Minv.setFromTriplets(entries.begin(), entries.end());
  Minv.makeCompressed();
  return Minv;
}

}  // namespace fcsolve
