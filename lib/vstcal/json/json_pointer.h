// A JSON pointer ("/a/b/3", RFC 6901) from keys and array indices given as text: how a page names
// the value a cell shows (`data-key`) and finds it in a file. Keys are the formats' declared ones
// (formats/errsim/report_keys.h, formats/report/report_keys.h), none of which needs escaping.
#pragma once

#include <initializer_list>
#include <string>
#include <string_view>

namespace vstcal {

inline std::string JsonPointer(std::initializer_list<std::string_view> parts) {
  std::string pointer;
  for (const std::string_view part : parts) pointer.append("/").append(part);
  return pointer;
}

}  // namespace vstcal
