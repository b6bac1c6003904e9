// fcsolve._fcsolve: the compiled half of the fcsolve Python package. The
// user-facing API (docstrings, numpy/scipy conversion) is in python/fcsolve/;
// this module holds the C++ objects and the typed exceptions.
#include "bindings.hpp"

#include <fcsolve/config.hpp>

namespace fcsolve_py {

namespace {

/// Exception classes, created once and kept for the life of the process.
struct ExceptionTypes {
  PyObject* invalid_problem = nullptr;
  PyObject* io_error = nullptr;
  PyObject* usage_error = nullptr;
};
ExceptionTypes exception_types;

PyObject* make_exception(py::module_& m, const char* name, PyObject* base, const char* doc) {
  const std::string qualified = std::string("fcsolve.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, base, nullptr);
  if (!type) throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;  // the reference from PyErr_NewExceptionWithDoc is kept on purpose
}

/// Raises `type(message)` with extra attributes set on the instance.
void raise_with(PyObject* type, const char* message,
                std::initializer_list<std::pair<const char*, std::string>> attrs) {
  py::object instance = py::reinterpret_borrow<py::object>(type)(message);
  for (const auto& [key, value] : attrs) instance.attr(key) = value;
  PyErr_SetObject(type, instance.ptr());
}

void translate(std::exception_ptr p) {
  try {
    if (p) std::rethrow_exception(p);
  } catch (const fcsolve::InvalidProblem& e) {
    raise_with(exception_types.invalid_problem, e.what(), {{"field", e.field()}});
  } catch (const fcsolve::IoError& e) {
    raise_with(exception_types.io_error, e.what(), {{"path", e.path()}, {"dataset", e.dataset()}});
  } catch (const fcsolve::UsageError& e) {
    raise_with(exception_types.usage_error, e.what(), {});
  }
}

}  // namespace

Vector vector_argument(py::handle obj, const char* field) {
  const py::array a = py::array::ensure(obj);  // null (error cleared) if not array-like
  if (!a) throw InvalidProblem(field, "expected a 1-D array of real numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw InvalidProblem(field, "expected real numbers, got dtype " +
                                    std::string(py::str(a.dtype())));
  if (a.ndim() != 1)
    throw InvalidProblem(field, "expected a 1-D array, got " + std::to_string(a.ndim()) +
                                    " dimensions");
  const auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(a);
  if (!values) throw py::error_already_set();
  return Eigen::Map<const Vector>(values.data(), values.size());
}

}  // namespace fcsolve_py

PYBIND11_MODULE(_fcsolve, m) {
  using namespace fcsolve_py;
  m.doc() = "Compiled core of fcsolve (use the `fcsolve` package, not this module directly).";
  m.attr("__version__") = FCSOLVE_VERSION_STRING;
  // pybind11 < 2.12 does not support numpy 2: fcsolve/__init__.py checks.
  m.attr("_pybind11_version") = py::make_tuple(PYBIND11_VERSION_MAJOR, PYBIND11_VERSION_MINOR);

  exception_types.invalid_problem = make_exception(
      m, "InvalidProblemError", PyExc_ValueError,
      "Problem data that does not describe a valid FC/I or FC/II instance (wrong shape, "
      "non-finite entry, negative friction coefficient, wrong dtype...). `field` names the "
      "offending argument ('W', 'q', 'mu', 'M', 'H', 'r0', ...).");
  exception_types.io_error = make_exception(
      m, "FclibError", PyExc_OSError,
      "A file that cannot be read or written as FCLIB HDF5. `path` and `dataset` say where.");
  exception_types.usage_error = make_exception(
      m, "UsageError", PyExc_ValueError,
      "A request fcsolve cannot honour: unknown solver, unknown setting, out-of-range value, "
      "a solver used on a problem kind it does not support.");
  py::register_exception_translator(&translate);

  init_problems(m);
  init_solvers(m);
}
