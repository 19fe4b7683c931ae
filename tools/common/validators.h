// CLI11 validators shared by the tools. CLI11 alone reads "nan"/"inf" as doubles, wraps "-1" into
// unsigned integers and quotes DBL_MAX in its range messages (CLI::PositiveNumber: "Value -5 not in
// range 0 to 1797…", 309 digits); these say what is wanted instead.
// Lists of numbers ("X,Y,Z") are CLI11 options of typed vectors or arrays with ->delimiter(',')
// and ->check(kFinite), which CLI11 applies to every item.
#pragma once

#include <cstdint>
#include <utility>

#include <CLI/CLI.hpp>

namespace vstcal::tools {

extern const CLI::Validator kNonEmpty;       // a string flag given as ""
extern const CLI::Validator kFinite;         // a number (or each item of a list): no nan/inf, no "0.1x"
extern const CLI::Validator kPositiveFinite;  // a number flag > 0, finite
extern const CLI::Validator kSeed;           // a whole number in [0, 2^64)
extern const CLI::Validator kNonNegativeFinite;  // a number flag ≥ 0, finite
extern const CLI::Validator kPositiveCount;  // a whole number ≥ 1 (sample counts)
extern const CLI::Validator kCount;          // a whole number ≥ 0
extern const CLI::Validator kLengthUnit;     // one of vstcal::kLengthUnitNames (mm, cm, m, in)

// "i/N" with 0 ≤ i < N → {i, N}; throws InputError naming `flag` otherwise.
std::pair<uint64_t, uint64_t> ParseShard(const std::string& text, const std::string& flag);

// "1280x720" → {1280, 720}: two whole numbers from 1 to `max_side`; throws InputError naming
// `flag` and showing `example` otherwise.
std::pair<int, int> ParseSize(const std::string& text, const std::string& flag, const std::string& example,
                              int max_side);

}  // namespace vstcal::tools
