// printf into a std::string as long as the text needs: a fixed buffer cut lines short (a camera
// centre of 1e200 printed with %.2f is three 200-digit numbers, cut at 512 bytes).
#pragma once

#include <cstdio>
#include <string>

namespace vstcal {

template <typename... Args>
std::string StringPrintf(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  if (n <= 0) return {};
  std::string text(static_cast<size_t>(n), '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

}  // namespace vstcal
