// The proximal subproblem of FC/II(W, q, mu) about a centre c (Rockafellar
// 1976; Acary, Bremond & Huber 2018, sec. on the proximal point method):
//   FC/II(W + alpha I, q - alpha c, mu),
// whose velocity u' = W r + q + alpha (r - c) is u plus the proximal term.
// It is the same cone problem, so any FC/II solver solves it.
//
// The regularised W is one compressed-column copy of W with every diagonal
// entry stored; a new alpha rewrites only those entries, and a new centre
// only the shifted q, in place (no allocation): the view handed to the inner
// solver stays valid for the life of this object.
#pragma once

#include <fcsolve/core/types.hpp>
#include <fcsolve/problem/local_problem.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace fcsolve {

class ProximalProblem {
 public:
  /// Copies W with its diagonal made explicit; p must outlive *this (q, mu
  /// are read from it).
  void compute(const LocalProblemView& p) {
    const Index m = p.size();
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(std::size_t(p.W.nonZeros() + m));
    for (Index j = 0; j < m; ++j)
      for (SparseMap::InnerIterator it(p.W, j); it; ++it)
        t.emplace_back(int(it.row()), int(j), it.value());
    for (Index i = 0; i < m; ++i) t.emplace_back(int(i), int(i), 0.0);  // summed with W_ii
    W_.resize(m, m);
    W_.setFromTriplets(t.begin(), t.end());
    W_.makeCompressed();
    diagonal_position_.resize(std::size_t(m));
    diagonal_.resize(m);
    for (Index i = 0; i < m; ++i) {
      const int* begin = W_.innerIndexPtr() + W_.outerIndexPtr()[i];
      const int* end = W_.innerIndexPtr() + W_.outerIndexPtr()[i + 1];
      const Index pos = Index(std::lower_bound(begin, end, int(i)) - W_.innerIndexPtr());
      diagonal_position_[std::size_t(i)] = pos;
      diagonal_[i] = W_.valuePtr()[pos];
    }
    const double mean = m > 0 ? diagonal_.cwiseAbs().mean() : 0.0;
    diagonal_scale_ = mean > 0 && std::isfinite(mean) ? mean : 1.0;
    q_ = p.q;
    source_.emplace(p);
    view_.emplace(p.d, detail::map_compressed(W_, "W"), detail::map_vector(q_), p.mu);
    alpha_ = 0;
  }

  /// W + alpha I (alpha >= 0): rewrites the stored diagonal only.
  void set_alpha(double alpha) {
    alpha_ = alpha;
    double* values = W_.valuePtr();
    for (std::size_t i = 0; i < diagonal_position_.size(); ++i)
      values[diagonal_position_[i]] = diagonal_[Index(i)] + alpha;
  }

  /// q - alpha c for the current alpha.
  void set_centre(const Eigen::Ref<const Vector>& c) { q_ = source_->q - alpha_ * c; }

  double alpha() const { return alpha_; }
  /// mean |W_ii| (1 if W has no diagonal): alpha's natural unit.
  double diagonal_scale() const { return diagonal_scale_; }
  /// FC/II(W + alpha I, q - alpha c, mu); valid as long as *this.
  const LocalProblemView& view() const { return *view_; }

 private:
  SparseMatrix W_;
  Vector q_, diagonal_;
  std::vector<Index> diagonal_position_;
  std::optional<LocalProblemView> source_, view_;
  double alpha_ = 0, diagonal_scale_ = 1;
};

}  // namespace fcsolve
