// The CLI's two renderings of a report (fcsolve/core/report_fields.hpp): the
// key=value line and the members of a JSON object.
#pragma once

#include "json_writer.hpp"

#include <fcsolve/core/report_fields.hpp>

#include <cstdio>
#include <string>
#include <variant>

namespace fcsolve_cli {

/// A string as the key=value line shows it: in double quotes, with quotes and
/// backslashes escaped, a newline as \n and other control or non-ASCII bytes
/// as '?', so that the line stays one line of ASCII.
inline std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (c == '\n') { out += "\\n"; continue; }
    if (c < 0x20 || c >= 0x7f) { out += '?'; continue; }
    out += static_cast<char>(c);
  }
  return out + "\"";
}

inline std::string text_value(const fcsolve::Field& f) {
  struct Visitor {
    const fcsolve::Field& f;
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(long long i) const { return std::to_string(i); }
    std::string operator()(double x) const {
      char buf[40];
      std::snprintf(buf, sizeof buf, f.number_format, x);
      return buf;
    }
    std::string operator()(const std::string& s) const { return f.quoted ? quoted(s) : s; }
  };
  return std::visit(Visitor{f}, f.value);
}

/// "k1=v1 k2=v2 ..." of the fields shown in text.
inline std::string text_line(const fcsolve::Fields& fields) {
  std::string out;
  for (const auto& f : fields) {
    if (!f.shown_in(fcsolve::ShownInText)) continue;
    if (!out.empty()) out += ' ';
    out += f.name + "=" + text_value(f);
  }
  return out;
}

/// The fields shown in JSON, as members of the object `w` has open.
inline JsonWriter& json_fields(JsonWriter& w, const fcsolve::Fields& fields) {
  for (const auto& f : fields)
    if (f.shown_in(fcsolve::ShownInJson))
      std::visit([&](const auto& x) { w.field(f.name, x); }, f.value);
  return w;
}

}  // namespace fcsolve_cli
