// A few semismooth Newton steps on the natural map, from an interior-point
// iterate, against the data as given: the IPMs stop where double precision
// stops them (NT scalings of points 1e-12 from the boundary), or where they
// solved the symmetric part of W or M, or at a "fake solution"; this polish
// takes the last digits (quadratic convergence once the contact states are
// identified). Global form, unknowns (v, r):
//   F = [ M v - H r - f ; Phi(r, H^T v + w) ],
//   J = [ M  -H ; A H^T  B ],   dPhi_a = A_a du_a + B_a dr_a,
// local form, unknown r: F = Phi(r, W r + q), J = A W + B. Phi is the natural
// map of core/error.hpp (rho = 1: its norm is the FCLIB error) through
// formulation/natural_map.hpp, or, with s frozen, r - P_K(r - u - (mu s, 0)).
// Steps are damped by backtracking on the squared scaled residual; the polish
// only ever returns a point at least as good as the one it was given, and
// starts no step after `max_seconds` (the caller's time budget). B gets
// a tiny diagonal shift (kJacobianShift): a sticking contact has B_a = 0, and
// with a rank-deficient H the Jacobian would be singular (the reactions are
// not unique); the shift picks a small-norm step among them.
#pragma once

#include <fcsolve/core/error.hpp>
#include <fcsolve/core/timer.hpp>
#include <fcsolve/formulation/natural_map.hpp>
#include <fcsolve/ipm/form_common.hpp>
#include <fcsolve/ipm/kkt_factorization.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <vector>

namespace fcsolve {
namespace ipm {

struct PolishResult {
  int iterations = 0;
  double initial_error = 0, error = 0;
};

/// Diagonal shift added to every B_a (dimensionless: Phi has rho = 1).
inline constexpr double kJacobianShift = 1e-10;

namespace detail {

/// Phi_a for every contact, and (A_a, B_a) when `A`, `B` are given;
/// `frozen` null: the Coulomb natural map, else u~ = u + (mu s, 0).
template <int N>
void natural_map_blocks(const Vector& r, const Vector& u, const Eigen::Ref<const Vector>& mu,
                        const Vector* frozen, Vector& phi, std::vector<Mat<N>>* A,
                        std::vector<Mat<N>>* B) {
  using Cone = CoulombCone<N>;
  const Vec<N> rho = Vec<N>::Ones();
  for (Index a = 0; a < mu.size(); ++a) {
    const Vec<N> ra = r.template segment<N>(a * N), ua = u.template segment<N>(a * N);
    Vec<N> G;
    if (!frozen) {
      if (A) NaturalMapFunction<Cone>::value_and_jacobian(ra, ua, mu[a], rho, G, (*A)[std::size_t(a)],
                                                          (*B)[std::size_t(a)]);
      else G = NaturalMapFunction<Cone>::value(ra, ua, mu[a], rho);
    } else {
      Vec<N> z = ra - ua;
      z[0] -= mu[a] * (*frozen)[a];
      G = ra - Cone::project(z, mu[a]);
      if (A) {
        const Mat<N> J = coulomb_projection_jacobian<N>(z, mu[a]);
        (*A)[std::size_t(a)] = J;
        (*B)[std::size_t(a)] = Mat<N>::Identity() - J;
      }
    }
    phi.template segment<N>(a * N) = G;
  }
}

/// J dz = b for the successive Jacobians of one polish: dense LU for small
/// systems, else the backend's sparse LU with the symbolic analysis of the
/// first Jacobian reused (every Jacobian has the same pattern: all N x N
/// blocks are stored, zeros included).
template <class Backend>
class JacobianSolver {
 public:
  bool solve(const SparseMatrix& J, const Vector& b, Vector& x) {
    if (J.rows() <= 400) {
      const DenseMatrix dense = J;
      x = Eigen::PartialPivLU<DenseMatrix>(dense).solve(b);
      return x.allFinite();
    }
    J_ = J;  // the LU reads it again at solve time
    if (!analysed_) {
      KktSolvers<Backend>::configure(lu_);
      lu_.analyzePattern(J_);
      analysed_ = true;
    }
    lu_.factorize(J_);
    if (lu_.info() != Eigen::Success) return false;
    x = lu_.solve(b);
    return x.allFinite();
  }

 private:
  SparseMatrix J_;
  typename Backend::GeneralSolver lu_;
  bool analysed_ = false;
};

}  // namespace detail

/// Polishes (v, r) of FC/I; `q_norm` = ||H^T M^-1 f + w|| (error scale).
template <int N, class Backend>
PolishResult polish_global(const GlobalProblemView& p, double q_norm, Vector& v, Vector& r,
                           const Vector* frozen, double target, int max_iter, double max_seconds) {
  Stopwatch clock;
  const Index n = p.num_dofs(), m = p.size(), nc = p.num_contacts();
  const double qs = q_norm > 0 ? q_norm : 1.0;
  std::vector<Mat<N>> A(static_cast<std::size_t>(nc)), B(static_cast<std::size_t>(nc));
  Vector phi(m), u(m), F(n + m), dz(n + m);
  // Scaled residual and the error of core/error.hpp at (v, r).
  auto evaluate = [&](const Vector& vv, const Vector& rr, bool jacobian, double& error) {
    u.noalias() = p.H.transpose() * vv;
    u += p.w;
    detail::natural_map_blocks<N>(rr, u, p.mu, frozen, phi, jacobian ? &A : nullptr,
                                  jacobian ? &B : nullptr);
    const Vector Mv = p.M * vv, Hr = p.H * rr;
    F.head(n) = Mv - Hr - p.f;
    F.tail(m) = phi;
    const double s1 = std::max({p.f.norm(), Mv.norm(), Hr.norm()});
    const double e1 = F.head(n).norm() / (s1 > 0 ? s1 : 1.0), e2 = phi.norm() / qs;
    error = std::max(e1, e2);
    return e1 * e1 + e2 * e2;
  };
  PolishResult res;
  detail::JacobianSolver<Backend> linear;
  double error;
  double merit = evaluate(v, r, true, error);
  res.initial_error = res.error = error;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int k = 0; k < max_iter && error > target && clock.seconds() < max_seconds; ++k) {
    t.clear();
    for (Index j = 0; j < n; ++j)
      for (SparseMap::InnerIterator it(p.M, j); it; ++it) t.emplace_back(int(it.row()), int(j), it.value());
    for (Index j = 0; j < m; ++j) {
      const Index a = j / N;
      const int k_col = int(j % N);
      for (SparseMap::InnerIterator it(p.H, j); it; ++it) {
        t.emplace_back(int(it.row()), int(n + j), -it.value());
        // (A H^T)(a N + i, dof) = sum_k A(i, k) H(dof, a N + k)
        for (int i = 0; i < N; ++i)
          t.emplace_back(int(n + a * N + i), int(it.row()), A[std::size_t(a)](i, k_col) * it.value());
      }
    }
    for (Index a = 0; a < nc; ++a)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
          t.emplace_back(int(n + a * N + i), int(n + a * N + j),
                         B[std::size_t(a)](i, j) + (i == j ? kJacobianShift : 0.0));
    SparseMatrix J(n + m, n + m);
    J.setFromTriplets(t.begin(), t.end());
    J.makeCompressed();
    const Vector rhs = -F;
    if (!linear.solve(J, rhs, dz)) break;
    // Backtracking on the scaled squared residual.
    double step = 1, trial_error = error, trial_merit = merit;
    Vector v_try, r_try;
    bool accepted = false;
    for (int ls = 0; ls < 30; ++ls, step *= 0.5) {
      v_try = v + step * dz.head(n);
      r_try = r + step * dz.tail(m);
      trial_merit = evaluate(v_try, r_try, false, trial_error);
      if (trial_merit <= (1 - 1e-4 * step) * merit) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    v = v_try;
    r = r_try;
    merit = evaluate(v, r, true, error);
    res.iterations = k + 1;
    res.error = error;
  }
  return res;
}

/// Polishes r of FC/II.
template <int N, class Backend>
PolishResult polish_local(const LocalProblemView& p, Vector& r, const Vector* frozen, double target,
                          int max_iter, double max_seconds) {
  Stopwatch clock;
  const Index m = p.size(), nc = p.num_contacts();
  const double qs = p.q.norm() > 0 ? p.q.norm() : 1.0;
  std::vector<Mat<N>> A(static_cast<std::size_t>(nc)), B(static_cast<std::size_t>(nc));
  Vector phi(m), u(m), dr(m);
  auto evaluate = [&](const Vector& rr, bool jacobian) {
    u.noalias() = p.W * rr;
    u += p.q;
    detail::natural_map_blocks<N>(rr, u, p.mu, frozen, phi, jacobian ? &A : nullptr,
                                  jacobian ? &B : nullptr);
    return phi.norm() / qs;
  };
  PolishResult res;
  detail::JacobianSolver<Backend> linear;
  double error = evaluate(r, true);
  res.initial_error = res.error = error;
  std::vector<Eigen::Triplet<double, int>> t;
  for (int k = 0; k < max_iter && error > target && clock.seconds() < max_seconds; ++k) {
    t.clear();
    // (A W)(a N + i, j) = sum_k A(i, k) W(a N + k, j)
    for (Index j = 0; j < m; ++j)
      for (SparseMap::InnerIterator it(p.W, j); it; ++it) {
        const Index a = it.row() / N;
        const int kk = int(it.row() % N);
        for (int i = 0; i < N; ++i)
          t.emplace_back(int(a * N + i), int(j), A[std::size_t(a)](i, kk) * it.value());
      }
    for (Index a = 0; a < nc; ++a)
      for (int j = 0; j < N; ++j)
        for (int i = 0; i < N; ++i)
          t.emplace_back(int(a * N + i), int(a * N + j),
                         B[std::size_t(a)](i, j) + (i == j ? kJacobianShift : 0.0));
    SparseMatrix J(m, m);
    J.setFromTriplets(t.begin(), t.end());
    J.makeCompressed();
    const Vector rhs = -phi;
    if (!linear.solve(J, rhs, dr)) break;
    double step = 1, trial = error;
    Vector r_try;
    bool accepted = false;
    for (int ls = 0; ls < 30; ++ls, step *= 0.5) {
      r_try = r + step * dr;
      trial = evaluate(r_try, false);
      if (trial * trial <= (1 - 1e-4 * step) * error * error) {
        accepted = true;
        break;
      }
    }
    if (!accepted) break;
    r = r_try;
    error = evaluate(r, true);
    res.iterations = k + 1;
    res.error = error;
  }
  return res;
}

}  // namespace ipm
}  // namespace fcsolve
