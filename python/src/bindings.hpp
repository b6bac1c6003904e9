// Shared pieces of the fcsolve Python extension (fcsolve._fcsolve): the
// C++-owned problem objects the Python classes wrap, numpy views of their
// data, argument conversion. The extension is split in three translation
// units so that only expose_solvers.cpp instantiates the solver catalogue.
#pragma once

#include <fcsolve/core/exceptions.hpp>
#include <fcsolve/core/report_fields.hpp>
#include <fcsolve/linalg/default_backend.hpp>
#include <fcsolve/problem/global_problem.hpp>
#include <fcsolve/problem/local_problem.hpp>
#include <fcsolve/problem/reduction.hpp>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <variant>

namespace fcsolve_py {

namespace py = pybind11;
using fcsolve::Index;
using fcsolve::InvalidProblem;
using fcsolve::SparseMatrix;
using fcsolve::Vector;

/// A validated FC/II problem owned by C++ (wrapped by fcsolve.LocalProblem).
/// Immutable once built: Python sees its arrays as read-only views.
struct LocalProblemData {
  fcsolve::LocalProblem problem;
};

/// A validated FC/I problem owned by C++ (wrapped by fcsolve.GlobalProblem).
struct GlobalProblemData {
  using Reduction = fcsolve::GlobalReduction<fcsolve::DefaultBackend>;
  fcsolve::GlobalProblem problem;
  /// Factorisation of M, built on the first error() call and kept: the
  /// error of a global solution needs ||H^T M^-1 f + w|| (and v when absent).
  std::shared_ptr<const Reduction> error_reduction;
  /// ||H^T M^-1 f + w|| (the FCLIB error scale) once a solve or an error
  /// call computed it; < 0 before. Passed to registry::solve, which then
  /// does not factorise M again for it.
  double reduced_q_norm = -1;

  const Reduction& reduction_for_error() {
    if (!error_reduction) {
      error_reduction = std::make_shared<Reduction>(problem, /*form_W=*/false);
      reduced_q_norm = error_reduction->free_velocity_norm();
    }
    return *error_reduction;
  }
};

/// A report (summary, error, stage, catalogue entry) as the Python dict:
/// the fields shown in Python, in order (fcsolve/core/report_fields.hpp).
inline py::dict fields_dict(const fcsolve::Fields& fields) {
  py::dict out;
  for (const auto& f : fields)
    if (f.shown_in(fcsolve::ShownInPython))
      std::visit([&](const auto& x) { out[py::str(f.name)] = py::cast(x); }, f.value);
  return out;
}

/// A read-only 1-D numpy view of `n` values at `data`, keeping `owner` alive.
template <class T>
py::array_t<T> read_only_view(const T* data, Index n, py::handle owner) {
  py::array_t<T> a(static_cast<py::ssize_t>(n), data, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

inline py::array_t<double> vector_view(const Vector& v, py::handle owner) {
  return read_only_view(v.data(), v.size(), owner);
}

/// (data, indices, indptr, (rows, cols)) of a compressed-column matrix, as
/// read-only views: what scipy.sparse.csc_matrix((data, indices, indptr))
/// takes without copying.
inline py::tuple csc_view(const SparseMatrix& A, py::handle owner) {
  return py::make_tuple(read_only_view(A.valuePtr(), A.nonZeros(), owner),
                        read_only_view(A.innerIndexPtr(), A.nonZeros(), owner),
                        read_only_view(A.outerIndexPtr(), A.cols() + 1, owner),
                        py::make_tuple(A.rows(), A.cols()));
}

/// A 1-D array of real numbers as an Eigen vector (copied); anything else
/// (2-D, complex, strings, ...) throws InvalidProblem(field).
Vector vector_argument(py::handle obj, const char* field);

/// The same, None giving an empty vector.
inline Vector optional_vector_argument(py::handle obj, const char* field) {
  return obj.is_none() ? Vector() : vector_argument(obj, field);
}

void init_problems(py::module_& m);
void init_solvers(py::module_& m);

}  // namespace fcsolve_py
