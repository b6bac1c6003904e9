// Panagiotopoulos' fixed point on FC/II(W, q, mu) (Panagiotopoulos 1975;
// Acary, Bremond & Huber 2018, sec. on fixed points [PFP]; Siconos' PFP):
// alternate the normal and the tangential problems of the contact law,
//
//   normal, r_T fixed:      0 <= W_NN r_N + (q_N + W_NT r_T) _|_ r_N >= 0     (an LCP)
//   tangential, r_N fixed:  -(W_TT r_T + q_T + W_TN r_N) in N_D(s)(r_T),
//                           D(s) the discs of radius s = mu r_N
//
// until the FCLIB error of r = (r_N, r_T) is <= tol. A fixed point of the
// alternation is a Coulomb solution. Each problem is solved by NSGS (nsgs/)
// on its own blocks of W, split once by compute(): the normal one with the
// exact 1 x 1 local solve (Frictionless, local::Enumerative), the
// tangential one with one projection on the disc per contact
// (cone/tresca.hpp, local::Projection), both warm-started and to the
// adaptive tolerance max(err_k / 10, tol) (fixed_point/splitting_solver.hpp).
// After compute() only the right-hand sides and the radii change
// (Nsgs::refresh_q_and_mu): nothing is allocated. Frictionless contact:
// the normal LCP is the whole problem.
//
// Success is declared only on the FCLIB error of the Coulomb problem
// (problem/error.hpp); a failed solve returns the best outer iterate.
#pragma once

#include <fcsolve/fixed_point/splitting_solver.hpp>
#include <fcsolve/local/enumerative.hpp>
#include <fcsolve/storage/storage.hpp>

#include <algorithm>
#include <vector>

namespace fcsolve {

template <class Cone, class Storage>
class Panagiotopoulos : public SplittingSolver<Cone> {
  using Base = SplittingSolver<Cone>;
  static constexpr int d = Cone::dim;

 public:
  static constexpr int t = d > 1 ? d - 1 : 1;  ///< tangential components (frictionless: unused)
  static constexpr bool has_tangent = d > 1;
  using typename Base::Settings;
  using Normal = Nsgs<Frictionless, rebind_block_dim_t<Storage, 1>, local::Enumerative<Frictionless>>;
  using Tangent = Nsgs<FrictionDisc<t>, rebind_block_dim_t<Storage, t>, local::Projection<FrictionDisc<t>>>;

  explicit Panagiotopoulos(const Settings& s = {}) : Base(s) {}

  /// Validates p, splits W into its normal and tangential blocks and builds
  /// the two inner NSGS. The viewed data must outlive *this.
  Panagiotopoulos& compute(const LocalProblemView& p) {
    Stopwatch clock;
    this->prepare(p);
    split(p);
    const Index nc = p.num_contacts();
    normal_.settings().ordering = ContactOrdering::Natural;
    normal_.compute(LocalProblemView(1, W_nn_, qn_, zero_mu_));
    if constexpr (has_tangent) {
      tangent_.settings().ordering = ContactOrdering::Natural;
      tangent_.compute(LocalProblemView(t, W_tt_, qt_, radius_));
    }
    rn_.resize(nc);
    un_.resize(nc);
    rt_.resize(t * nc);
    ut_.resize(t * nc);
    this->info_.setup_seconds = clock.seconds();
    return *this;
  }

  /// r: warm start in, solution out (the best outer iterate if the solve
  /// fails); u = W r + q on return.
  const SolverInfo& solve(Eigen::Ref<Vector> r, Eigen::Ref<Vector> u) {
    return this->iterate("Panagiotopoulos", "normal-tangential alternations", r, u,
                         [&](Eigen::Ref<Vector> x, double tol, double remaining, double) {
                           Stopwatch clock;
                           FCSOLVE_NO_MALLOC_BEGIN();
                           gather(x);
                           qn_ = qn0_;
                           if constexpr (has_tangent) qn_.noalias() += W_nt_ * rt_;
                           FCSOLVE_NO_MALLOC_END();
                           int done = inner_solve(normal_, rn_, un_, qn_, tol, remaining);
                           if constexpr (has_tangent) {
                             FCSOLVE_NO_MALLOC_BEGIN();
                             for (Index a = 0; a < radius_.size(); ++a)
                               radius_[a] = this->problem_->mu[a] * rn_[a];
                             qt_ = qt0_;
                             qt_.noalias() += W_tn_ * rn_;
                             FCSOLVE_NO_MALLOC_END();
                             done += inner_solve(tangent_, rt_, ut_, qt_, tol, remaining - clock.seconds());
                           }
                           FCSOLVE_NO_MALLOC_BEGIN();
                           scatter(x);
                           FCSOLVE_NO_MALLOC_END();
                           return done;
                         });
  }

 private:
  /// Solves one subproblem (its q changed in place) to `tol` on the outer
  /// scale ||q||; returns its sweeps.
  template <class Inner>
  int inner_solve(Inner& inner, Vector& x, Vector& y, const Vector& q_sub, double tol, double remaining) {
    auto& is = inner.settings();
    is.tol = tol * this->error_->scale() / error_scale(q_sub.norm());
    is.max_iter = this->settings_.inner_max_iter;
    is.max_time = std::max(remaining, 1e-9);
    inner.refresh_q_and_mu();
    return inner.solve(x, y).iterations;
  }

  /// W's blocks NN, NT, TN, TT and q's parts, by component (normal first).
  void split(const LocalProblemView& p) {
    const Index nc = p.num_contacts();
    const auto part = [](Index i) { return i % d == 0 ? i / d : (i / d) * t + i % d - 1; };
    std::vector<Eigen::Triplet<double, int>> blocks[2][2];
    for (Index j = 0; j < p.W.outerSize(); ++j)
      for (SparseMap::InnerIterator it(p.W, j); it; ++it) {
        const Index i = it.row();
        blocks[i % d != 0][j % d != 0].emplace_back(int(part(i)), int(part(j)), it.value());
      }
    const auto assemble = [&](SparseMatrix& A, int row_t, int col_t) {
      A.resize(row_t ? t * nc : nc, col_t ? t * nc : nc);
      A.setFromTriplets(blocks[row_t][col_t].begin(), blocks[row_t][col_t].end());
      A.makeCompressed();
    };
    assemble(W_nn_, 0, 0);
    assemble(W_nt_, 0, 1);
    assemble(W_tn_, 1, 0);
    assemble(W_tt_, 1, 1);
    qn0_.resize(nc);
    qt0_.resize(t * nc);
    for (Index i = 0; i < p.size(); ++i) (i % d == 0 ? qn0_[part(i)] : qt0_[part(i)]) = p.q[i];
    qn_ = qn0_;
    qt_ = qt0_;
    zero_mu_ = Vector::Zero(nc);
    radius_ = Vector::Zero(nc);
  }

  void gather(const Eigen::Ref<const Vector>& r) {
    for (Index a = 0; a < rn_.size(); ++a) {
      rn_[a] = r[a * d];
      if constexpr (has_tangent) rt_.template segment<t>(a * t) = r.template segment<t>(a * d + 1);
    }
  }
  void scatter(Eigen::Ref<Vector> r) const {
    for (Index a = 0; a < rn_.size(); ++a) {
      r[a * d] = rn_[a];
      if constexpr (has_tangent) r.template segment<t>(a * d + 1) = rt_.template segment<t>(a * t);
    }
  }

  SparseMatrix W_nn_, W_nt_, W_tn_, W_tt_;
  Vector qn0_, qt0_, qn_, qt_, zero_mu_, radius_;
  Vector rn_, un_, rt_, ut_;
  Normal normal_;
  Tangent tangent_;
};

}  // namespace fcsolve
