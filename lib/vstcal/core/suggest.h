// "Did you mean …?" for an unknown name (a key in a file, a term on the command line): the
// candidate closest by edit distance, when it is close enough to be a likely typo.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace vstcal {

// The candidate closest to `word` by edit distance, when it is close enough to be a likely typo
// (at most a third of the word's length, at least 1 edit); nullopt otherwise.
std::optional<std::string_view> ClosestMatch(std::string_view word, std::span<const std::string_view> candidates);

// The fix part of a message about an unknown key: `did you mean "tracking"? (known: a, b, …)` when
// a candidate is close, `use one of a, b, …` otherwise.
std::string SuggestKey(std::string_view word, std::span<const std::string_view> candidates);

}  // namespace vstcal
