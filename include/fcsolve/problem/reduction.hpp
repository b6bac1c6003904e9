// Global -> reduced: FC/I(M, H, f, w, mu) becomes FC/II(W, q, mu) with
//   W = H^T M^-1 H,   q = H^T M^-1 f + w     (Acary, Bremond & Huber 2018, sec. 2)
// and v is recovered from r by v = M^-1 (H r + f). With bilateral constraints
// (G, b) M is replaced by the saddle-point matrix
//   K = [ M  -G ]   acting on (v, lambda):  K (v, lambda) = (H r + f, -b),
//       [ G^T 0 ]
// and W, q, v take the v-block of K^-1.
//
// When M is block-diagonal with small blocks (rigid bodies) W is formed from
// M's block inverse (problem/block_diagonal_inverse.hpp): the many-right-hand-
// side solve below is quadratic in the number of contacts.
//
// M is factorised once: Cholesky when it is symmetric up to rounding, LU when
// it is not (the LMGC files: symmetrising M there changes W by 16 %), LU too
// if Cholesky fails. `Backend` is a linear-algebra policy (EigenBackend,
// SuiteSparseBackend).
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/linalg/eigen_backend.hpp>
#include <fcsolve/problem/block_diagonal_inverse.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/symmetry.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

namespace fcsolve {

template <class Backend = EigenBackend>
class GlobalReduction {
 public:
  GlobalReduction() = default;
  explicit GlobalReduction(const GlobalProblemView& p, bool form_W = true,
                           double max_seconds = std::numeric_limits<double>::infinity()) {
    compute(p, form_W, max_seconds);
  }

  /// Factorises M (or K) and forms q and (if form_W) W. Throws
  /// InvalidProblem("M", ...) when M (or K) is singular. A W not formed
  /// from M's block inverse (an elastic body, M^-1 dense; bilateral
  /// constraints, K^-1) is formed by blocks of columns and, with a finite
  /// `max_seconds`, given up once that time is spent (formed_W() false, W
  /// 0 x 0; q and velocity() stay valid): its many-right-hand-side solve is
  /// the one part of a reduction that can outlast a caller's time limit by
  /// seconds (an elastic block of 700 contacts: 2.2 to 3.4 s).
  GlobalReduction& compute(const GlobalProblemView& p, bool form_W = true,
                           double max_seconds = std::numeric_limits<double>::infinity()) {
    Stopwatch clock;
    formed_W_ = form_W;
    n_ = p.num_dofs();
    rows_ = n_ + (p.has_bilateral() ? p.G->cols() : 0);
    H_ = SparseMatrix(p.H);
    asymmetry_ = relative_asymmetry(p.M);
    symmetric_ = false;
    sym_.reset();
    gen_.reset();
    if (p.has_bilateral()) {
      factorise_general(saddle_point_matrix(p), "M, G (saddle-point matrix)");
    } else {
      if (asymmetry_ <= kSymmetryRoundoff) {
        sym_ = std::make_unique<typename Backend::SymmetricSolver>();
        sym_->compute(SparseMatrix(p.M));
        symmetric_ = sym_->info() == Eigen::Success;
        if (!symmetric_) sym_.reset();
      }
      if (!symmetric_) factorise_general(SparseMatrix(p.M), "M");
    }

    // q = H^T (M^-1 f)_v + w, W = H^T (M^-1 H)_v
    rhs_.setZero(rows_);
    rhs_.head(n_) = p.f;
    if (p.has_bilateral()) rhs_.tail(rows_ - n_) = -*p.b;
    const Vector y = solve(rhs_);
    local_.d = p.d;
    local_.q = H_.transpose() * y.head(n_) + p.w;
    local_.mu = p.mu;
    if (!form_W) {
      local_.W.resize(0, 0);
    } else if (const auto Minv = p.has_bilateral() ? std::nullopt : block_diagonal_inverse(p.M, symmetric_)) {
      // Rigid bodies: linear in the number of contacts (block_diagonal_inverse.hpp).
      local_.W = H_.transpose() * SparseMatrix(*Minv * H_);
    } else {
      formed_W_ = form_W_by_blocks(clock, max_seconds);
    }
    local_.W.makeCompressed();
    seconds_ = clock.seconds();
    return *this;
  }

  /// The reduced problem FC/II(W, q, mu) (owned; d and mu copied).
  const LocalProblem& local() const { return local_; }
  /// ||q|| = ||H^T M^-1 f + w||: the scale of the global error (problem/error.hpp).
  double free_velocity_norm() const { return local_.q.norm(); }

  /// v = M^-1 (H r + f) (with G: the v-block of K^-1 (H r + f, -b)).
  Vector velocity(const Eigen::Ref<const Vector>& r) const { return solve_for(r).head(n_); }
  /// lambda, the bilateral multipliers (empty without G).
  Vector multipliers(const Eigen::Ref<const Vector>& r) const {
    return solve_for(r).tail(rows_ - n_);
  }

  /// False when compute() was asked not to form W, or gave it up at its
  /// max_seconds.
  bool formed_W() const { return formed_W_; }
  bool uses_cholesky() const { return symmetric_; }
  double asymmetry_of_M() const { return asymmetry_; }
  double seconds() const { return seconds_; }

 private:
  static SparseMatrix saddle_point_matrix(const GlobalProblemView& p) {
    const Index n = p.num_dofs(), np = p.G->cols();
    std::vector<Eigen::Triplet<double, int>> t;
    t.reserve(static_cast<std::size_t>(p.M.nonZeros() + 2 * p.G->nonZeros()));
    for (Index j = 0; j < n; ++j)
      for (SparseMap::InnerIterator it(p.M, j); it; ++it)
        t.emplace_back(int(it.row()), int(j), it.value());
    for (Index j = 0; j < np; ++j)
      for (SparseMap::InnerIterator it(*p.G, j); it; ++it) {
        t.emplace_back(int(it.row()), int(n + j), -it.value());
        t.emplace_back(int(n + j), int(it.row()), it.value());
      }
    SparseMatrix K(n + np, n + np);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    return K;
  }

  void factorise_general(SparseMatrix A, const char* what) {
    // UMFPACK reads the matrix again at solve time: keep it alive here.
    factored_ = std::move(A);
    factored_.makeCompressed();
    gen_ = std::make_unique<typename Backend::GeneralSolver>();
    gen_->compute(factored_);
    if (gen_->info() != Eigen::Success)
      throw InvalidProblem("M", std::string("singular or ill-formed ") + what +
                                    ": the LU factorisation failed");
  }

  /// W = H^T M^-1 H by blocks of columns of H, the clock read after each
  /// block but the last; false (W 0 x 0) once it reads more than
  /// max_seconds (a W completed past the limit is kept: the solver's own
  /// time check then ends it, NSGS within 64 contact visits, a Newton or
  /// interior-point solver before its first step). A block is
  /// sized to take about kBlockShare of max_seconds (from the last block's
  /// time per column), so the limit is overrun by about that much, within
  /// 48 to 192 columns: on an elastic block of 700 contacts (2250 columns)
  /// blocks of 48 took 2.45 s in all, of 96 2.21 s, of 192 2.14 s, all at
  /// once 2.2-2.5 s. Without a limit too: on one of 1500 contacts, by
  /// blocks 11.9-12.6 s and 0.89 GB peak, all at once 13.8-14.4 s and
  /// 2.1 GB (M^-1 H whole, then its product). A column's values do not
  /// depend on the blocks; the blocks' columns are W's, appended in order.
  bool form_W_by_blocks(const Stopwatch& clock, double max_seconds) {
    constexpr double kBlockShare = 0.05;
    constexpr Index kMinColumns = 48, kMaxColumns = 192;
    const Index m = H_.cols();
    SparseMatrix W(m, m);
    Index next = kMinColumns;
    for (Index j0 = 0; j0 < m;) {
      const Index count = std::min(next, m - j0);
      const double before = clock.seconds();
      const SparseMatrix block = W_columns(j0, count);
      W.reserve(extra_entries(W, block.nonZeros(), double(m - j0) / double(count)));
      for (Index j = 0; j < count; ++j) {
        W.startVec(j0 + j);
        for (SparseMatrix::InnerIterator it(block, j); it; ++it) W.insertBack(it.row(), j0 + j) = it.value();
      }
      j0 += count;
      if (j0 == m) break;  // W is complete: kept, the clock not read
      const double now = clock.seconds();
      if (now > max_seconds) {
        local_.W.resize(0, 0);
        return false;
      }
      const double per_column = std::max(now - before, 1e-9) / double(count);
      next = std::max(Index(std::min(kBlockShare * max_seconds / per_column, double(kMaxColumns))), kMinColumns);
    }
    W.finalize();
    local_.W = std::move(W);
    return true;
  }

  /// Columns j0 .. j0 + count - 1 of W = H^T (M^-1 H)_v (with G: the
  /// v-block of K^-1 applied to H padded with zero rows).
  SparseMatrix W_columns(Index j0, Index count) const {
    if (rows_ == n_) return H_.transpose() * solve_sparse(H_.middleCols(j0, count));
    SparseMatrix Hk = H_.middleCols(j0, count);
    Hk.conservativeResize(rows_, count);
    return H_.transpose() * SparseMatrix(solve_sparse(Hk).topRows(n_));
  }

  /// What to reserve beyond W's entries (W filled column by column;
  /// SparseMatrix::reserve(n) makes room for n more) before the next block's
  /// `block_entries`: nothing while they fit; else the block's density
  /// extrapolated to the columns left (`blocks_left` blocks like it), and at
  /// least W's size, so that W is reallocated a few times, not once a block
  /// (W of an elastic block of 4000 contacts is 1.7 GB in 63 blocks).
  static Index extra_entries(const SparseMatrix& W, Index block_entries, double blocks_left) {
    const Index size = W.data().size();
    if (size + block_entries <= W.data().allocatedSize()) return 0;
    const Index extrapolated = Index(std::ceil(double(block_entries) * blocks_left));
    return std::max({extrapolated, block_entries, size});
  }

  Vector solve(const Vector& b) const {
    Vector x = symmetric_ ? Vector(sym_->solve(b)) : Vector(gen_->solve(b));
    return x;
  }
  SparseMatrix solve_sparse(const SparseMatrix& B) const {
    SparseMatrix X = symmetric_ ? SparseMatrix(sym_->solve(B)) : SparseMatrix(gen_->solve(B));
    return X;
  }
  Vector solve_for(const Eigen::Ref<const Vector>& r) const {
    Vector b = rhs_;
    b.head(n_) += H_ * r;
    return solve(b);
  }

  Index n_ = 0, rows_ = 0;
  SparseMatrix H_, factored_;
  Vector rhs_;  // (f, -b): the constant right-hand side
  LocalProblem local_;
  double asymmetry_ = 0, seconds_ = 0;
  bool symmetric_ = false, formed_W_ = false;
  std::unique_ptr<typename Backend::SymmetricSolver> sym_;
  std::unique_ptr<typename Backend::GeneralSolver> gen_;
};

}  // namespace fcsolve
