// The Newton matrix of the interior-point methods,
//   K = A0 + sum_a G_a B_a G_a^T + delta diag(weights),
// with A0 (n x n) and G (n x D nc, column block a = G_a) fixed and the d x d
// blocks B_a new at every iteration. The global form has the augmented
//   A0 = [M -Hs; -Hs^T 0],  G = [0; I],  B_a = -P_a^-1 T_a^2
// (ipm/global_form.hpp), the local form A0 = D^-1 W D^-1, G = I,
// B_a = P_a^-1 T_a^2 (ipm/local_form.hpp).
//
// The pattern of K and the scatter maps are built once; an iteration writes
// the values in place (no allocation), refactorises numerically (symbolic
// analysis reused), and solves with iterative refinement against K without
// the static regularisation delta I (which keeps rank-deficient or nearly
// singular systems factorisable).
#pragma once

#include <fcsolve/ipm/kkt_factorization.hpp>
#include <fcsolve/ipm/nt_scaling.hpp>

#include <vector>

namespace fcsolve {
namespace ipm {

/// A rate (flops a second) above what a numerical factorisation of K
/// reaches on one core: CHOLMOD's simplicial LDL^T and KLU's left-looking
/// LU update one scalar at a time through index arrays. Measured with the
/// LDL^T of ipm-socqp on sphere piles (FC/I, 2026-12-02, docs/results.md):
/// 0.8 GFlop/s at 10^4 contacts (7.6e8 flops), 1.8 GFlop/s at 10^5 (1.7e11
/// flops, 96 s). A factorisation whose counted flops would not end within
/// the time left even at this rate is not started
/// (InteriorPoint::factorization_fits).
inline constexpr double kFactorizationFlopRateBound = 4e9;

template <int D, class Factorization>
class KktSystem {
 public:
  using Block = Mat<D>;
  using Blocks = std::vector<Block, Eigen::aligned_allocator<Block>>;

  /// Builds the pattern of A0 + G B G^T (+ diagonal) and the scatter maps.
  /// `symmetric`: A0 and every B_a are symmetric (Cholesky) or not (LU).
  void compute(const SparseMatrix& A0, const SparseMatrix& G, bool symmetric) {
    n_ = A0.rows();
    nc_ = G.cols() / D;
    A0_ = A0;
    A0_.makeCompressed();
    G_ = G;
    G_.makeCompressed();
    // Rows touched by each contact and the dense d-column block of G there.
    row_start_.assign(std::size_t(nc_ + 1), 0);
    rows_.clear();
    g_local_.clear();
    std::vector<Index> mark(std::size_t(n_), -1);
    for (Index a = 0; a < nc_; ++a) {
      const std::size_t first = rows_.size();
      for (int k = 0; k < D; ++k)
        for (SparseMatrix::InnerIterator it(G_, a * D + k); it; ++it)
          if (mark[std::size_t(it.row())] != a) {
            mark[std::size_t(it.row())] = a;
            rows_.push_back(it.row());
          }
      std::sort(rows_.begin() + std::ptrdiff_t(first), rows_.end());
      row_start_[std::size_t(a + 1)] = Index(rows_.size());
      const Index nr = Index(rows_.size() - first);
      const std::size_t off = g_local_.size();
      g_local_.resize(off + std::size_t(nr * D), 0.0);
      for (int k = 0; k < D; ++k)
        for (SparseMatrix::InnerIterator it(G_, a * D + k); it; ++it) {
          const auto pos = std::lower_bound(rows_.begin() + std::ptrdiff_t(first), rows_.end(),
                                            it.row()) - (rows_.begin() + std::ptrdiff_t(first));
          g_local_[off + std::size_t(k * nr + pos)] = it.value();  // column-major nr x d
        }
      max_rows_ = std::max(max_rows_, nr);
    }
    // Pattern: A0, every (R_a x R_a) block, the diagonal.
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(std::size_t(A0_.nonZeros() + n_));
    for (Index j = 0; j < n_; ++j) {
      t.emplace_back(int(j), int(j), 0.0);
      for (SparseMatrix::InnerIterator it(A0_, j); it; ++it) t.emplace_back(int(it.row()), int(j), 0.0);
    }
    for (Index a = 0; a < nc_; ++a)
      for (Index p = row_start_[a]; p < row_start_[a + 1]; ++p)
        for (Index q = row_start_[a]; q < row_start_[a + 1]; ++q)
          t.emplace_back(int(rows_[std::size_t(p)]), int(rows_[std::size_t(q)]), 0.0);
    SparseMatrix pattern(n_, n_);
    pattern.setFromTriplets(t.begin(), t.end());
    pattern.makeCompressed();
    pattern_ = pattern;
    factor_.set_pattern(std::move(pattern), symmetric);
    // Scatter maps into the factorisation's value array.
    a0_index_.resize(std::size_t(A0_.nonZeros()));
    for (Index j = 0, k = 0; j < n_; ++j)
      for (SparseMatrix::InnerIterator it(A0_, j); it; ++it, ++k)
        a0_index_[std::size_t(k)] = factor_.index_of(it.row(), j);
    diag_index_.resize(std::size_t(n_));
    for (Index j = 0; j < n_; ++j) diag_index_[std::size_t(j)] = factor_.index_of(j, j);
    pair_start_.assign(std::size_t(nc_ + 1), 0);
    pair_index_.clear();
    for (Index a = 0; a < nc_; ++a) {
      for (Index q = row_start_[a]; q < row_start_[a + 1]; ++q)
        for (Index p = row_start_[a]; p < row_start_[a + 1]; ++p)
          pair_index_.push_back(factor_.index_of(rows_[std::size_t(p)], rows_[std::size_t(q)]));
      pair_start_[std::size_t(a + 1)] = Index(pair_index_.size());
    }
    blocks_.assign(std::size_t(nc_), Block::Zero());
    reg_weight_.setOnes(n_);
    scratch_.resize(max_rows_ * max_rows_ + 2 * max_rows_ * D);
    res_.resize(n_);
    corr_.resize(n_);
    work_.resize(n_);
  }

  Index size() const { return n_; }
  bool symmetric() const { return factor_.symmetric(); }
  /// Switches between Cholesky (symmetric A0 and blocks) and LU; the next
  /// factorize() redoes the symbolic analysis if the kind changed.
  void set_symmetric(bool symmetric) {
    if (symmetric != factor_.symmetric()) factor_.set_pattern(pattern_, symmetric);
  }
  Blocks& blocks() { return blocks_; }
  /// Diagonal of the static regularisation: factorize(delta) adds
  /// delta * weight_j to K_jj (signed for quasi-definite K; default 1).
  Vector& regularization_weights() { return reg_weight_; }
  const Blocks& blocks() const { return blocks_; }

  /// The least time the next factorize() can take: its flops, as the
  /// symbolic analysis counts them, at kFactorizationFlopRateBound; 0 where
  /// the factorisation does not count them.
  double least_factorization_seconds() { return factor_.estimated_flops() / kFactorizationFlopRateBound; }

  /// Writes A0 + G B G^T + delta diag(weights) (B = blocks()) and factorises it.
  bool factorize(double delta) {
    double* val = factor_.values();
    std::fill(val, val + factor_.num_values(), 0.0);
    const double* a0 = A0_.valuePtr();
    for (std::size_t k = 0; k < a0_index_.size(); ++k) val[a0_index_[k]] += a0[k];
    for (Index a = 0; a < nc_; ++a) {
      const Index nr = row_start_[a + 1] - row_start_[a];
      if (nr == 0) continue;
      Eigen::Map<const Eigen::MatrixXd> Ga(local_block(a), nr, D);
      Eigen::Map<Eigen::MatrixXd> GB(scratch_.data(), nr, D);
      Eigen::Map<Eigen::MatrixXd> C(scratch_.data() + max_rows_ * D, nr, nr);
      GB.noalias() = Ga * blocks_[std::size_t(a)];
      C.noalias() = GB * Ga.transpose();
      const Index* idx = pair_index_.data() + pair_start_[std::size_t(a)];
      for (Index k = 0; k < nr * nr; ++k) val[idx[k]] += C.data()[k];
    }
    if (delta != 0)
      for (Index j = 0; j < n_; ++j) val[diag_index_[std::size_t(j)]] += delta * reg_weight_[j];
    return factor_.factorize();
  }

  /// y = (A0 + G B G^T) x, without the regularisation.
  void apply(const Vector& x, Vector& y) const {
    y.noalias() = A0_ * x;
    for (Index a = 0; a < nc_; ++a) {
      const Index nr = row_start_[a + 1] - row_start_[a];
      Eigen::Map<const Eigen::MatrixXd> Ga(local_block(a), nr, D);
      Vec<D> gx = Vec<D>::Zero();
      for (Index p = 0; p < nr; ++p) gx += Ga.row(p).transpose() * x[rows_[std::size_t(row_start_[a] + p)]];
      const Vec<D> bgx = blocks_[std::size_t(a)] * gx;
      for (Index p = 0; p < nr; ++p) y[rows_[std::size_t(row_start_[a] + p)]] += Ga.row(p).dot(bgx);
    }
  }

  /// x = K^-1 b with up to `refinement` steps of iterative refinement against
  /// the unregularised matrix. Returns the final relative residual.
  double solve(const Vector& b, Vector& x, int refinement) {
    factor_.solve(b, x);
    const double bn = b.norm();
    if (!(bn > 0)) return 0;
    double rel = 0;
    for (int k = 0; k <= refinement; ++k) {
      apply(x, work_);
      res_ = b - work_;
      const double rn = res_.norm() / bn;
      if (k > 0 && !(rn < rel)) {  // refinement stopped helping: undo the last step
        x -= corr_;
        break;
      }
      rel = rn;
      if (k == refinement || rn <= 1e-11) break;
      factor_.solve(res_, corr_);
      x += corr_;
    }
    return rel;
  }


 private:
  const double* local_block(Index a) const {
    // blocks of G are stored one after the other: offset = d * sum of earlier row counts
    return g_local_.data() + D * row_start_[a];
  }

  Index n_ = 0, nc_ = 0, max_rows_ = 0;
  SparseMatrix A0_, G_, pattern_;
  std::vector<Index> row_start_, rows_, a0_index_, diag_index_, pair_start_, pair_index_;
  std::vector<double> g_local_, scratch_;
  Blocks blocks_;
  Factorization factor_;
  Vector res_, corr_, work_, reg_weight_;
};

}  // namespace ipm
}  // namespace fcsolve
