// A report as an ordered list of named values: the problem summary, the error
// report, a solve outcome and a catalogue entry are each described once
// (problem/report_fields.hpp, solvers/report_fields.hpp) and rendered by the
// front ends: the CLI as a key=value line or JSON (cli/field_output.hpp),
// Python as a dict (python/src/bindings.hpp). Order is the output order.
#pragma once

#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace fcsolve {

/// Where a field is shown. The key=value line is the short form; a few
/// fields are in one structured form only because they always were (the
/// CLI's and Python's keys are an interface: kept as published).
enum FieldOutput : unsigned {
  ShownInText = 1,    ///< the CLI's key=value line
  ShownInJson = 2,    ///< the CLI's --json object
  ShownInPython = 4,  ///< the Python dict
  ShownStructured = ShownInJson | ShownInPython,
  ShownEverywhere = ShownInText | ShownInJson | ShownInPython,
};

struct Field {
  using Value = std::variant<bool, long long, double, std::string>;

  std::string name;
  Value value;
  const char* number_format = "%.3e";  ///< printf format of a real in the key=value line
  bool quoted = false;                 ///< a string in the key=value line is quoted
  unsigned shown = ShownEverywhere;    ///< FieldOutput bits

  static Field integer(std::string name, long long x, unsigned shown = ShownEverywhere) {
    return {std::move(name), Value(x), "%.3e", false, shown};
  }
  static Field real(std::string name, double x, const char* text_format = "%.3e",
                    unsigned shown = ShownEverywhere) {
    return {std::move(name), Value(x), text_format, false, shown};
  }
  static Field flag(std::string name, bool x, unsigned shown = ShownEverywhere) {
    return {std::move(name), Value(x), "%.3e", false, shown};
  }
  static Field text(std::string name, std::string x, bool quoted_in_text = false,
                    unsigned shown = ShownEverywhere) {
    return {std::move(name), Value(std::move(x)), "%.3e", quoted_in_text, shown};
  }
  bool shown_in(FieldOutput where) const { return (shown & where) != 0; }
};

using Fields = std::vector<Field>;

}  // namespace fcsolve
