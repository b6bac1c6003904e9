// Every setting enum's text names in one table beside the enum, so that its
// to_string and its parser can never disagree. An enum E opts in with
//
//   inline constexpr EnumName<E> kENames[] = {{E::A, "a"}, {E::B, "b"}};
//   constexpr const auto& enum_names(E) { return kENames; }   // found by ADL
//
// and gets enum_to_string(e), parse_enum<E>(text) and enum_choices<E>()
// (the names in table order, as the catalogue lists them). An enum of
// namespace fcsolve also gets to_string(e); one of a nested namespace
// declares its own `to_string(E e) { return enum_to_string(e); }` there.
#pragma once

#include <fcsolve/core/exceptions.hpp>

#include <string>
#include <vector>

namespace fcsolve {

template <class E>
struct EnumName {
  E value;
  const char* name;
};

template <class E>
const char* enum_to_string(E e) {
  for (const auto& n : enum_names(E{}))
    if (n.value == e) return n.name;
  return "?";
}

/// to_string for every enum of namespace fcsolve that has a name table.
template <class E, class = decltype(enum_names(E{}))>
const char* to_string(E e) {
  return enum_to_string(e);
}

template <class E>
std::vector<std::string> enum_choices() {
  std::vector<std::string> v;
  for (const auto& n : enum_names(E{})) v.emplace_back(n.name);
  return v;
}

/// The value named `text`; UsageError naming `what` and the choices otherwise.
template <class E>
E parse_enum(const std::string& text, const char* what) {
  std::string list;
  for (const auto& n : enum_names(E{})) {
    if (text == n.name) return n.value;
    list += (list.empty() ? "" : ", ") + std::string(n.name);
  }
  throw UsageError(std::string(what) + ": unknown value '" + text + "' (expected one of " + list + ")");
}

}  // namespace fcsolve
