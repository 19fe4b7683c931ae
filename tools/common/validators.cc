#include "common/validators.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "vstcal/core/error.h"
#include "vstcal/core/units.h"

namespace vstcal::tools {
namespace {

// True when the whole text is one number; its value in *v.
bool ParseNumber(const std::string& text, double* v) {
  char* end = nullptr;
  *v = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

}  // namespace

const CLI::Validator kNonEmpty([](std::string& text) -> std::string { return text.empty() ? "must not be empty" : ""; },
                               "NONEMPTY");

const CLI::Validator kLengthUnit = CLI::IsMember(std::vector<std::string>(kLengthUnitNames.begin(), kLengthUnitNames.end()));

const CLI::Validator kFinite(
    [](std::string& text) -> std::string {
      double v = 0;
      if (ParseNumber(text, &v) && !std::isfinite(v)) return "must be a finite number, got " + text;
      return "";  // anything else is for CLI11's own conversion to judge
    },
    "FINITE");

const CLI::Validator kPositiveFinite(
    [](std::string& text) -> std::string {
      double v = 0;
      if (!ParseNumber(text, &v) || !std::isfinite(v) || !(v > 0)) return "expected a positive number, got \"" + text + "\"";
      return "";
    },
    "POSITIVE");

const CLI::Validator kSeed(
    [](std::string& text) -> std::string {
      uint64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (text.empty() || ec != std::errc() || end != text.data() + text.size()) {
        return "expected a whole number from 0 to 18446744073709551615, got \"" + text + "\"";
      }
      return "";
    },
    "UINT64");

const CLI::Validator kPositiveCount(
    [](std::string& text) -> std::string {
      uint64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (text.empty() || ec != std::errc() || end != text.data() + text.size() || v == 0) {
        return "expected a whole number ≥ 1, got \"" + text + "\"";
      }
      return "";
    },
    "COUNT");

std::pair<uint64_t, uint64_t> ParseShard(const std::string& text, const std::string& flag) {
  const size_t slash = text.find('/');
  uint64_t i = 0, n = 0;
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  bool ok = slash != std::string::npos;
  if (ok) {
    const auto a = std::from_chars(begin, begin + slash, i);
    const auto b = std::from_chars(begin + slash + 1, end, n);
    ok = slash > 0 && a.ec == std::errc() && a.ptr == begin + slash && b.ec == std::errc() && b.ptr == end && n > 0 && i < n;
  }
  if (!ok) throw InputError(flag + ": expected i/N with 0 ≤ i < N (e.g. 0/4), got \"" + text + "\"; number the shards 0 … N−1");
  return {i, n};
}

std::pair<int, int> ParseSize(const std::string& text, const std::string& flag, const std::string& example) {
  int a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X') || a <= 0 || b <= 0) {
    throw InputError(flag + ": expected two positive integers as " + example + ", got \"" + text + "\"");
  }
  return {a, b};
}

Eigen::Vector2d ParsePoint2(const std::string& text, const std::string& flag) {
  const auto items = CLI::detail::split(text, ',');
  Eigen::Vector2d p;
  bool ok = items.size() == 2;
  for (size_t i = 0; ok && i < 2; ++i) ok = ParseNumber(items[i], &p(i)) && std::isfinite(p(i));
  if (!ok) throw InputError(flag + ": expected two numbers U,V (e.g. 640.5,360), got \"" + text + "\"");
  return p;
}

}  // namespace vstcal::tools
