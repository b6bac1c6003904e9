// The fallback of the hybrid Newton strategy: block Gauss-Seidel sweeps
// (Jean & Touzot 1988; Moreau 1994) whose one-contact problems
//   u^a = W^aa r^a + qh^a,  qh^a = q^a + sum_{b != a} W^ab r^b
// are solved by a few local Alart-Curnier Newton steps with backtracking on
// ||G|| (the NSGS-AC local solver), falling back on the projection
// r^a <- P_K(r^a - rho (u^a + g(u^a))) when the local Newton makes no progress.
// Small on purpose: it only has to bring Newton back to where it converges.
// Storages with row access recompute (W r)^a per contact; the others keep
// u = W r + q current with column updates.
#pragma once

#include <fcsolve/formulation/alart_curnier.hpp>
#include <fcsolve/newton/rho_strategy.hpp>

#include <Eigen/LU>

#include <vector>

namespace fcsolve {

template <class Cone, class Storage>
class GaussSeidelFallback {
 public:
  static constexpr int d = Cone::dim;
  using Vec = typename Cone::Vec;
  using Mat = SmallMatrix<d>;

  void compute(const Storage& W) {
    rho_.resize(static_cast<std::size_t>(W.num_blocks()));
    for (Index a = 0; a < W.num_blocks(); ++a)
      rho_[a] = contact_rho<d>(RhoStrategy::SplitSpectralNorm, 1.0, W.diagonal_block(a));
  }

  /// One sweep over the contacts; r in/out, u = W r + q on entry and on exit.
  void sweep(const Storage& W, const VectorMap& q, const VectorMap& mu, Eigen::Ref<Vector> r,
             Eigen::Ref<Vector> u) const {
    for (Index a = 0; a < W.num_blocks(); ++a) {
      const Mat& Waa = W.diagonal_block(a);
      const Vec ra = r.template segment<d>(a * d);
      Vec ua;
      if constexpr (Storage::row_access) ua = W.block_row_product(a, r) + q.template segment<d>(a * d);
      else ua = u.template segment<d>(a * d);
      const Vec qh = ua - Waa * ra;
      const Vec rn = solve_contact(Waa, qh, mu[a], rho_[a], ra);
      r.template segment<d>(a * d) = rn;
      if constexpr (!Storage::row_access) W.add_block_column(a, Vec(rn - ra), u);
    }
    if constexpr (Storage::row_access) {
      W.multiply(r, u);
      u += q;
    }
  }

 private:
  static Vec solve_contact(const Mat& Waa, const Vec& qh, double mu, const Vec& rho, Vec r) {
    using AC = AlartCurnierFunction<Cone>;
    Vec G;
    Mat A, B;
    const Vec r0 = r;
    AC::value_and_jacobian(r, Vec(Waa * r + qh), mu, rho, G, A, B);
    const double g0 = G.norm();
    if (g0 == 0) return r;
    double g = g0;
    for (int it = 0; it < 10 && g > 0; ++it) {
      const Mat J = A * Waa + B;
      const Vec dr = -J.fullPivLu().solve(G);
      if (!dr.allFinite()) break;
      bool moved = false;
      for (double t = 1; t > 1e-3; t *= 0.5) {
        const Vec rt = r + t * dr;
        const double gt = AC::value(rt, Vec(Waa * rt + qh), mu, rho).norm();
        if (gt < (1 - 1e-4 * t) * g) {
          r = rt;
          moved = true;
          break;
        }
      }
      if (!moved) break;
      AC::value_and_jacobian(r, Vec(Waa * r + qh), mu, rho, G, A, B);
      g = G.norm();
    }
    if (!(g < g0)) {  // no local progress: one projection step
      const Vec z = r0 - rho[0] * Cone::modified_velocity(Vec(Waa * r0 + qh), mu);
      r = Cone::project(z, mu);
    }
    return r;
  }

  std::vector<Vec, Eigen::aligned_allocator<Vec>> rho_;
};

}  // namespace fcsolve
