// An enum's names — the words its values have in files, messages and on command lines — declared
// once as a table; both directions and the list for messages derive from that table.
//
//   inline constexpr EnumNames<Viewer, 3> kViewerNames = {{{Viewer::kNone, "none"}, …}};
//   NameOf(kViewerNames, v);  FromName(kViewerNames, "hmd");  JoinedNames(kViewerNames)
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vstcal {

template <typename E>
struct EnumName {
  E value;
  std::string_view name;
};

template <typename E, size_t N>
using EnumNames = std::array<EnumName<E>, N>;

// The value's name; "?" for a value the table lacks (a bug the tests catch: every table is
// complete, tests/unit/enum_names_test.cc).
template <typename E, size_t N>
constexpr std::string_view NameOf(const EnumNames<E, N>& table, E value) {
  for (const EnumName<E>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

template <typename E, size_t N>
constexpr std::optional<E> FromName(const EnumNames<E, N>& table, std::string_view name) {
  for (const EnumName<E>& entry : table) {
    if (entry.name == name) return entry.value;
  }
  return std::nullopt;
}

// The names in table order, for a command line's choices.
template <typename E, size_t N>
std::vector<std::string> NamesOf(const EnumNames<E, N>& table) {
  std::vector<std::string> names;
  for (const EnumName<E>& entry : table) names.emplace_back(entry.name);
  return names;
}

// "\"a\", \"b\" or \"c\"", for messages.
template <typename E, size_t N>
std::string JoinedNames(const EnumNames<E, N>& table) {
  std::string text;
  for (size_t i = 0; i < N; ++i) {
    if (i > 0) text += i + 1 == N ? " or " : ", ";
    text += '"';
    text += table[i].name;
    text += '"';
  }
  return text;
}

}  // namespace vstcal
