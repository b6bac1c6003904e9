// The solver catalogue seen from Python: every registered entry, its typed
// settings, solve() with the GIL released, callbacks and Ctrl-C; and the
// interior-point family's existence check and diagnostics when the library
// has them. The only translation unit of the module that includes
// solvers/catalog.hpp; the families themselves are compiled apart
// (fcsolve_catalog), the interior-point ones the check reuses here.
#include "bindings.hpp"
#include "iteration_hook.hpp"

#include <fcsolve/core/timer.hpp>
#include <fcsolve/solvers/catalog.hpp>
#include <fcsolve/solvers/report_fields.hpp>

#if __has_include(<fcsolve/ipm/existence_check.hpp>) && __has_include(<fcsolve/ipm/diagnostics.hpp>)
#include <fcsolve/ipm/diagnostics.hpp>
#include <fcsolve/ipm/existence_check.hpp>
#define FCSOLVE_PY_EXISTENCE_CHECK 1
#endif

#include <pybind11/stl.h>

#include <cmath>
#include <limits>

namespace fcsolve_py {

namespace {

namespace registry = fcsolve::registry;
using fcsolve::IterationInfo;
using fcsolve::UsageError;
using registry::SettingSpec;
using registry::SettingType;
using registry::SettingValue;
using registry::SettingValues;
using registry::SolverEntry;
using namespace pybind11::literals;

// ------------------------------------------------------------ settings

bool is_python_bool(py::handle v) {
  if (PyBool_Check(v.ptr())) return true;
  const std::string name = Py_TYPE(v.ptr())->tp_name;
  return name == "numpy.bool_" || name == "numpy.bool";
}

[[noreturn]] void setting_type_error(const SolverEntry& e, const SettingSpec& s, py::handle v,
                                     const std::string& expected) {
  throw py::type_error("setting '" + s.name + "' of solver '" + e.name + "' (" +
                       registry::to_string(s.type) + ") expects " + expected + ", got " +
                       std::string(py::repr(v)) + " of type " + Py_TYPE(v.ptr())->tp_name);
}

/// A Python value as the typed value `s` declares: the Python type must fit
/// (TypeError otherwise); the range and the choices are checked by
/// SettingValues::set (UsageError, a ValueError).
SettingValue setting_value(const SolverEntry& e, const SettingSpec& s, py::handle v) {
  const bool boolean = is_python_bool(v);
  switch (s.type) {
    case SettingType::Real: {
      if (boolean || PyUnicode_Check(v.ptr())) setting_type_error(e, s, v, "a real number");
      const double x = PyFloat_AsDouble(v.ptr());
      if (x == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        setting_type_error(e, s, v, "a real number");
      }
      return x;
    }
    case SettingType::Integer: {
      if (boolean) setting_type_error(e, s, v, "an integer");
      if (PyIndex_Check(v.ptr())) {
        const auto index = py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()));
        if (!index) throw py::error_already_set();
        const long long i = PyLong_AsLongLong(index.ptr());
        if (i == -1 && PyErr_Occurred()) throw py::error_already_set();
        return i;
      }
      if (PyFloat_Check(v.ptr())) {
        const double x = PyFloat_AsDouble(v.ptr());
        if (std::isfinite(x) && std::floor(x) == x) return x;  // 5.0 is accepted as 5
      }
      setting_type_error(e, s, v, "an integer");
    }
    case SettingType::Boolean:
      if (!boolean) setting_type_error(e, s, v, "True or False");
      return PyObject_IsTrue(v.ptr()) == 1;
    case SettingType::Choice:
      if (!PyUnicode_Check(v.ptr())) {
        std::string list;
        for (const auto& c : s.choices) list += (list.empty() ? "'" : ", '") + c + "'";
        setting_type_error(e, s, v, "a string, one of " + list);
      }
      return v.cast<std::string>();
  }
  throw UsageError("setting '" + s.name + "': unknown type");
}

const SettingSpec& find_setting(const SolverEntry& e, const std::string& name) {
  for (const auto& s : e.settings)
    if (s.name == name) return s;
  std::string known;
  for (const auto& s : e.settings) known += (known.empty() ? "" : ", ") + s.name;
  throw UsageError("unknown setting '" + name + "' for solver '" + e.name + "'" +
                   (known.empty() ? " (it has no settings)" : " (its settings: " + known + ")"));
}

py::object to_python(const SettingValue& v) {
  return std::visit([](const auto& x) -> py::object { return py::cast(x); }, v);
}

/// The settings of one solver, typed and checked on every assignment
/// (fcsolve.Settings).
struct Settings {
  const SolverEntry* entry;
  SettingValues values;

  explicit Settings(const SolverEntry& e) : entry(&e), values(registry::default_settings(e)) {}

  void set(const std::string& name, py::handle value) {
    const SettingSpec& spec = find_setting(*entry, name);
    values.set(name, setting_value(*entry, spec, value));
  }
  void update(const py::dict& kwargs) {
    for (auto [key, value] : kwargs) set(key.cast<std::string>(), value);
  }
  py::object get(const std::string& name) const {
    find_setting(*entry, name);
    return to_python(values.values().at(name));
  }
  py::dict as_dict() const {
    py::dict out;
    for (const auto& s : entry->settings) out[py::str(s.name)] = to_python(values.values().at(s.name));
    return out;
  }
};

// ------------------------------------------------------------ results

/// What fcsolve.solve returns (fcsolve.Result).
struct Result {
  registry::SolveOutcome outcome;
  double tol = 0;
  bool global = false;
};

py::object optional_view(const Vector& v, bool present, py::handle owner) {
  if (!present) return py::none();
  return vector_view(v, owner);
}

std::string result_repr(const Result& r) {
  const auto& info = r.outcome.info;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "<fcsolve.Result solver='%s' status='%s' iterations=%d error=%.3e tol=%.1e "
                "seconds=%.3g>",
                r.outcome.solver.c_str(), fcsolve::to_string(info.status), info.iterations,
                info.error, r.tol, r.outcome.seconds);
  return buf;
}

// ------------------------------------------------------------ solve

/// The entry and its settings: `solver` is a name or a Settings object;
/// `kwargs` overrides its values.
std::pair<const SolverEntry*, SettingValues> resolve_solver(py::handle solver, const py::dict& kwargs) {
  Settings settings = [&] {
    if (PyUnicode_Check(solver.ptr())) return Settings(registry::find(solver.cast<std::string>()));
    if (py::isinstance<Settings>(solver)) return solver.cast<const Settings&>();
    throw py::type_error("solver must be a solver name (str) or an fcsolve.Settings, got " +
                         std::string(Py_TYPE(solver.ptr())->tp_name));
  }();
  if (kwargs.size()) settings.update(kwargs);
  return {settings.entry, std::move(settings.values)};
}

fcsolve::SolverSettings common_settings(const SolverEntry& e, double tol, py::handle max_iter,
                                        py::handle max_time, bool history) {
  // Types are checked here; values by the registry (check_common), as for the CLI.
  fcsolve::SolverSettings common;
  long long iterations = e.default_max_iter;
  if (!max_iter.is_none()) {
    if (is_python_bool(max_iter) || !PyIndex_Check(max_iter.ptr()))
      throw py::type_error("max_iter must be an integer or None");
    int overflow = 0;
    iterations = PyLong_AsLongLongAndOverflow(max_iter.ptr(), &overflow);
    if (overflow) iterations = overflow > 0 ? std::numeric_limits<long long>::max()
                                            : std::numeric_limits<long long>::min();
  }
  double seconds = common.max_time;
  if (!max_time.is_none()) {
    if (is_python_bool(max_time)) throw py::type_error("max_time must be a number of seconds or None");
    seconds = PyFloat_AsDouble(max_time.ptr());
    if (seconds == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw py::type_error("max_time must be a number of seconds or None");
    }
  }
  fcsolve::registry::detail::check_common(tol, iterations, seconds);
  common.tol = tol;
  common.max_iter = int(iterations);
  common.max_time = seconds;
  common.record_history = history;
  return common;
}

template <class Data>
py::object solve(Data& data, py::handle solver, double tol, py::handle max_iter,
                 py::handle max_time, py::handle r0, py::handle v0, py::object callback,
                 bool history, const py::dict& kwargs) {
  constexpr bool global = std::is_same_v<Data, GlobalProblemData>;
  auto [entry, values] = resolve_solver(solver, kwargs);
  registry::SolveRequest request;
  request.settings = std::move(values);
  request.common = common_settings(*entry, tol, max_iter, max_time, history);
  request.r0 = optional_vector_argument(r0, "r0");
  if (!v0.is_none()) {
    if (!global) throw UsageError("v0 is a warm start for global problems only");
    request.v0 = vector_argument(v0, "v0");
  }
  if (!callback.is_none() && !PyCallable_Check(callback.ptr()))
    throw py::type_error("callback must be callable(iteration, error, seconds) or None");

  if constexpr (global) {  // the error scale ||H^T M^-1 f + w||, if an earlier call computed it
    if (data.reduced_q_norm >= 0) request.reduced_q_norm = data.reduced_q_norm;
  }
  PythonIterationHook hook(std::move(callback));
  request.common.callback = [h = &hook](const IterationInfo& it) { return (*h)(it); };
  Result result;
  result.tol = tol;
  result.global = global;
  {
    py::gil_scoped_release unlocked;
    result.outcome = registry::solve(data.problem, *entry, request);
  }
  if constexpr (global) data.reduced_q_norm = result.outcome.reduced_q_norm;
  hook.raise_pending();
  return py::cast(std::move(result));
}

py::dict setting_dict(const SettingSpec& s) {
  py::list choices;
  for (const auto& c : s.choices) choices.append(c);
  return py::dict("name"_a = s.name, "type"_a = registry::to_string(s.type),
                  "default"_a = to_python(s.default_value), "doc"_a = s.doc, "choices"_a = choices,
                  "min"_a = s.min, "max"_a = s.max);
}

py::list solver_list() {
  py::list out;
  for (const auto& e : registry::entries()) {
    py::list settings;
    for (const auto& s : e.settings) settings.append(setting_dict(s));
    py::dict entry = fields_dict(registry::entry_fields(e));
    entry["settings"] = settings;
    out.append(entry);
  }
  return out;
}

/// Mean seconds of `repeats` registry::solve calls made from C++ with one
/// prepared request: the baseline of bench/python_overhead.py. With
/// `with_callback`, a no-op per-iteration callback is installed (the Python
/// path always has one, for Ctrl-C).
double cpp_solve_seconds(const LocalProblemData& data, const std::string& solver, int repeats,
                         double tol, bool with_callback) {
  const SolverEntry& e = registry::find(solver);
  registry::SolveRequest request = registry::make_request(e);
  request.common.tol = tol;
  if (with_callback) request.common.callback = [](const IterationInfo&) { return false; };
  const fcsolve::LocalProblemView view(data.problem);
  py::gil_scoped_release unlocked;
  fcsolve::Stopwatch clock;
  double sink = 0;
  for (int k = 0; k < repeats; ++k) sink += registry::solve(view, e, request).info.error;
  const double seconds = clock.seconds() / std::max(repeats, 1);
  return sink >= 0 ? seconds : -seconds;  // keeps the loop from being optimised away
}

// ------------------------------------------------------------ existence, diagnostics

#ifdef FCSOLVE_PY_EXISTENCE_CHECK

template <class Data>
py::dict existence_dict(const Data& data, double tol, double max_time, bool to_optimum) {
  fcsolve::ipm::ExistenceReport rep;
  {
    py::gil_scoped_release unlocked;
    rep = fcsolve::ipm::check_existence(data.problem, tol, max_time,
                                        to_optimum ? fcsolve::ipm::ExistenceStop::AtOptimum
                                                   : fcsolve::ipm::ExistenceStop::AtCertifiedWitness);
  }
  return py::dict("slater"_a = rep.slater,
                  "verdict"_a = rep.slater ? "solution-exists" : "not-established",
                  "x_star"_a = rep.x, "margin"_a = rep.margin,
                  "witness"_a = py::array_t<double>(rep.witness.size(), rep.witness.data()),
                  "witness_norm"_a = rep.witness_norm, "check_error"_a = rep.solver_error,
                  "check_status"_a = fcsolve::ipm::check_status(rep),
                  "check_iterations"_a = rep.info.iterations, "check_program"_a = rep.program);
}

template <class Data>
py::dict diagnostics_dict(const Data& data) {
  constexpr bool global = std::is_same_v<Data, GlobalProblemData>;
  fcsolve::ipm::ProblemDiagnostics d;
  {
    py::gil_scoped_release unlocked;
    d = fcsolve::ipm::diagnose(data.problem);
  }
  py::dict out;
  if (global) out["contact_ratio"] = d.contact_ratio;
  out[global ? "rank_H" : "rank_W"] = d.rank_H;
  out["m"] = d.columns_H;
  out["lambda_min_W"] = d.lambda_min_W;
  out["lambda_max_W"] = d.lambda_max_W;
  out["cond_W"] = d.cond_W;
  out["asymmetry_W"] = d.asymmetry_W;
  return out;
}

template <class Data>
void add_checks(py::module_& m) {
  m.def("check_existence", &existence_dict<Data>, "problem"_a, "tol"_a = 1e-10,
        "max_time"_a = std::numeric_limits<double>::infinity(), "to_optimum"_a = false,
        "Slater's assumption by the SOC program of Acary & Cadoux 2013 (see fcsolve.check_existence).");
  m.def("diagnostics", &diagnostics_dict<Data>, "problem"_a,
        "Rank of H (or W), spectrum and asymmetry of W (see Problem.diagnostics).");
}
#endif  // FCSOLVE_PY_EXISTENCE_CHECK

template <class Data>
void add_solve(py::module_& m, const char* name) {
  m.def(name, &solve<Data>, "problem"_a, "solver"_a, "tol"_a, "max_iter"_a, "max_time"_a, "r0"_a,
        "v0"_a, "callback"_a, "history"_a, "settings"_a,
        "Low-level solve (use fcsolve.solve): releases the GIL while the solver runs.");
}

}  // namespace

void init_solvers(py::module_& m) {
  py::class_<Settings>(m, "Settings", R"doc(Typed settings of one solver.

    Settings("nsgs", omega=1.2) starts from the solver's defaults and sets the
    given values. Every assignment (s["omega"] = 1.2, s.omega = 1.2,
    s.update(...)) is checked against the solver's declaration: an unknown
    name or an out-of-range value raises fcsolve.UsageError (a ValueError), a
    value of the wrong type raises TypeError. Pass it to fcsolve.solve as
    `solver` to reuse it: fcsolve.solve(problem, s).)doc")
      .def(py::init([](const std::string& solver, const py::kwargs& kwargs) {
             Settings s(registry::find(solver));
             s.update(kwargs);
             return s;
           }),
           "solver"_a)
      .def_property_readonly("solver", [](const Settings& s) { return s.entry->name; },
                             "The solver these settings belong to.")
      .def("__getitem__", &Settings::get)
      .def("__setitem__", &Settings::set)
      .def("__contains__", [](const Settings& s, const std::string& name) {
        return s.values.declares(name);
      })
      .def("__getattr__", [](const Settings& s, const std::string& name) {
        if (!s.values.declares(name))
          throw py::attribute_error("solver '" + s.entry->name + "' has no setting '" + name + "'");
        return s.get(name);
      })
      .def("__setattr__", &Settings::set)
      .def("__dir__", [](const Settings& s) {
        py::list names;
        for (const auto& spec : s.entry->settings) names.append(spec.name);
        return names;
      })
      .def("__iter__", [](const Settings& s) { return py::iter(s.as_dict()); })
      .def("__len__", [](const Settings& s) { return s.entry->settings.size(); })
      .def("keys", [](const Settings& s) { return s.as_dict().attr("keys")(); }, "The setting names.")
      .def("items", [](const Settings& s) { return s.as_dict().attr("items")(); },
           "(name, value) pairs.")
      .def("update", [](Settings& s, const py::kwargs& kwargs) { s.update(kwargs); },
           "Sets several values, each checked.")
      .def("as_dict", &Settings::as_dict, "The values, by name.")
      .def("copy", [](const Settings& s) { return s; }, "An independent copy.")
      .def("__repr__", [](const Settings& s) {
        std::string out = "fcsolve.Settings('" + s.entry->name + "'";
        for (auto [key, value] : s.as_dict())
          out += ", " + std::string(py::str(key)) + "=" + std::string(py::repr(value));
        return out + ")";
      });

  py::class_<Result>(m, "Result", R"doc(The outcome of fcsolve.solve.

    r, u: reactions and relative velocities (numpy, read-only);
    v: velocities (global problems, else None); multipliers: bilateral
    multipliers lambda (problems with G, else None); status: 'converged',
    'max-iterations', 'timeout', 'stalled', 'diverged', 'nan', 'stopped';
    converged: status == 'converged', which fcsolve grants only when `error`
    <= tol; error: the FCLIB error of the returned solution, recomputed from
    the data; iterations; seconds (whole call), setup_seconds, solve_seconds;
    history: per-iteration error (when history=True); message: what the
    solver did (fallbacks, regularisation...); solver; tol.)doc")
      .def_property_readonly("r", [](py::object self) {
        return vector_view(self.cast<const Result&>().outcome.r, self);
      }, "Reactions r (m = d * number of contacts).")
      .def_property_readonly("u", [](py::object self) {
        return vector_view(self.cast<const Result&>().outcome.u, self);
      }, "Relative velocities u = W r + q (local) or H^T v + w (global).")
      .def_property_readonly("v", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        return optional_view(r.outcome.v, r.global, self);
      }, "Velocities v (global problems; None for local ones).")
      .def_property_readonly("multipliers", [](py::object self) {
        const Result& r = self.cast<const Result&>();
        return optional_view(r.outcome.lambda, r.outcome.lambda.size() > 0, self);
      }, "Bilateral multipliers lambda (problems with G; else None).")
      .def_property_readonly("status", [](const Result& r) { return fcsolve::to_string(r.outcome.info.status); },
                             "'converged', 'max-iterations', 'timeout', 'stalled', 'diverged', 'nan' or 'stopped'.")
      .def_property_readonly("converged", [](const Result& r) { return r.outcome.info.converged(); },
                             "True when status is 'converged': the recomputed error is <= tol.")
      .def_property_readonly("iterations", [](const Result& r) { return r.outcome.info.iterations; },
                             "Iterations done (sweeps, Newton steps...).")
      .def_property_readonly("error", [](const Result& r) { return r.outcome.info.error; },
                             "FCLIB error of the returned solution, recomputed from the problem's data.")
      .def_property_readonly("seconds", [](const Result& r) { return r.outcome.seconds; },
                             "Wall time of the whole call (validation, reduction, solve, error check).")
      .def_property_readonly("setup_seconds", [](const Result& r) { return r.outcome.info.setup_seconds; },
                             "Time in the solver's setup (factorisations, reduction).")
      .def_property_readonly("solve_seconds", [](const Result& r) { return r.outcome.info.solve_seconds; },
                             "Time in the solver's iterations.")
      .def_property_readonly("history", [](const Result& r) {
        const auto& h = r.outcome.info.history;
        return py::array_t<double>(static_cast<py::ssize_t>(h.size()), h.data());
      }, "Error after each iteration (solve(..., history=True); else empty).")
      .def_property_readonly("message", [](const Result& r) { return r.outcome.info.message; },
                             "What the solver did beyond iterating (fallbacks, regularisation...).")
      .def_property_readonly("solver", [](const Result& r) { return r.outcome.solver; },
                             "Name of the solver that ran.")
      .def_property_readonly("stages", [](const Result& r) {
        py::list out;
        for (const auto& st : r.outcome.stages)
          out.append(fields_dict(registry::stage_fields(st)));
        return out;
      }, "Stages a staged solver ('auto') ran, as dicts (stage, solver, seconds, iterations, "
         "error, status, why); empty for the other solvers.")
      .def_property_readonly("tol", [](const Result& r) { return r.tol; }, "The tolerance asked for.")
      .def("__repr__", &result_repr);

  add_solve<LocalProblemData>(m, "solve_local");
  add_solve<GlobalProblemData>(m, "solve_global");
#ifdef FCSOLVE_PY_EXISTENCE_CHECK
  add_checks<LocalProblemData>(m);
  add_checks<GlobalProblemData>(m);
#endif
  m.def("solvers", &solver_list, "Every registered solver and its settings, as dicts.");
  m.def("_cpp_solve_seconds", &cpp_solve_seconds, "problem"_a, "solver"_a, "repeats"_a,
        "tol"_a = 1e-8, "with_callback"_a = false, "Benchmark baseline: mean seconds of registry::solve from C++.");
}

}  // namespace fcsolve_py
