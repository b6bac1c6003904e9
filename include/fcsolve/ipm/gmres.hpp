// Restarted GMRES for a matrix-free operator (Saad & Schultz 1986; Saad,
// "Iterative methods for sparse linear systems", 2003, Alg. 6.9: Arnoldi
// with modified Gram-Schmidt, Givens rotations on the Hessenberg matrix).
// Used by the ACLM Newton step, whose Jacobian (I - dF/ds) is available only
// through products (one KKT solve each).
#pragma once

#include <fcsolve/core/types.hpp>

#include <cmath>
#include <vector>

namespace fcsolve {
namespace ipm {

/// Solves A x = b from x = 0 until ||b - A x|| <= rel_tol ||b|| or
/// `max_products` products with A; returns the products used.
template <class Apply>
int gmres(Apply&& apply, const Vector& b, Vector& x, double rel_tol, int max_products,
          int restart) {
  const Index n = b.size();
  x.setZero(n);
  const double bn = b.norm();
  if (!(bn > 0) || n == 0) return 0;
  restart = int(std::min<Index>(restart, n));
  DenseMatrix V(n, restart + 1), Hm = DenseMatrix::Zero(restart + 1, restart);
  Vector cs(restart), sn(restart), g(restart + 1), w(n), r(n);
  int products = 0;
  while (products < max_products) {
    apply(x, w);
    ++products;
    r = b - w;
    double beta = r.norm();
    if (beta <= rel_tol * bn) break;
    V.col(0) = r / beta;
    g.setZero();
    g[0] = beta;
    int j = 0;
    for (; j < restart && products < max_products; ++j) {
      apply(V.col(j), w);
      ++products;
      for (int i = 0; i <= j; ++i) {
        Hm(i, j) = w.dot(V.col(i));
        w -= Hm(i, j) * V.col(i);
      }
      Hm(j + 1, j) = w.norm();
      if (Hm(j + 1, j) > 0) V.col(j + 1) = w / Hm(j + 1, j);
      for (int i = 0; i < j; ++i) {  // earlier rotations on the new column
        const double t = cs[i] * Hm(i, j) + sn[i] * Hm(i + 1, j);
        Hm(i + 1, j) = -sn[i] * Hm(i, j) + cs[i] * Hm(i + 1, j);
        Hm(i, j) = t;
      }
      const double h = std::hypot(Hm(j, j), Hm(j + 1, j));
      cs[j] = h > 0 ? Hm(j, j) / h : 1.0;
      sn[j] = h > 0 ? Hm(j + 1, j) / h : 0.0;
      Hm(j, j) = h;
      Hm(j + 1, j) = 0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      if (std::abs(g[j + 1]) <= rel_tol * bn || !(Hm(j, j) > 0)) {
        ++j;
        break;
      }
    }
    // x += V y with H y = g (upper triangular j x j).
    Vector y = g.head(j);
    for (int i = j - 1; i >= 0; --i) {
      for (int k = i + 1; k < j; ++k) y[i] -= Hm(i, k) * y[k];
      y[i] = Hm(i, i) != 0 ? y[i] / Hm(i, i) : 0.0;
    }
    x += V.leftCols(j) * y;
    if (std::abs(g[j]) <= rel_tol * bn) break;
  }
  return products;
}

}  // namespace ipm
}  // namespace fcsolve
