// Typed, self-describing solver settings for the run-time solver catalogue
// (CLI, Python, benchmarks). A solver family declares each knob once
// (name, type, default, range, doc); values given as text or typed values
// are checked against that declaration, so a misspelt name or an
// out-of-range value raises a UsageError instead of being ignored.
#pragma once

#include <fcsolve/core/enum_names.hpp>
#include <fcsolve/core/exceptions.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace fcsolve {
namespace registry {

enum class SettingType { Real, Integer, Boolean, Choice };

inline constexpr EnumName<SettingType> kSettingTypeNames[] = {{SettingType::Real, "real"},
                                                             {SettingType::Integer, "integer"},
                                                             {SettingType::Boolean, "boolean"},
                                                             {SettingType::Choice, "choice"}};
constexpr const auto& enum_names(SettingType) { return kSettingTypeNames; }
inline const char* to_string(SettingType t) { return enum_to_string(t); }

using SettingValue = std::variant<bool, long long, double, std::string>;

struct SettingSpec {
  std::string name;
  SettingType type = SettingType::Real;
  SettingValue default_value;
  std::string doc;
  std::vector<std::string> choices;  ///< for Choice
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
};

inline SettingSpec real_setting(std::string name, double def, std::string doc,
                                double min = -std::numeric_limits<double>::infinity(),
                                double max = std::numeric_limits<double>::infinity()) {
  return {std::move(name), SettingType::Real, def, std::move(doc), {}, min, max};
}
inline SettingSpec integer_setting(std::string name, long long def, std::string doc,
                                   double min = -std::numeric_limits<double>::infinity(),
                                   double max = std::numeric_limits<double>::infinity()) {
  return {std::move(name), SettingType::Integer, def, std::move(doc), {}, min, max};
}
inline SettingSpec boolean_setting(std::string name, bool def, std::string doc) {
  return {std::move(name), SettingType::Boolean, def, std::move(doc), {}, 0, 1};
}
inline SettingSpec choice_setting(std::string name, std::string def,
                                  std::vector<std::string> choices, std::string doc) {
  return {std::move(name), SettingType::Choice, std::move(def), std::move(doc),
          std::move(choices)};
}

/// A choice among the names of enum E (core/enum_names.hpp), in table order.
template <class E>
SettingSpec enum_setting(std::string name, E def, std::string doc) {
  return choice_setting(std::move(name), enum_to_string(def), enum_choices<E>(), std::move(doc));
}

inline std::string format_value(const SettingValue& v) {
  struct {
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(long long i) const { return std::to_string(i); }
    std::string operator()(double x) const {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.6g", x);
      return buf;
    }
    std::string operator()(const std::string& s) const { return s; }
  } fmt;
  return std::visit(fmt, v);
}

/// Settings of one solver: every declared knob has a value (its default
/// unless set), and only declared knobs exist. Copies share their values
/// until one of them is set (copy on write): a request made from an entry's
/// cached defaults (registry::default_settings) copies no map.
class SettingValues {
 public:
  /// std::less<>: lookups by a literal build no std::string (the entries
  /// read their settings on every solve; on a one-contact problem that
  /// cost a third of NSGS' own time).
  using Map = std::map<std::string, SettingValue, std::less<>>;

  SettingValues() = default;
  explicit SettingValues(const std::vector<SettingSpec>& specs)
      : specs_(&specs), values_(std::make_shared<Map>()) {
    for (const auto& s : specs) (*values_)[s.name] = s.default_value;
  }

  /// Sets a typed value (ints are accepted for reals, 0/1 for booleans).
  void set(const std::string& name, const SettingValue& value) {
    const SettingSpec& s = spec(name);
    SettingValue checked = coerce(s, value);
    writable()[name] = std::move(checked);
  }
  /// Parses a textual value ("1e-3", "42", "true", "natural").
  void set_text(const std::string& name, const std::string& text) {
    const SettingSpec& s = spec(name);
    switch (s.type) {
      case SettingType::Real: {
        char* end = nullptr;
        errno = 0;
        const double x = std::strtod(text.c_str(), &end);
        if (text.empty() || *end != '\0' || errno == ERANGE)
          bad(s, "'" + text + "' is not a real number");
        set(name, x);
        return;
      }
      case SettingType::Integer: {
        char* end = nullptr;
        errno = 0;
        const long long i = std::strtoll(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || errno == ERANGE)
          bad(s, "'" + text + "' is not an integer");
        set(name, i);
        return;
      }
      case SettingType::Boolean:
        if (text == "true" || text == "1" || text == "yes" || text == "on") set(name, true);
        else if (text == "false" || text == "0" || text == "no" || text == "off") set(name, false);
        else bad(s, "'" + text + "' is not a boolean (true/false)");
        return;
      case SettingType::Choice:
        set(name, text);
        return;
    }
  }

  double real(std::string_view name) const { return std::get<double>(get(name)); }
  long long integer(std::string_view name) const { return std::get<long long>(get(name)); }
  bool boolean(std::string_view name) const { return std::get<bool>(get(name)); }
  /// The value of an enum_setting, parsed by the enum's own name table.
  template <class E>
  E enumerated(const char* name) const {
    return parse_enum<E>(choice(name), name);
  }
  const std::string& choice(std::string_view name) const {
    return std::get<std::string>(get(name));
  }
  const Map& values() const {
    static const Map none;
    return values_ ? *values_ : none;
  }
  bool declares(std::string_view name) const { return values().count(name) > 0; }
  /// The map itself, shared: while a holder keeps it, it cannot change (a
  /// shared map is copied before any write), so it identifies these values.
  std::shared_ptr<const Map> shared_values() const { return values_; }

 private:
  /// The map, this object's own before it changes (copy on write).
  Map& writable() {
    if (!values_) values_ = std::make_shared<Map>();
    else if (values_.use_count() > 1) values_ = std::make_shared<Map>(*values_);
    return *values_;
  }
  const SettingValue& get(std::string_view name) const {
    const Map& v = values();
    auto it = v.find(name);
    if (it == v.end()) throw UsageError("setting '" + std::string(name) + "' is not declared");
    return it->second;
  }
  const SettingSpec& spec(const std::string& name) const {
    if (specs_)
      for (const auto& s : *specs_)
        if (s.name == name) return s;
    std::string known;
    if (specs_)
      for (const auto& s : *specs_) known += (known.empty() ? "" : ", ") + s.name;
    throw UsageError("unknown setting '" + name + "'" +
                     (known.empty() ? " (this solver has no settings)" : " (known: " + known + ")"));
  }
  [[noreturn]] static void bad(const SettingSpec& s, const std::string& why) {
    throw UsageError("setting '" + s.name + "' (" + to_string(s.type) + "): " + why);
  }
  static SettingValue coerce(const SettingSpec& s, const SettingValue& v) {
    switch (s.type) {
      case SettingType::Real: {
        double x;
        if (auto d = std::get_if<double>(&v)) x = *d;
        else if (auto i = std::get_if<long long>(&v)) x = double(*i);
        else bad(s, "expected a real number");
        if (!std::isfinite(x) && !(std::isinf(x) && std::isinf(s.max) && x > 0))
          bad(s, "must be finite");
        if (x < s.min || x > s.max)
          bad(s, format_value(x) + " is outside [" + format_value(s.min) + ", " +
                     format_value(s.max) + "]");
        return x;
      }
      case SettingType::Integer: {
        long long i;
        if (auto p = std::get_if<long long>(&v)) i = *p;
        else if (auto d = std::get_if<double>(&v); d && std::floor(*d) == *d) i = (long long)*d;
        else bad(s, "expected an integer");
        if (double(i) < s.min || double(i) > s.max)
          bad(s, std::to_string(i) + " is outside [" + format_value(s.min) + ", " +
                     format_value(s.max) + "]");
        return i;
      }
      case SettingType::Boolean:
        if (auto b = std::get_if<bool>(&v)) return *b;
        if (auto i = std::get_if<long long>(&v); i && (*i == 0 || *i == 1)) return *i == 1;
        bad(s, "expected a boolean");
      case SettingType::Choice: {
        const auto* str = std::get_if<std::string>(&v);
        if (!str) bad(s, "expected one of its choices as a string");
        for (const auto& c : s.choices)
          if (c == *str) return *str;
        std::string list;
        for (const auto& c : s.choices) list += (list.empty() ? "" : ", ") + c;
        bad(s, "'" + *str + "' is not one of: " + list);
      }
    }
    bad(s, "unknown type");
  }

  const std::vector<SettingSpec>* specs_ = nullptr;
  std::shared_ptr<Map> values_;  ///< null: no knobs (a default-made object)
};

}  // namespace registry
}  // namespace fcsolve
