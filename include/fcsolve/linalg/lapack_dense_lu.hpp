// Dense LU with partial pivoting by LAPACK's dgetrf (blocked, BLAS 3), for a
// matrix held sparse that is (nearly) full: the Newton matrix J = A W + B of
// an elastic body, whose Delassus operator W is dense by construction. A
// multifrontal sparse LU does the same 2/3 n^3 flops on such a matrix but
// spends more time assembling fronts than in BLAS (UMFPACK on a full
// 3072 x 3072 J: about 2.5 s a factorisation; dgetrf: about 0.6 s).
// Needs LAPACK (the fcsolve::cholmod target links it when CMake finds it and
// then defines FCSOLVE_WITH_LAPACK).
#pragma once

#include <fcsolve/core/types.hpp>

#include <Eigen/Core>

namespace fcsolve {
namespace lapack {
extern "C" void dgetrf_(const int* m, const int* n, double* a, const int* lda, int* ipiv,
                        int* info);
}  // namespace lapack

class LapackDenseLU {
 public:
  /// Factorises J (rows == cols); false when a pivot is exactly zero or a
  /// factor is not finite (the caller then regularises J). Allocates only
  /// when the size changes.
  bool factorize(const SparseMatrix& J) {
    const int n = int(J.rows());
    lu_.setZero(n, n);
    for (Index j = 0; j < J.outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(J, j); it; ++it) lu_(it.row(), j) = it.value();
    pivots_.resize(n);
    int info = 0;
    lapack::dgetrf_(&n, &n, lu_.data(), &n, pivots_.data(), &info);
    return info == 0 && lu_.diagonal().allFinite();
  }

  /// x = J^{-1} b from the last factorisation: P J = L U, dgetrf's row
  /// interchanges (1-based, applied in order), then the two triangles.
  void solve(const Vector& b, Vector& x) const {
    x = b;
    for (Index i = 0; i < pivots_.size(); ++i) {
      const Index p = pivots_[i] - 1;
      if (p != i) std::swap(x[i], x[p]);
    }
    lu_.triangularView<Eigen::UnitLower>().solveInPlace(x);
    lu_.triangularView<Eigen::Upper>().solveInPlace(x);
  }

 private:
  DenseMatrix lu_;
  Eigen::VectorXi pivots_;
};

}  // namespace fcsolve
