// What the local and the global interior-point forms hold alike: the viewed
// problem, the KKT system whose contact blocks an iteration rewrites, the
// scales, and the accessors the engine reads. A form derives from it and adds
// its own linear algebra (local_form.hpp, global_form.hpp).
#pragma once

#include <fcsolve/ipm/form_common.hpp>
#include <fcsolve/ipm/kkt_system.hpp>

#include <optional>

namespace fcsolve {
namespace ipm {

/// `ContactBlockSign` is the sign of the contact block P^-1 T^2 in the
/// form's KKT matrix: +1 in the reduced form K = Ws + P^-1 T^2, -1 in the
/// augmented global form [M -Hs; -Hs^T -P^-1 T^2].
template <class ConeType, class Factorization, class ViewType, int ContactBlockSign>
class FormBase {
  static_assert(ConeType::dim == 2 || ConeType::dim == 3,
                "the interior-point forms map a Coulomb cone (d = 2 or 3) onto the Lorentz cone");

 public:
  using Cone = ConeType;
  static constexpr int dim = Cone::dim;
  /// The iterates live in the Lorentz cone L^D, D = d (ipm/ names the
  /// contact dimension D because d names a Newton direction here).
  static constexpr int D = dim;
  using View = ViewType;
  using Backend = typename Factorization::Backend;

  const View& view() const { return *p_; }
  Index size() const { return m_; }
  Index num_contacts() const { return nc_; }
  const VectorMap& mu() const { return p_->mu; }
  double initial_scaling() const { return theta_; }
  double error_scale() const { return q_norm_ > 0 ? q_norm_ : 1.0; }
  KktSystem<D, Factorization>& kkt() { return kkt_; }
  /// Whether K is factorised symmetric (LDL^T): the data are symmetric and
  /// s is frozen (coupled s makes the contact blocks unsymmetric).
  bool symmetric_kkt(bool coupled) const { return symmetric_data_ && !coupled; }

  /// Contact blocks ±P_a^-1 T_a^2 (P_a^-1 = I - e n_a^T when s is coupled);
  /// a symmetric factorisation iff the data are symmetric and s frozen.
  bool factorize(const ContactState<D>& cs, bool coupled, double delta) {
    kkt_.set_symmetric(symmetric_kkt(coupled));
    auto& B = kkt_.blocks();
    for (std::size_t a = 0; a < B.size(); ++a) {
      const Mat<D>& T = cs.scaling[a].T;
      B[a].noalias() = double(ContactBlockSign) * (T * T);
      if (coupled) {
        const Eigen::Matrix<double, 1, D> row = cs.normal[a].transpose() * B[a];
        B[a].row(0) -= row;
      }
    }
    return kkt_.factorize(delta);
  }

  /// Uniform scaling T = theta I, P = I (the initial point).
  bool factorize_uniform(double theta, double delta) {
    kkt_.set_symmetric(symmetric_kkt(false));
    for (auto& B : kkt_.blocks()) B = double(ContactBlockSign) * theta * theta * Mat<D>::Identity();
    return kkt_.factorize(delta);
  }

  /// r = D^-1 y (D = diag(mu, 1, ...), nt_scaling.hpp).
  void reaction(const Iterate& it, Vector& r) const { reaction_from_lorentz<D>(it.y, p_->mu, r); }

 protected:
  std::optional<View> p_;
  Index m_ = 0, nc_ = 0;
  KktSystem<D, Factorization> kkt_;
  bool symmetric_data_ = true;
  double q_norm_ = 0, theta_ = 1;
};

}  // namespace ipm
}  // namespace fcsolve
