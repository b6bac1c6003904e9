// The per-iteration hook fcsolve.solve installs in the solver settings:
// the user's Python callback, and Ctrl-C while the GIL is released.
#pragma once

#include <fcsolve/core/solver_settings.hpp>

#include <pybind11/pybind11.h>

namespace fcsolve_py {

namespace py = pybind11;

/// The per-iteration hook a Python solve installs. It calls the user's
/// callback (taking the GIL), and without one checks for Ctrl-C every
/// kSignalCheckSeconds (or 1024 iterations), so a long solve can be
/// interrupted while short ones never take the GIL.
/// SciPy's convention: the callback stops the solve by returning True or by
/// raising StopIteration (status 'stopped'); None or False goes on. Any other
/// Python exception (KeyboardInterrupt, or one raised by the callback) stops
/// the solve and is raised again once the solver has returned.
class PythonIterationHook {
 public:
  static constexpr double kSignalCheckSeconds = 0.05;

  explicit PythonIterationHook(py::object callback) : callback_(std::move(callback)) {}

  /// True stops the solve (fcsolve::IterationCallback's convention).
  bool operator()(const fcsolve::IterationInfo& it) {
    if (error_type_) return true;
    if (callback_.is_none()) {
      // it.seconds is the solver's own clock (no second clock read per
      // iteration); the count covers a solver that leaves it at 0.
      if (it.seconds < next_signal_check_ && (++calls_ & 1023) != 0) return false;
      next_signal_check_ = it.seconds + kSignalCheckSeconds;
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() == 0) return false;
      keep_pending_error();
      return true;
    }
    py::gil_scoped_acquire gil;
    PyObject* answer = PyObject_CallFunction(callback_.ptr(), "idd", it.iteration, it.error, it.seconds);
    if (!answer && PyErr_ExceptionMatches(PyExc_StopIteration)) {
      PyErr_Clear();  // a request to stop, not an error
      return true;
    }
    int stop = 0;
    if (answer && answer != Py_None) stop = PyObject_IsTrue(answer);
    Py_XDECREF(answer);
    if (!answer || stop < 0 || PyErr_CheckSignals() != 0) {
      keep_pending_error();
      return true;
    }
    return stop == 1;
  }

  /// Raises the exception that stopped the solve, if any (GIL held).
  void raise_pending() {
    if (!error_type_) return;
    PyErr_Restore(error_type_.release().ptr(), error_value_.release().ptr(),
                  error_trace_.release().ptr());
    throw py::error_already_set();
  }

 private:
  void keep_pending_error() {
    PyObject *type, *value, *trace;
    PyErr_Fetch(&type, &value, &trace);
    error_type_ = py::reinterpret_steal<py::object>(type);
    error_value_ = py::reinterpret_steal<py::object>(value);
    error_trace_ = py::reinterpret_steal<py::object>(trace);
  }

  py::object callback_;
  unsigned calls_ = 0;
  double next_signal_check_ = kSignalCheckSeconds;
  py::object error_type_, error_value_, error_trace_;
};

}  // namespace fcsolve_py
