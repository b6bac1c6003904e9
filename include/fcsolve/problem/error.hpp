// The one error measure every fcsolve solver reports (Acary, Bremond & Huber
// 2018, the FCLIB error; Acary 2025 (talk), eq. (20); docs/references.md):
//
//   F_nat(r)^a = r^a - P_{K^a}(r^a - u~^a),   u~ = u + g(u)   (natural map)
//   error      = ||F_nat(r)||_2 / ||q||_2     (||q|| = 0 -> absolute)
//
// computed exactly as the independent checker shared/tools/fcref.py does.
// Also: the Siconos 4.x scaling ||F|| / max(||q||, ||r||, ||u||) and the
// per-contact maximum. For FC/I the complementarity part uses u = H^T v + w
// and the reduced ||q|| = ||H^T M^-1 f + w|| (so a global problem and its
// reduction score alike), and the equilibrium residual
// ||M v - H r - G lambda - f|| / max(||f||, ||M v||, ||H r||, ||G lambda||)
// (plus ||G^T v + b|| / max(||b||, ||G||_F ||v||) with bilateral
// constraints: the scale must not vanish with the residual, or b = 0, the
// common case of joints, would always score 1); the global error is the
// larger of the two.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace fcsolve {

/// Natural-map residual F^a = r^a - P_K(r^a - u~^a) of one contact.
template <class Cone>
typename Cone::Vec natural_map(const typename Cone::Vec& r, const typename Cone::Vec& u,
                               typename Cone::Scalar mu) {
  return r - Cone::project(typename Cone::Vec(r - Cone::modified_velocity(u, mu)), mu);
}

struct NaturalMapNorms {
  double squared_sum = 0;   ///< sum over contacts of ||F^a||^2
  double max_contact = 0;   ///< max over contacts of ||F^a||
  Index worst_contact = -1;  ///< argmax, -1 if every F^a = 0
};

/// Accumulates ||F^a||^2 over all contacts (no allocation).
template <class Cone>
NaturalMapNorms natural_map_norms(const Eigen::Ref<const Vector>& r,
                                  const Eigen::Ref<const Vector>& u,
                                  const Eigen::Ref<const Vector>& mu) {
  constexpr int d = Cone::dim;
  using Vec = typename Cone::Vec;
  NaturalMapNorms out;
  for (Index a = 0; a < mu.size(); ++a) {
    const Vec ra = r.template segment<d>(a * d), ua = u.template segment<d>(a * d);
    const double s = natural_map<Cone>(ra, ua, mu[a]).squaredNorm();
    out.squared_sum += s;
    if (s > out.max_contact) {
      out.max_contact = s;
      out.worst_contact = a;
    }
  }
  out.max_contact = std::sqrt(out.max_contact);
  return out;
}

inline NaturalMapNorms natural_map_norms(int d, const Eigen::Ref<const Vector>& r,
                                         const Eigen::Ref<const Vector>& u,
                                         const Eigen::Ref<const Vector>& mu) {
  return dispatch_cone(d, [&](auto cone) {
    return natural_map_norms<decltype(cone)>(r, u, mu);
  });
}

/// A lower bound on ||F_nat(0)||, the FCLIB error of r = 0 times ||q||, for
/// the Coulomb cones (and the frictionless one); 0 for other cones. At r = 0,
/// u = q and F^a(0) = -P_K(z), z = -(q^a + g(q^a)) = (-q_N - mu ||q_T||,
/// -q_T). Where q_N^a < 0, z is not in the polar cone (that needs q_N >= 0),
/// and P_K(z)'s normal part is at least -q_N / (1 + mu^2): exactly that on
/// the boundary ray (Coulomb3D::project: (z_N + mu ||z_T||) / (1 + mu^2)),
/// and inside K, where ||q_T|| <= mu z_N, z_N = -q_N - mu ||q_T|| >= -q_N -
/// mu^2 z_N. So ||F^a(0)|| >= max(0, -q_N^a) / (1 + mu_a^2).
template <class Cone>
double zero_reaction_error_bound(const Eigen::Ref<const Vector>& q, const Eigen::Ref<const Vector>& mu) {
  using Scalar = typename Cone::Scalar;
  constexpr bool coulomb = std::is_same_v<Cone, Coulomb3DTpl<Scalar>> ||
                           std::is_same_v<Cone, Coulomb2DTpl<Scalar>> ||
                           std::is_same_v<Cone, FrictionlessTpl<Scalar>>;
  if constexpr (!coulomb) {
    return 0;
  } else {
    constexpr int d = Cone::dim;
    double bound = 0;
    for (Index a = 0; a < mu.size(); ++a)
      bound = std::max(bound, -q[a * d] / (1 + mu[a] * mu[a]));
    return bound;
  }
}

/// Divisor of the FCLIB relative error: ||q||, or 1 when q = 0.
inline double error_scale(double q_norm) { return q_norm > 0 ? q_norm : 1.0; }

/// The error of a local (FC/II) solution in its three scalings.
struct LocalErrorReport {
  double error = 0;          ///< FCLIB: ||F|| / ||q||
  double siconos_error = 0;  ///< ||F|| / max(||q||, ||r||, ||u||)
  double absolute = 0;       ///< ||F||
  double max_contact = 0;    ///< max_a ||F^a|| / ||q||
  Index worst_contact = -1;
};

inline LocalErrorReport local_error_report(const LocalProblemView& p,
                                           const Eigen::Ref<const Vector>& r,
                                           const Eigen::Ref<const Vector>& u) {
  const NaturalMapNorms nm = natural_map_norms(p.d, r, u, p.mu);
  const double qn = p.q.norm(), scale = error_scale(qn);
  LocalErrorReport out;
  out.absolute = std::sqrt(nm.squared_sum);
  out.error = out.absolute / scale;
  const double sic = std::max({qn, r.norm(), u.norm()});
  out.siconos_error = out.absolute / (sic > 0 ? sic : 1.0);
  out.max_contact = nm.max_contact / scale;
  out.worst_contact = nm.worst_contact;
  return out;
}

inline LocalErrorReport local_error_report(const LocalProblemView& p,
                                           const Eigen::Ref<const Vector>& r) {
  const Vector u = p.W * r + p.q;
  return local_error_report(p, r, u);
}

/// FCLIB relative error of r for FC/II (u = W r + q recomputed).
inline double local_error(const LocalProblemView& p, const Eigen::Ref<const Vector>& r) {
  return local_error_report(p, r).error;
}

/// Allocation-free error evaluation for solvers: caches ||q|| and a work u.
/// The cone is fixed at compile time, so the loop inlines the projection.
template <class Cone>
class LocalErrorEvaluator {
 public:
  explicit LocalErrorEvaluator(const LocalProblemView& p)
      : p_(p), scale_(error_scale(p.q.norm())), u_(p.size()) {}
  /// Error of r, with u = W r + q given by the caller.
  double operator()(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& u) const {
    return std::sqrt(natural_map_norms<Cone>(r, u, p_.mu).squared_sum) / scale_;
  }
  /// Error of r (computes u = W r + q into a cached work vector).
  double operator()(const Eigen::Ref<const Vector>& r) {
    u_.noalias() = p_.W * r;
    u_ += p_.q;
    return (*this)(r, u_);
  }
  double scale() const { return scale_; }

 private:
  LocalProblemView p_;
  double scale_;
  Vector u_;
};

/// Allocation-free global error evaluation for solvers on FC/I without
/// bilateral constraints: global_error_report's error (below), with work
/// vectors cached. The reduced ||q|| is the caller's (it costs a
/// factorisation of M); set_scale() replaces it when the view's w changes.
template <class Cone>
class GlobalErrorEvaluator {
 public:
  GlobalErrorEvaluator(const GlobalProblemView& p, double reduced_q_norm)
      : p_(p), scale_(error_scale(reduced_q_norm)), f_norm_(p.f.norm()), u_(p.size()),
        Mv_(p.num_dofs()), Hr_(p.num_dofs()), balance_(p.num_dofs()) {}

  /// max(complementarity, equilibrium) of (r, v), with the velocity u given
  /// (H^T v + w, or the caller's own u, e.g. with a compliance term).
  double operator()(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& u,
                    const Eigen::Ref<const Vector>& v) {
    complementarity_ = std::sqrt(natural_map_norms<Cone>(r, u, p_.mu).squared_sum) / scale_;
    balance_residual(r, v);
    const double denom = std::max({f_norm_, Mv_.norm(), Hr_.norm()});
    equilibrium_ = balance_.norm() / (denom > 0 ? denom : 1.0);
    return std::max(complementarity_, equilibrium_);
  }
  /// The error of (r, v) with u = H^T v + w.
  double operator()(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& v) {
    u_.noalias() = p_.H.transpose() * v;
    u_ += p_.w;
    return (*this)(r, u_, v);
  }

  /// M v - H r - f (also what the error's equilibrium part measures).
  const Vector& balance_residual(const Eigen::Ref<const Vector>& r, const Eigen::Ref<const Vector>& v) {
    Mv_.noalias() = p_.M * v;
    Hr_.noalias() = p_.H * r;
    balance_ = Mv_ - Hr_ - p_.f;
    return balance_;
  }

  void set_scale(double reduced_q_norm) { scale_ = error_scale(reduced_q_norm); }
  double scale() const { return scale_; }
  /// The two parts of the last error.
  double complementarity() const { return complementarity_; }
  double equilibrium() const { return equilibrium_; }

 private:
  GlobalProblemView p_;
  double scale_, f_norm_;
  double complementarity_ = 0, equilibrium_ = 0;
  Vector u_, Mv_, Hr_, balance_;
};

/// The error of a global (FC/I) solution.
struct GlobalErrorReport {
  double error = 0;            ///< max(complementarity, equilibrium)
  double complementarity = 0;  ///< ||F_nat(r; u = H^T v + w)|| / ||q_reduced||
  double equilibrium = 0;      ///< relative residual of the balance (and bilateral) equations
  double max_contact = 0;      ///< max_a ||F^a|| / ||q_reduced||
  Index worst_contact = -1;
};

/// `reduced_q_norm` is ||H^T M^-1 f + w|| (GlobalReduction::free_velocity_norm()).
/// `lambda` is needed only with bilateral constraints.
inline GlobalErrorReport global_error_report(const GlobalProblemView& p, double reduced_q_norm,
                                             const Eigen::Ref<const Vector>& r,
                                             const Eigen::Ref<const Vector>& v,
                                             const Vector& lambda = Vector()) {
  const Vector u = p.H.transpose() * v + p.w;
  const NaturalMapNorms nm = natural_map_norms(p.d, r, u, p.mu);
  const double scale = error_scale(reduced_q_norm);
  GlobalErrorReport out;
  out.complementarity = std::sqrt(nm.squared_sum) / scale;
  out.max_contact = nm.max_contact / scale;
  out.worst_contact = nm.worst_contact;

  const Vector Mv = p.M * v, Hr = p.H * r;
  Vector residual = Mv - Hr - p.f;
  double denom = std::max({p.f.norm(), Mv.norm(), Hr.norm()});
  if (p.has_bilateral()) {
    if (lambda.size() != p.G->cols())
      throw InvalidProblem("lambda", "bilateral multipliers must have " +
                                         std::to_string(p.G->cols()) + " entries");
    const Vector Gl = *p.G * lambda;
    residual -= Gl;
    denom = std::max(denom, Gl.norm());
  }
  out.equilibrium = residual.norm() / (denom > 0 ? denom : 1.0);
  if (p.has_bilateral()) {
    const Vector Gtv = p.G->transpose() * v;
    // ||G||_F ||v|| bounds ||G^T v|| and is the size of its terms, so the
    // ratio is small when G^T v + b cancels, also when b = 0.
    const double bden = std::max(p.b->norm(), p.G->norm() * v.norm());
    out.equilibrium =
        std::max(out.equilibrium, (Gtv + *p.b).norm() / (bden > 0 ? bden : 1.0));
  }
  out.error = std::max(out.complementarity, out.equilibrium);
  return out;
}

}  // namespace fcsolve
