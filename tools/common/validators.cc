#include "common/validators.h"

#include <charconv>
#include <cmath>
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
      if (!ParseNumber(text, &v)) return "expected a number, got \"" + text + "\"";
      if (!std::isfinite(v)) return "must be a finite number, got " + text;
      return "";
    },
    "");  // no name: CLI11 would append it to the type in its messages ("X,Y,Z:FINITE")

const CLI::Validator kPositiveFinite(
    [](std::string& text) -> std::string {
      double v = 0;
      if (!ParseNumber(text, &v) || !std::isfinite(v) || !(v > 0)) return "expected a positive number, got \"" + text + "\"";
      return "";
    },
    "POSITIVE");

const CLI::Validator kNonNegativeFinite(
    [](std::string& text) -> std::string {
      double v = 0;
      if (!ParseNumber(text, &v) || !std::isfinite(v) || !(v >= 0)) return "expected a number ≥ 0, got \"" + text + "\"";
      return "";
    },
    "NONNEGATIVE");

const CLI::Validator kCount(
    [](std::string& text) -> std::string {
      uint64_t v = 0;
      const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
      if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return "expected a whole number ≥ 0, got \"" + text + "\"";
      return "";
    },
    "COUNT");

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

std::pair<int, int> ParseSize(const std::string& text, const std::string& flag, const std::string& example,
                              int max_side) {
  // Each side as digits only; a side beyond any integer type is "too large", not malformed.
  const size_t x = text.find_first_of("xX");
  bool too_large = false;
  auto side = [&](std::string_view digits) -> long long {
    long long v = 0;
    const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (digits.empty() || ptr != digits.data() + digits.size() || digits[0] == '-') return 0;
    if (ec == std::errc::result_out_of_range) too_large = true;
    return ec == std::errc() ? v : 0;
  };
  const std::string_view all(text);
  const long long a = x == std::string::npos ? 0 : side(all.substr(0, x));
  const long long b = x == std::string::npos ? 0 : side(all.substr(x + 1));
  if (too_large || a > max_side || b > max_side) {
    throw InputError(flag + ": " + text + " exceeds the largest side vstcal accepts, " + std::to_string(max_side) +
                     " (docs/reliability.md#limits); give a smaller size");
  }
  if (a <= 0 || b <= 0) {
    throw InputError(flag + ": expected two positive integers as " + example + ", got \"" + text + "\"");
  }
  return {static_cast<int>(a), static_cast<int>(b)};
}

}  // namespace vstcal::tools
