// Entry i of A x for a contact's small fixed-size matrix A, written out so
// that it inlines anywhere (in a large translation unit Eigen's product went
// out of line, a call a contact visit: perf, an NSGS sweep of a sphere pile)
// and summed in the order Eigen 3.4's coefficient-based product sums it with
// 2-wide SSE2 packets, so that the written-out product gives Eigen's bits:
// rows taken two at a time by packets, ((A_i0 x_0 + A_i1 x_1) + A_i2 x_2);
// the row left over after the packets (the last of three) as a reduction,
// A_i0 x_0 + (A_i1 x_1 + A_i2 x_2) (checked on 10^5 random 3 x 3 products).
// Under other instruction sets the two may differ at rounding level only.
#pragma once

#include <fcsolve/core/compiler.hpp>
#include <fcsolve/core/types.hpp>

namespace fcsolve {

/// sum_j A(i, j) x(offset + j), in Eigen's order (see above).
template <class Matrix, class XVector>
FCSOLVE_ALWAYS_INLINE typename Matrix::Scalar product_row(const Matrix& A, int i, const XVector& x, Index offset) {
  constexpr int rows = Matrix::RowsAtCompileTime, cols = Matrix::ColsAtCompileTime;
  static_assert(rows > 0 && cols > 0, "a fixed-size matrix");
  if constexpr (cols == 3 && rows % 2 == 1) {
    if (i == rows - 1)
      return A(i, 0) * x.coeff(offset) + (A(i, 1) * x.coeff(offset + 1) + A(i, 2) * x.coeff(offset + 2));
  }
  typename Matrix::Scalar t = A(i, 0) * x.coeff(offset);
  for (int j = 1; j < cols; ++j) t += A(i, j) * x.coeff(offset + j);
  return t;
}

}  // namespace fcsolve
