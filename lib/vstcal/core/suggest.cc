#include "vstcal/core/suggest.h"

#include <algorithm>
#include <vector>

namespace vstcal {
namespace {

size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<std::string_view> ClosestMatch(std::string_view word, std::span<const std::string_view> candidates) {
  std::optional<std::string_view> best;
  size_t best_distance = std::max<size_t>(1, word.size() / 3) + 1;
  for (const std::string_view c : candidates) {
    const size_t d = EditDistance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string SuggestKey(std::string_view word, std::span<const std::string_view> candidates) {
  std::string known;
  for (const std::string_view c : candidates) known += (known.empty() ? "" : ", ") + std::string(c);
  const auto match = ClosestMatch(word, candidates);
  if (match) return "did you mean \"" + std::string(*match) + "\"? (known: " + known + ")";
  return "use one of " + known;
}

}  // namespace vstcal
