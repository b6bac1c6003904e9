// Problems, FCLIB files, the error measure, the reduction and the summary.
#include "bindings.hpp"

#include <fcsolve/problem/error.hpp>
#include <fcsolve/io/fclib.hpp>
#include <fcsolve/problem/report_fields.hpp>
#include <fcsolve/problem/summary.hpp>
#include <fcsolve/problem/validate.hpp>

#include <pybind11/stl.h>

namespace fcsolve_py {

namespace {

using fcsolve::GlobalProblem;
using fcsolve::GlobalProblemView;
using fcsolve::LocalProblem;
using fcsolve::LocalProblemView;
using fcsolve::ProblemText;
using namespace pybind11::literals;

using IntArray = py::array_t<int, py::array::c_style>;
using RealArray = py::array_t<double, py::array::c_style>;

/// A compressed-column matrix from (data, indices, indptr, (rows, cols))
/// with int32 indices, copied after its structure is checked (so that no
/// index is followed out of bounds).
SparseMatrix sparse_argument(const py::tuple& csc, const std::string& field) {
  if (csc.size() != 4) throw InvalidProblem(field, "expected (data, indices, indptr, shape)");
  const auto data = csc[0].cast<RealArray>();
  const auto indices = csc[1].cast<IntArray>();
  const auto indptr = csc[2].cast<IntArray>();
  const auto shape = csc[3].cast<std::pair<Index, Index>>();
  const Index rows = shape.first, cols = shape.second;
  if (rows < 0 || cols < 0) throw InvalidProblem(field, "negative shape");
  if (data.ndim() != 1 || indices.ndim() != 1 || indptr.ndim() != 1)
    throw InvalidProblem(field, "data, indices and indptr must be 1-D");
  const Index nnz = data.size();
  if (indices.size() != nnz)
    throw InvalidProblem(field, "indices and data differ in length");
  if (indptr.size() != cols + 1)
    throw InvalidProblem(field, "indptr must have columns + 1 = " + std::to_string(cols + 1) +
                                    " entries, got " + std::to_string(indptr.size()));
  const int* p = indptr.data();
  if (p[0] != 0) throw InvalidProblem(field, "indptr must start at 0");
  for (Index j = 0; j < cols; ++j)
    if (p[j + 1] < p[j]) throw InvalidProblem(field, "indptr decreases at column " + std::to_string(j));
  if (p[cols] != nnz)
    throw InvalidProblem(field, "indptr ends at " + std::to_string(p[cols]) + " but there are " +
                                    std::to_string(nnz) + " entries");
  const fcsolve::SparseMap map(rows, cols, nnz, p, indices.data(), data.data());
  fcsolve::detail::check_sparse_structure(map, field);
  SparseMatrix A = map;
  A.makeCompressed();
  return A;
}

ProblemText text_argument(const std::string& title, const std::string& description,
                          const std::string& math_info) {
  return {title, description, math_info};
}

py::dict summary_dict(const fcsolve::ProblemSummary& s, const std::string& title) {
  return fields_dict(fcsolve::summary_fields(s, title));
}

void check_length(const Vector& x, Index size, const char* field) {
  if (x.size() != size)
    throw InvalidProblem(field, "expected " + std::to_string(size) + " entries, got " +
                                    std::to_string(x.size()));
}

py::dict local_error_dict(const LocalProblemData& self, py::handle r_obj) {
  const Vector r = vector_argument(r_obj, "r");
  check_length(r, self.problem.size(), "r");
  const fcsolve::LocalErrorReport e = fcsolve::local_error_report(self.problem, r);
  return fields_dict(fcsolve::error_fields(e));
}

py::dict global_error_dict(GlobalProblemData& self, py::handle r_obj, py::handle v_obj,
                           py::handle lambda_obj) {
  const GlobalProblem& p = self.problem;
  const Vector r = vector_argument(r_obj, "r");
  check_length(r, p.size(), "r");
  Vector v = optional_vector_argument(v_obj, "v");
  Vector lambda = optional_vector_argument(lambda_obj, "multipliers");
  if (v.size()) check_length(v, p.num_dofs(), "v");
  if (lambda.size() && !p.has_bilateral())
    throw InvalidProblem("multipliers", "the problem has no bilateral constraints (G)");
  const auto& reduction = self.reduction_for_error();
  if (!v.size()) v = reduction.velocity(r);
  if (p.has_bilateral()) {
    if (!lambda.size()) lambda = reduction.multipliers(r);
    check_length(lambda, p.G.cols(), "multipliers");
  }
  const fcsolve::GlobalErrorReport e =
      fcsolve::global_error_report(p, reduction.free_velocity_norm(), r, v, lambda);
  return fields_dict(fcsolve::error_fields(e));
}

py::object solution_dict(const fcsolve::fclib::Solution& s) {
  py::dict out;
  for (auto [name, v] : {std::pair<const char*, const Vector*>{"r", &s.r}, {"u", &s.u},
                         {"v", &s.v}, {"l", &s.l}})
    out[name] = v->size() ? py::object(py::array_t<double>(v->size(), v->data())) : py::none();
  return std::move(out);
}

fcsolve::fclib::Solution solution_argument(const py::tuple& t) {
  if (t.size() != 4) throw fcsolve::UsageError("a solution is (r, u, v, l), each None or an array");
  return {optional_vector_argument(t[0], "solution r"), optional_vector_argument(t[1], "solution u"),
          optional_vector_argument(t[2], "solution v"), optional_vector_argument(t[3], "solution l")};
}

/// Runs `f`, turning an HDF5 exception that escaped the adapter into an
/// FclibError naming the file.
template <class F>
auto with_hdf5_errors(const std::string& path, F&& f) {
  try {
    return f();
  } catch (const H5::Exception& e) {
    throw fcsolve::IoError(path, "", "HDF5 error: " + e.getDetailMsg());
  }
}

template <class Data>
void add_text_properties(py::class_<Data>& c) {
  c.def_property_readonly("title", [](const Data& s) { return s.problem.text.title; })
      .def_property_readonly("description", [](const Data& s) { return s.problem.text.description; })
      .def_property_readonly("math_info", [](const Data& s) { return s.problem.text.math_info; })
      .def_property_readonly("d", [](const Data& s) { return s.problem.d; })
      .def_property_readonly("size", [](const Data& s) { return s.problem.size(); })
      .def_property_readonly("num_contacts", [](const Data& s) { return s.problem.num_contacts(); })
      .def_property_readonly("mu", [](py::object self) {
        return vector_view(self.cast<const Data&>().problem.mu, self);
      });
}

}  // namespace

void init_problems(py::module_& m) {
  py::class_<LocalProblemData> local(m, "LocalProblemData",
                                     "C++-owned, validated FC/II data (see fcsolve.LocalProblem).");
  local
      .def(py::init([](int d, const py::tuple& W, py::handle q, py::handle mu,
                       const std::string& title, const std::string& description,
                       const std::string& math_info) {
             auto out = std::make_unique<LocalProblemData>();
             LocalProblem& p = out->problem;
             p.d = d;
             p.W = sparse_argument(W, "W");
             p.q = vector_argument(q, "q");
             p.mu = vector_argument(mu, "mu");
             p.text = text_argument(title, description, math_info);
             fcsolve::validate(p);
             return out;
           }),
           "d"_a, "W"_a, "q"_a, "mu"_a, "title"_a = "", "description"_a = "", "math_info"_a = "")
      .def_property_readonly("W", [](py::object self) {
        return csc_view(self.cast<const LocalProblemData&>().problem.W, self);
      })
      .def_property_readonly("q", [](py::object self) {
        return vector_view(self.cast<const LocalProblemData&>().problem.q, self);
      })
      .def("error", [](const LocalProblemData& s, py::handle r) {
        const Vector rv = vector_argument(r, "r");
        check_length(rv, s.problem.size(), "r");
        return fcsolve::local_error(s.problem, rv);
      }, "r"_a)
      .def("error_report", &local_error_dict, "r"_a)
      .def("summary", [](const LocalProblemData& s) {
        return summary_dict(fcsolve::summarize(LocalProblemView(s.problem)), s.problem.text.title);
      })
      .def("save", [](const LocalProblemData& s, const std::string& path) {
        with_hdf5_errors(path, [&] { fcsolve::fclib::write_local(path, s.problem); });
      }, "path"_a);
  add_text_properties(local);

  py::class_<GlobalProblemData> global(m, "GlobalProblemData",
                                       "C++-owned, validated FC/I data (see fcsolve.GlobalProblem).");
  global
      .def(py::init([](int d, const py::tuple& M, const py::tuple& H, py::handle f, py::handle w,
                       py::handle mu, py::object G, py::handle b, const std::string& title,
                       const std::string& description, const std::string& math_info) {
             auto out = std::make_unique<GlobalProblemData>();
             GlobalProblem& p = out->problem;
             p.d = d;
             p.M = sparse_argument(M, "M");
             p.H = sparse_argument(H, "H");
             p.f = vector_argument(f, "f");
             p.w = vector_argument(w, "w");
             p.mu = vector_argument(mu, "mu");
             if (G.is_none() != b.is_none())
               throw InvalidProblem(G.is_none() ? "G" : "b", "G and b must be given together");
             if (!G.is_none()) {
               p.G = sparse_argument(G.cast<py::tuple>(), "G");
               p.b = vector_argument(b, "b");
               if (p.G.cols() == 0) throw InvalidProblem("G", "has no columns (pass G=None)");
             }
             p.text = text_argument(title, description, math_info);
             fcsolve::validate(p);
             return out;
           }),
           "d"_a, "M"_a, "H"_a, "f"_a, "w"_a, "mu"_a, "G"_a = py::none(), "b"_a = py::none(),
           "title"_a = "", "description"_a = "", "math_info"_a = "")
      .def_property_readonly("M", [](py::object self) {
        return csc_view(self.cast<const GlobalProblemData&>().problem.M, self);
      })
      .def_property_readonly("H", [](py::object self) {
        return csc_view(self.cast<const GlobalProblemData&>().problem.H, self);
      })
      .def_property_readonly("G", [](py::object self) -> py::object {
        const auto& p = self.cast<const GlobalProblemData&>().problem;
        if (!p.has_bilateral()) return py::none();
        return csc_view(p.G, self);
      })
      .def_property_readonly("f", [](py::object self) {
        return vector_view(self.cast<const GlobalProblemData&>().problem.f, self);
      })
      .def_property_readonly("w", [](py::object self) {
        return vector_view(self.cast<const GlobalProblemData&>().problem.w, self);
      })
      .def_property_readonly("b", [](py::object self) -> py::object {
        const auto& p = self.cast<const GlobalProblemData&>().problem;
        if (!p.has_bilateral()) return py::none();
        return vector_view(p.b, self);
      })
      .def_property_readonly("num_dofs", [](const GlobalProblemData& s) { return s.problem.num_dofs(); })
      .def("error", [](GlobalProblemData& s, py::handle r, py::handle v, py::handle lambda) {
        return global_error_dict(s, r, v, lambda)["error"].cast<double>();
      }, "r"_a, "v"_a = py::none(), "multipliers"_a = py::none())
      .def("error_report", &global_error_dict, "r"_a, "v"_a = py::none(),
           "multipliers"_a = py::none())
      .def("reduce", [](const GlobalProblemData& s) {
        auto out = std::make_unique<LocalProblemData>();
        {
          py::gil_scoped_release unlocked;
          out->problem = GlobalProblemData::Reduction(s.problem).local();
        }
        out->problem.text = s.problem.text;
        return out;
      })
      .def("summary", [](const GlobalProblemData& s) {
        return summary_dict(fcsolve::summarize(GlobalProblemView(s.problem)), s.problem.text.title);
      })
      .def("save", [](const GlobalProblemData& s, const std::string& path) {
        with_hdf5_errors(path, [&] { fcsolve::fclib::write_global(path, s.problem); });
      }, "path"_a);
  add_text_properties(global);

  m.def("load", [](const std::string& path) -> py::object {
    return with_hdf5_errors(path, [&]() -> py::object {
      fcsolve::fclib::Problem p = fcsolve::fclib::read_problem(path);
      if (auto* lp = std::get_if<LocalProblem>(&p)) {
        auto out = std::make_unique<LocalProblemData>();
        out->problem = std::move(*lp);
        return py::cast(std::move(out));
      }
      auto out = std::make_unique<GlobalProblemData>();
      out->problem = std::move(std::get<GlobalProblem>(p));
      return py::cast(std::move(out));
    });
  }, "path"_a, "Reads an FCLIB file: a LocalProblemData or a GlobalProblemData.");

  m.def("read_solution", [](const std::string& path) -> py::object {
    auto s = with_hdf5_errors(path, [&] { return fcsolve::fclib::read_solution(path); });
    return s ? solution_dict(*s) : py::none();
  }, "path"_a, "The /solution group of an FCLIB file as {r, u, v, l} (None if absent).");
  m.def("read_guesses", [](const std::string& path) {
    py::list out;
    for (const auto& g : with_hdf5_errors(path, [&] { return fcsolve::fclib::read_guesses(path); }))
      out.append(solution_dict(g));
    return out;
  }, "path"_a, "The /guesses groups of an FCLIB file, in order.");
  m.def("write_solution", [](const std::string& path, const py::tuple& s) {
    const auto sol = solution_argument(s);
    with_hdf5_errors(path, [&] { fcsolve::fclib::write_solution(path, sol); });
  }, "path"_a, "solution"_a, "Writes (or replaces) /solution; solution = (r, u, v, l).");
  m.def("write_guesses", [](const std::string& path, const py::list& guesses) {
    std::vector<fcsolve::fclib::Solution> all;
    for (auto g : guesses) all.push_back(solution_argument(g.cast<py::tuple>()));
    with_hdf5_errors(path, [&] { fcsolve::fclib::write_guesses(path, all); });
  }, "path"_a, "guesses"_a, "Writes (or replaces) /guesses; each guess = (r, u, v, l).");
}

}  // namespace fcsolve_py
