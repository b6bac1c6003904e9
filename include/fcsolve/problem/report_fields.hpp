// The problem summary and the error reports as ordered fields
// (core/report_fields.hpp): what `fcsolve info` / `fcsolve error` print and
// what Problem.summary() / Problem.error_report() return in Python.
#pragma once

#include <fcsolve/core/report_fields.hpp>
#include <fcsolve/problem/error.hpp>
#include <fcsolve/problem/summary.hpp>

#include <string>

namespace fcsolve {

/// kind, d, nc, [n], m, the matrix sizes, the mu range, the asymmetry of W
/// (local) or M (global) and the title.
inline Fields summary_fields(const ProblemSummary& s, const std::string& title) {
  const bool global = s.kind == "global";
  Fields f = {Field::text("kind", s.kind), Field::integer("d", s.d), Field::integer("nc", s.nc)};
  if (global) f.push_back(Field::integer("n", s.n));
  f.push_back(Field::integer("m", s.m));
  if (global) {
    f.push_back(Field::integer("nnz_M", s.nnz_M));
    f.push_back(Field::integer("nnz_H", s.nnz_H));
    f.push_back(Field::integer("nonzeros_M", s.nonzeros_M));
    f.push_back(Field::integer("nonzeros_H", s.nonzeros_H));
    // Without bilateral constraints the CLI leaves them out; Python's dict
    // always had them (0).
    const unsigned bilateral = s.p > 0 ? ShownEverywhere : ShownInPython;
    f.push_back(Field::integer("p", s.p, bilateral));
    f.push_back(Field::integer("nnz_G", s.nnz_G, bilateral));
  } else {
    f.push_back(Field::integer("nnz_W", s.nnz_W));
    f.push_back(Field::integer("nonzeros_W", s.nonzeros_W));
  }
  f.push_back(Field::real("mu_min", s.mu_min, "%.6g"));
  f.push_back(Field::real("mu_max", s.mu_max, "%.6g"));
  f.push_back(Field::real(global ? "asymmetry_M" : "asymmetry_W", s.asymmetry, "%.3e"));
  f.push_back(Field::text("title", title, /*quoted_in_text=*/true));
  return f;
}

namespace detail {
/// The error, the report's own parts, then the worst contact; full
/// precision in every form.
template <class Report>
Fields error_fields(const Report& e, const Fields& parts, unsigned worst_contact_shown) {
  Fields f = {Field::real("error", e.error, "%.17g")};
  f.insert(f.end(), parts.begin(), parts.end());
  f.push_back(Field::real("max_contact", e.max_contact, "%.17g"));
  f.push_back(Field::integer("worst_contact", e.worst_contact, worst_contact_shown));
  return f;
}
}  // namespace detail

/// The FC/II error in its scalings.
inline Fields error_fields(const LocalErrorReport& e) {
  return detail::error_fields(e,
                              {Field::real("siconos_error", e.siconos_error, "%.17g"),
                               Field::real("absolute", e.absolute, "%.17g")},
                              ShownStructured);
}

/// The FC/I error and its two parts.
inline Fields error_fields(const GlobalErrorReport& e) {
  return detail::error_fields(e,
                              {Field::real("complementarity", e.complementarity, "%.17g"),
                               Field::real("equilibrium", e.equilibrium, "%.17g")},
                              ShownInPython);
}

}  // namespace fcsolve
