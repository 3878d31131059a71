// String helpers for core/io that take std::string_view.
//
// This Abseil build has its own absl::string_view type (ABSL_OPTION_USE_STD_STRING_VIEW is 0),
// so absl::StrCat and absl/strings/match.h do not accept std::string_view. `str_cat` forwards
// to absl::StrCat after adapting std::string_view arguments; the others are small enough to
// write out.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>

#include "absl/strings/str_cat.h"
#include "absl/strings/string_view.h"

namespace afmesh {
namespace string_util_internal {

template <typename T>
decltype(auto) adapt(const T& value) {
  if constexpr (std::is_same_v<T, std::string_view>) {
    return absl::string_view(value.data(), value.size());
  } else {
    return (value);
  }
}

}  // namespace string_util_internal

// absl::StrCat that also accepts std::string_view pieces.
template <typename... Pieces>
std::string str_cat(const Pieces&... pieces) {
  return absl::StrCat(string_util_internal::adapt(pieces)...);
}

inline char ascii_lower(char c) {
  return c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c;
}

// True when `a` and `b` are equal ignoring ASCII letter case.
inline bool equals_ignore_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (ascii_lower(a[i]) != ascii_lower(b[i])) return false;
  }
  return true;
}

// True when `text` begins with `prefix`, ignoring ASCII letter case.
inline bool starts_with_ignore_case(std::string_view text, std::string_view prefix) {
  return text.size() >= prefix.size() && equals_ignore_case(text.substr(0, prefix.size()), prefix);
}

// `text` with ASCII letters in lower case.
inline std::string ascii_lowercase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) c = ascii_lower(c);
  return lower;
}

}  // namespace afmesh
