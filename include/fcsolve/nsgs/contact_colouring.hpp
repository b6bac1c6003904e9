// A colouring of the contact graph for the parallel NSGS sweep: contacts a
// and b conflict when W stores a block W^{ab} or W^{ba} (they share a body),
// and no two contacts of one colour conflict. Gauss-Seidel with the contacts
// visited colour by colour is then a Jacobi step inside each colour: a
// contact of colour c reads only reactions of other colours, so the contacts
// of c can be updated in any order, or at the same time: the multicolour
// ordering of Gauss-Seidel (Saad, Iterative Methods for Sparse Linear
// Systems, 2nd ed. 2003, sec. 12.4), here on d x d blocks.
#pragma once

#include <fcsolve/core/types.hpp>

#include <algorithm>
#include <vector>

namespace fcsolve {

/// Contacts grouped by colour: colour c is
/// contacts[start[c]], ..., contacts[start[c + 1] - 1], in increasing order.
struct ContactColouring {
  std::vector<Index> start{0};
  std::vector<Index> contacts;

  Index num_colours() const { return static_cast<Index>(start.size()) - 1; }
};

/// The contact graph of W (m x m, blocks of size d): for every contact a,
/// the other contacts b with a stored entry in block (a, b) or (b, a), as
/// compressed rows (neighbours of a: adjacency[offsets[a] .. offsets[a+1])).
struct ContactGraph {
  std::vector<Index> offsets, adjacency;
};

inline ContactGraph contact_graph(const SparseMap& W, int d) {
  const Index nc = W.cols() / d;
  // Each stored entry gives a pair in both directions; sort and unique them.
  std::vector<std::pair<Index, Index>> pairs;
  pairs.reserve(static_cast<std::size_t>(2 * W.nonZeros() / (d * d) + 1));
  for (Index j = 0; j < W.outerSize(); ++j)
    for (SparseMap::InnerIterator it(W, j); it; ++it) {
      const Index a = it.row() / d, b = j / d;
      if (a == b) continue;
      pairs.emplace_back(a, b);
      pairs.emplace_back(b, a);
    }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  ContactGraph g;
  g.offsets.assign(static_cast<std::size_t>(nc + 1), 0);
  g.adjacency.reserve(pairs.size());
  for (const auto& [a, b] : pairs) {
    ++g.offsets[a + 1];
    g.adjacency.push_back(b);
  }
  for (Index a = 0; a < nc; ++a) g.offsets[a + 1] += g.offsets[a];
  return g;
}

/// Greedy first-fit colouring in the natural order: contact a takes the
/// smallest colour none of its lower-numbered neighbours has. Deterministic,
/// at most (largest degree + 1) colours, O(nnz(W)) after the sort.
inline ContactColouring colour_contacts(const SparseMap& W, int d) {
  const ContactGraph g = contact_graph(W, d);
  const Index nc = static_cast<Index>(g.offsets.size()) - 1;
  std::vector<Index> colour(static_cast<std::size_t>(nc), -1);
  std::vector<Index> taken_by;  // taken_by[c] == a: a neighbour of a has colour c
  Index num_colours = 0;
  for (Index a = 0; a < nc; ++a) {
    for (Index p = g.offsets[a]; p < g.offsets[a + 1]; ++p) {
      const Index c = colour[g.adjacency[p]];
      if (c >= 0) taken_by[c] = a;
    }
    Index c = 0;
    while (c < num_colours && taken_by[c] == a) ++c;
    if (c == num_colours) {
      ++num_colours;
      taken_by.push_back(-1);
    }
    colour[a] = c;
  }
  // Counting sort by colour (stable: contacts stay in increasing order).
  ContactColouring out;
  out.start.assign(static_cast<std::size_t>(num_colours + 1), 0);
  for (Index a = 0; a < nc; ++a) ++out.start[colour[a] + 1];
  for (Index c = 0; c < num_colours; ++c) out.start[c + 1] += out.start[c];
  out.contacts.resize(static_cast<std::size_t>(nc));
  std::vector<Index> next(out.start.begin(), out.start.end() - 1);
  for (Index a = 0; a < nc; ++a) out.contacts[next[colour[a]]++] = a;
  return out;
}

}  // namespace fcsolve
