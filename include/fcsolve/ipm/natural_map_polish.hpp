// A few semismooth Newton steps on the natural map, from an interior-point
// iterate, against the data as given: the IPMs stop where double precision
// stops them (NT scalings of points 1e-12 from the boundary), or where they
// solved the symmetric part of W or M, or at a "fake solution"; this polish
// takes the last digits (quadratic convergence once the contact states are
// identified). It is the Newton family's iteration on one more formulation:
// global form, unknowns (v, r):
//   F = [ M v - H r - f ; Phi(r, H^T v + w) ],
//   J = [ M  -H ; A H^T  B ],   dPhi_a = A_a du_a + B_a dr_a,
// assembled by newton/global_jacobian.hpp; local form, unknown r:
// F = Phi(r, W r + q), J = A W + B, assembled by newton/reduced_jacobian.hpp.
// Phi is the natural map of core/error.hpp (rho = 1: its norm is the FCLIB
// error) through formulation/natural_map.hpp, or, with s frozen,
// r - P_K(r - u - (mu s, 0)).
// The iteration is the Newton family's loop (newton/newton_loop.hpp,
// PolishNewton below) with monotone Armijo steps on the squared scaled
// residual (its merit includes the equilibrium rows), no stall restarts, the
// caller's target as tolerance, and no step started after `max_seconds`
// (the caller's time budget); it returns the iterate of least error, never
// one worse than it was given. B
// gets a tiny diagonal shift (kJacobianShift): a sticking contact has
// B_a = 0, and with a rank-deficient H the Jacobian would be singular (the
// reactions are not unique); the shift picks a small-norm step among them.
#pragma once

#include <fcsolve/core/timer.hpp>
#include <fcsolve/formulation/natural_map.hpp>
#include <fcsolve/ipm/form_common.hpp>
#include <fcsolve/ipm/kkt_factorization.hpp>
#include <fcsolve/newton/global_jacobian.hpp>
#include <fcsolve/newton/newton_loop.hpp>
#include <fcsolve/newton/reduced_jacobian.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>

#include <Eigen/LU>

#include <algorithm>
#include <cmath>

namespace fcsolve {
namespace ipm {

struct PolishResult {
  int iterations = 0;
  double initial_error = 0, error = 0;
};

/// Diagonal shift added to every B_a (dimensionless: Phi has rho = 1).
inline constexpr double kJacobianShift = 1e-10;

namespace detail {

template <int D>
using JacobianBlocks = typename ReducedJacobian<D>::BlockList;

/// Phi_a for every contact, and (A_a, B_a + kJacobianShift I) when `A`, `B`
/// are given; `frozen` null: the Coulomb natural map, else u~ = u + (mu s, 0).
template <int D>
void natural_map_blocks(const Vector& r, const Vector& u, const Eigen::Ref<const Vector>& mu,
                        const Vector* frozen, Vector& phi, JacobianBlocks<D>* A,
                        JacobianBlocks<D>* B) {
  using Cone = CoulombCone<D>;
  using V = SmallVector<D>;
  using M = SmallMatrix<D>;
  const V rho = V::Ones();
  for (Index a = 0; a < mu.size(); ++a) {
    const V ra = r.template segment<D>(a * D), ua = u.template segment<D>(a * D);
    V G;
    if (!frozen) {
      if (A) NaturalMapFunction<Cone>::value_and_jacobian(ra, ua, mu[a], rho, G, (*A)[std::size_t(a)],
                                                          (*B)[std::size_t(a)]);
      else G = NaturalMapFunction<Cone>::value(ra, ua, mu[a], rho);
    } else {
      V z = ra - ua;
      z[0] -= mu[a] * (*frozen)[a];
      G = ra - Cone::project(z, mu[a]);
      if (A) {
        const M J = coulomb_projection_jacobian<D>(z, mu[a]);
        (*A)[std::size_t(a)] = J;
        (*B)[std::size_t(a)] = M::Identity() - J;
      }
    }
    if (B) (*B)[std::size_t(a)].diagonal().array() += kJacobianShift;
    phi.template segment<D>(a * D) = G;
  }
}

/// J dz = b for the successive Jacobians of one polish: dense LU for small
/// systems, else the backend's sparse LU with the symbolic analysis of the
/// first Jacobian reused (every Jacobian has the pattern fixed by the
/// assembly: all d x d blocks are stored, zeros included).
template <class Backend>
class JacobianSolver {
 public:
  bool solve(const SparseMatrix& J, const Vector& b, Vector& x) {
    if (J.rows() <= 400) {
      const DenseMatrix dense = J;
      x = Eigen::PartialPivLU<DenseMatrix>(dense).solve(b);
      return x.allFinite();
    }
    if (!analysed_) {
      KktSolvers<Backend>::configure(lu_);
      lu_.analyzePattern(J);
      analysed_ = true;
    }
    lu_.factorize(J);  // J stays alive and unchanged until the solve (UMFPACK)
    if (lu_.info() != Eigen::Success) return false;
    x = lu_.solve(b);
    return x.allFinite();
  }

 private:
  typename Backend::GeneralSolver lu_;
  bool analysed_ = false;
};

/// The damped Newton iteration of both forms, on the Newton family's loop
/// (newton/newton_loop.hpp) with the polish's settings: the target as tol,
/// the caller's iteration and time budgets, the monotone Armijo backtracking
/// psi(t) <= (1 - 1e-4 t) psi(0), t = 1, 1/2, ... (30 trials), no stall
/// restarts, no rho changes and no fallback. Form provides
///   double evaluate(double& error)          merit (and Jacobian) at the iterate
///   double trial(double t, double& error)   merit at z + t dz
///   bool direction()                        solves J dz = -F
///   void take(double t)                     z <- z + t dz
///   void save_best(), restore_best()        keep / restore the iterate
template <class Form>
class PolishNewton : public NewtonLoop<PolishNewton<Form>> {
  using Loop = NewtonLoop<PolishNewton>;
  friend Loop;

 public:
  PolishNewton(Form& form, double target, int max_iter, double max_seconds)
      : Loop(polish_settings(target, max_iter, max_seconds)), form_(form) {}

  PolishResult run(const Stopwatch& clock) {
    Loop::run(clock);
    PolishResult res;
    res.initial_error = initial_error_;
    res.iterations = this->counters().steps;
    res.error = this->info().error;
    return res;
  }

 private:
  static NewtonSettings polish_settings(double target, int max_iter, double max_seconds) {
    NewtonSettings s;
    s.tol = target;
    s.max_iter = max_iter;
    s.max_time = max_seconds;
    s.line_search = LineSearch::Armijo;
    s.sigma = 0.5e-4;
    s.max_line_search = 30;
    s.min_step = 0;
    s.line_search_memory = 1;  // monotone
    s.nonmonotone = false;
    s.stall_window = 0;
    s.rho_strategy = RhoStrategy::Constant;
    s.hybrid = false;
    return s;
  }

  // ---- hooks of NewtonLoop
  double error() const { return error_; }
  void refresh() {
    merit_ = form_.evaluate(error_);
    if (!evaluated_) initial_error_ = error_;  // Loop::run refreshes first at the start
    evaluated_ = true;
  }
  void set_rho_factor(double) {}
  void save_best() { form_.save_best(); }
  void restore_best() { form_.restore_best(); }
  bool fallback_sweep() { return false; }
  bool newton_step() {
    if (!form_.direction()) return false;
    double trial_error = 0;
    const double t = this->step_length(merit_, [&](double s) { return form_.trial(s, trial_error); });
    if (t <= 0) return false;
    form_.take(t);
    refresh();
    return true;
  }

  Form& form_;
  double merit_ = 0, error_ = 0, initial_error_ = 0;
  bool evaluated_ = false;
};

/// FC/I in (v, r): merit (e1^2 + e2^2), error max(e1, e2) with e1 the
/// scaled equilibrium residual and e2 = ||Phi|| / ||q||, as core/error.hpp.
template <int D, class Backend>
class GlobalPolish {
 public:
  GlobalPolish(const GlobalProblemView& p, double q_norm, Vector& v, Vector& r, const Vector* frozen)
      : p_(p), v_(v), r_(r), frozen_(frozen), n_(p.num_dofs()), m_(p.size()) {
    q_scale_ = q_norm > 0 ? q_norm : 1.0;
    f_norm_ = p.f.norm();
    A_.resize(std::size_t(p.num_contacts()));
    B_.resize(std::size_t(p.num_contacts()));
    for (Vector* x : {&phi_, &u_, &Hr_, &r_try_, &best_r_}) x->resize(m_);
    for (Vector* x : {&Mv_, &v_try_, &best_v_}) x->resize(n_);
    F_.resize(n_ + m_);
    dz_.resize(n_ + m_);
  }

  double evaluate(double& error) { return residual(v_, r_, true, error); }
  double trial(double t, double& error) {
    v_try_ = v_ + t * dz_.head(n_);
    r_try_ = r_ + t * dz_.tail(m_);
    return residual(v_try_, r_try_, false, error);
  }
  bool direction() {
    if (J_.size() == 0) {  // the pattern, at the first step only
      jacobian_.compute(p_.M, p_.H);
      jacobian_.initialise(J_);
    }
    jacobian_.assemble(A_, B_, J_);
    rhs_ = -F_;
    return linear_.solve(J_, rhs_, dz_);
  }
  void take(double t) {
    v_ += t * dz_.head(n_);
    r_ += t * dz_.tail(m_);
  }
  void save_best() {
    best_v_ = v_;
    best_r_ = r_;
  }
  void restore_best() {
    v_ = best_v_;
    r_ = best_r_;
  }

 private:
  double residual(const Vector& v, const Vector& r, bool jacobian, double& error) {
    u_.noalias() = p_.H.transpose() * v;
    u_ += p_.w;
    natural_map_blocks<D>(r, u_, p_.mu, frozen_, phi_, jacobian ? &A_ : nullptr, jacobian ? &B_ : nullptr);
    Mv_.noalias() = p_.M * v;
    Hr_.noalias() = p_.H * r;
    F_.head(n_) = Mv_ - Hr_ - p_.f;
    F_.tail(m_) = phi_;
    const double s1 = std::max({f_norm_, Mv_.norm(), Hr_.norm()});
    const double e1 = F_.head(n_).norm() / (s1 > 0 ? s1 : 1.0), e2 = phi_.norm() / q_scale_;
    error = std::max(e1, e2);
    return e1 * e1 + e2 * e2;
  }

  const GlobalProblemView& p_;
  Vector& v_;
  Vector& r_;
  const Vector* frozen_;
  Index n_, m_;
  double q_scale_ = 1, f_norm_ = 0;
  GlobalJacobian<D> jacobian_;
  SparseMatrix J_;
  JacobianSolver<Backend> linear_;
  JacobianBlocks<D> A_, B_;
  Vector phi_, u_, Mv_, Hr_, F_, rhs_, dz_, v_try_, r_try_, best_v_, best_r_;
};

/// FC/II in r: merit error^2, error ||Phi|| / ||q||.
template <int D, class Backend>
class LocalPolish {
 public:
  LocalPolish(const LocalProblemView& p, Vector& r, const Vector* frozen)
      : p_(p), r_(r), frozen_(frozen), q_scale_(p.q.norm() > 0 ? p.q.norm() : 1.0) {
    A_.resize(std::size_t(p.num_contacts()));
    B_.resize(std::size_t(p.num_contacts()));
    for (Vector* x : {&phi_, &u_, &dr_, &r_try_, &best_r_}) x->resize(p.size());
  }

  double evaluate(double& error) { return residual(r_, true, error); }
  double trial(double t, double& error) {
    r_try_ = r_ + t * dr_;
    return residual(r_try_, false, error);
  }
  bool direction() {
    if (J_.size() == 0) {  // the pattern, at the first step only
      jacobian_.compute(p_.W);
      jacobian_.initialise(J_);
    }
    jacobian_.assemble(A_, B_, J_);
    rhs_ = -phi_;
    return linear_.solve(J_, rhs_, dr_);
  }
  void take(double t) { r_ += t * dr_; }
  void save_best() { best_r_ = r_; }
  void restore_best() { r_ = best_r_; }

 private:
  double residual(const Vector& r, bool jacobian, double& error) {
    u_.noalias() = p_.W * r;
    u_ += p_.q;
    natural_map_blocks<D>(r, u_, p_.mu, frozen_, phi_, jacobian ? &A_ : nullptr, jacobian ? &B_ : nullptr);
    error = phi_.norm() / q_scale_;
    return error * error;
  }

  const LocalProblemView& p_;
  Vector& r_;
  const Vector* frozen_;
  double q_scale_;
  ReducedJacobian<D> jacobian_;
  SparseMatrix J_;
  JacobianSolver<Backend> linear_;
  JacobianBlocks<D> A_, B_;
  Vector phi_, u_, rhs_, dr_, r_try_, best_r_;
};

}  // namespace detail

/// Polishes (v, r) of FC/I; `q_norm` = ||H^T M^-1 f + w|| (error scale).
template <int D, class Backend>
PolishResult polish_global(const GlobalProblemView& p, double q_norm, Vector& v, Vector& r,
                           const Vector* frozen, double target, int max_iter, double max_seconds) {
  Stopwatch clock;
  detail::GlobalPolish<D, Backend> form(p, q_norm, v, r, frozen);
  return detail::PolishNewton<detail::GlobalPolish<D, Backend>>(form, target, max_iter, max_seconds).run(clock);
}

/// Polishes r of FC/II.
template <int D, class Backend>
PolishResult polish_local(const LocalProblemView& p, Vector& r, const Vector* frozen, double target,
                          int max_iter, double max_seconds) {
  Stopwatch clock;
  detail::LocalPolish<D, Backend> form(p, r, frozen);
  return detail::PolishNewton<detail::LocalPolish<D, Backend>>(form, target, max_iter, max_seconds).run(clock);
}

}  // namespace ipm
}  // namespace fcsolve
