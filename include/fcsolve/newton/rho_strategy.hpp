// The per-contact rho = (rho_N, rho_T, ...) of the Newton formulations.
// Scaling rho with the inverse of the local stiffness W^aa balances r and
// rho u in G (Acary, Bremond & Huber 2018, "rho strategies" of the NSN
// solvers): a contact whose W^aa is large then weighs no more than the others.
#pragma once

#include <fcsolve/newton/newton_settings.hpp>
#include <fcsolve/core/types.hpp>

#include <Eigen/Eigenvalues>

#include <cmath>

namespace fcsolve {

/// ||M||_2 = sqrt(lambda_max(M^T M)) of a small block.
template <int D>
double spectral_norm(const SmallMatrix<D>& M) {
  if constexpr (D == 1) {
    return std::abs(M(0, 0));
  } else {
    const SmallMatrix<D> MtM = M.transpose() * M;
    Eigen::SelfAdjointEigenSolver<SmallMatrix<D>> eig(MtM, Eigen::EigenvaluesOnly);
    return std::sqrt(std::max(eig.eigenvalues().maxCoeff(), 0.0));
  }
}

/// rho of one contact from its diagonal block (`factor` = settings.rho; the
/// adaptive strategy starts from the split spectral values). A zero block
/// (a contact that nothing moves) falls back on rho = factor.
template <int D>
SmallVector<D> contact_rho(RhoStrategy strategy, double factor, const SmallMatrix<D>& Waa) {
  auto safe_inverse = [factor](double x) { return x > 0 && std::isfinite(x) ? factor / x : factor; };
  SmallVector<D> rho;
  switch (strategy) {
    case RhoStrategy::Constant:
      rho.setConstant(factor);
      break;
    case RhoStrategy::SpectralNorm:
      rho.setConstant(safe_inverse(spectral_norm<D>(Waa)));
      break;
    case RhoStrategy::SplitSpectralNorm:
    case RhoStrategy::Adaptive:
      rho[0] = safe_inverse(Waa(0, 0));
      if constexpr (D >= 2)
        rho.template tail<D - 1>().setConstant(
            safe_inverse(spectral_norm<D - 1>(Waa.template bottomRightCorner<D - 1, D - 1>())));
      break;
  }
  return rho;
}

}  // namespace fcsolve
