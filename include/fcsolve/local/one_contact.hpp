// One-contact problems and what every local (one-contact) solver shares.
//
// The one-contact problem is FC/II with a single contact:
//   find r, u in R^d with u = W r + q,  K* ∋ u + g(u) ⊥ r ∈ K,
// where W = W^{aa} is a d x d diagonal block of the Delassus operator and q
// the block's "free" velocity q^a + sum_{b != a} W^{ab} r^b (Jean & Touzot
// 1988; Moreau 1994). Nonsmooth Gauss-Seidel solves one such problem per
// contact and sweep, so a local solver is a compile-time policy:
//
//   struct Settings;                       knobs, member defaults
//   struct Data;                           what prepare() caches per contact
//   static Data prepare(const Mat& W, double mu, const Settings&);
//   static LocalResult solve(const Data&, const Vec& q, Vec& r, const Settings&);
//
// solve() reads r as a warm start and overwrites it; it must not allocate.
#pragma once

#include <fcsolve/cone/cones.hpp>
#include <fcsolve/cone/cone_types.hpp>
#include <fcsolve/core/compiler.hpp>
#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/small_product.hpp>
#include <fcsolve/problem/error.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <type_traits>
#include <utility>

namespace fcsolve {
namespace local {

/// Which branch of Coulomb's law a one-contact solution is on.
enum class ContactCase { Unknown, TakeOff, Stick, Slide };

inline constexpr EnumName<ContactCase> kContactCaseNames[] = {{ContactCase::Unknown, "unknown"},
                                                             {ContactCase::TakeOff, "take-off"},
                                                             {ContactCase::Stick, "stick"},
                                                             {ContactCase::Slide, "slide"}};
constexpr const auto& enum_names(ContactCase) { return kContactCaseNames; }
inline const char* to_string(ContactCase c) { return enum_to_string(c); }

/// What a local solve did. `converged` means the local stopping test held
/// (the solver's own tolerance), not that the NSGS iteration converged.
struct LocalResult {
  int iterations = 0;
  bool converged = false;
  ContactCase kind = ContactCase::Unknown;
};

/// Fixed-size helpers for one contact of cone `Cone`.
template <class Cone>
struct OneContact {
  static constexpr int dim = Cone::dim;
  using Vec = typename Cone::Vec;
  using Mat = SmallMatrix<dim>;

  /// u = W r + q
  static Vec velocity(const Mat& W, const Vec& q, const Vec& r) {
    Vec u = q;
    u.noalias() += W * r;
    return u;
  }
  /// ||F_nat(r)|| = ||r - P_K(r - (u + g(u)))||, the per-contact term of
  /// the FCLIB error (problem/error.hpp).
  static double residual(const Mat& W, const Vec& q, double mu, const Vec& r) {
    return natural_map<Cone>(r, velocity(W, q, r), mu).norm();
  }
  /// A x written out (core/small_product.hpp: inlines anywhere, Eigen's bits).
  FCSOLVE_ALWAYS_INLINE static Vec product(const Mat& A, const Vec& x) {
    Vec y;
    for (int i = 0; i < dim; ++i) y[i] = product_row(A, i, x, 0);
    return y;
  }
  /// Every entry finite. Eigen's allFinite() for a contact's vector went
  /// out of line in large translation units, 4 % of an NSGS sweep (perf,
  /// sphere pile of 10^4 contacts); written out it stays in the sweep.
  static bool is_finite(const Vec& v) {
    bool finite = true;
    for (int i = 0; i < dim; ++i) finite = finite && std::isfinite(v[i]);
    return finite;
  }
  /// Take-off is the solution exactly when q_N >= 0: r = 0, u = q, and
  /// u + g(u) ∈ K* reduces to q_N >= 0 (the tangential part is absorbed by g).
  static bool takes_off(const Vec& q) { return q[0] >= 0; }

  /// W^-1 by the closed form (d <= 3), or zero when |det W| is at rounding
  /// level relative to ||W||^d.
  static Mat inverse_or_zero(const Mat& W) {
    Mat inv;
    double det = 0;
    bool ok = false;
    W.computeInverseAndDetWithCheck(inv, det, ok, 0.0);
    double scale = 1e-13;  // ||W||^dim, without std::pow (slow on its first call)
    const double n = W.norm();
    for (int i = 0; i < dim; ++i) scale *= n;
    if (!ok || !(std::abs(det) > scale)) inv.setZero();
    return inv;
  }

  /// Eigenvalues of the symmetric part of W, increasing (closed form for
  /// d <= 3: Eigen's computeDirect).
  static Vec symmetric_eigenvalues(const Mat& W) {
    const Mat S = 0.5 * (W + W.transpose());
    if constexpr (dim == 1) {
      return S.diagonal();
    } else {
      Eigen::SelfAdjointEigenSolver<Mat> eig;
      eig.computeDirect(S, Eigen::EigenvaluesOnly);
      return eig.eigenvalues();
    }
  }
  static double largest_eigenvalue(const Mat& W) { return symmetric_eigenvalues(W)[dim - 1]; }
  /// rho = (1 / W_NN, 1 / ||W_TT||_2, ...): the split spectral scaling of
  /// the Newton formulations' rho (Acary, Bremond & Huber 2018), in closed
  /// form (||W_TT||_2 of a 1 x 1 or 2 x 2 block). A zero entry gives 1.
  static Vec split_rho(const Mat& W) {
    const auto inverse = [](double x) { return x > 0 && std::isfinite(x) ? 1 / x : 1.0; };
    Vec rho;
    rho[0] = inverse(W(0, 0));
    if constexpr (dim == 2) {
      rho[1] = inverse(std::abs(W(1, 1)));
    } else if constexpr (dim == 3) {
      // ||T||_2^2 = largest eigenvalue of T^T T = (t + sqrt(t^2 - 4 det^2)) / 2,
      // t = ||T||_F^2, det = det T
      const SmallMatrix<2> T = W.template bottomRightCorner<2, 2>();
      const double t = T.squaredNorm(), det = T.determinant();
      const double l = 0.5 * (t + std::sqrt(std::max(t * t - 4 * det * det, 0.0)));
      rho.template tail<2>().setConstant(inverse(std::sqrt(l)));
    }
    return rho;
  }

  /// Default projection parameter rho = 1 / lambda_max(sym W): the step of a
  /// projected gradient that never overshoots; +inf-safe when W is zero.
  static double default_rho(const Mat& W) {
    const double l = largest_eigenvalue(W);
    return l > 0 && std::isfinite(l) ? 1.0 / l : 1.0;
  }
};

/// Compile-time check of the local solver policy (see the header comment).
template <class L, class = void>
struct is_local_solver : std::false_type {};
template <class L>
struct is_local_solver<
    L, std::void_t<typename L::Settings, typename L::Data, typename L::Cone,
                   decltype(L::prepare(std::declval<const SmallMatrix<L::Cone::dim>&>(), 0.0,
                                       std::declval<const typename L::Settings&>())),
                   decltype(L::solve(std::declval<const typename L::Data&>(),
                                     std::declval<const typename L::Cone::Vec&>(),
                                     std::declval<typename L::Cone::Vec&>(),
                                     std::declval<const typename L::Settings&>()))>>
    : std::true_type {};
template <class L>
inline constexpr bool is_local_solver_v = is_local_solver<L>::value;

}  // namespace local
}  // namespace fcsolve
