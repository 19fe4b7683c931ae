#include "vstcal/sensitivity/bootstrap.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"
#include "vstcal/sensitivity/unit_points.h"

namespace vstcal {

void BootstrapRows(uint64_t seed, uint64_t replicate, size_t num_rows, std::vector<size_t>& rows) {
  VSTCAL_CHECK(num_rows > 0, "bootstrap of no rows");
  // Stream 0 of the bootstrap seed; replicate r is the Philox index, so replicates are independent.
  const CounterRng rng(seed, 0);
  rows.resize(num_rows);
  const double n = static_cast<double>(num_rows);
  for (size_t j = 0; j < num_rows; j += 2) {
    const PhiloxCounter b = rng.Bits(replicate, static_cast<uint32_t>(j / 2));
    for (size_t h = 0; h < 2 && j + h < num_rows; ++h) {
      const uint64_t word = (uint64_t{b[2 * h]} << 32) | b[2 * h + 1];
      // floor(u·N) with u ∈ (0, 1): bias below N / 2^53 per row.
      rows[j + h] = std::min(num_rows - 1, static_cast<size_t>(ToOpenUnit(word) * n));
    }
  }
}

double SortedQuantile(std::span<const double> sorted, double p) {
  VSTCAL_CHECK(!sorted.empty() && p >= 0 && p <= 1, "quantile of an empty sample or p outside [0, 1]");
  const double h = p * static_cast<double>(sorted.size() - 1);
  const size_t lo = static_cast<size_t>(std::floor(h));
  if (lo + 1 >= sorted.size()) return sorted.back();
  return sorted[lo] + (h - static_cast<double>(lo)) * (sorted[lo + 1] - sorted[lo]);
}

Estimate SummarizeReplicates(double value, std::vector<double> replicates, double confidence) {
  Estimate e;
  e.value = value;
  e.interval = {value, value};
  if (replicates.size() < 2) return e;
  double mean = 0;
  for (double r : replicates) mean += r;
  mean /= static_cast<double>(replicates.size());
  double ss = 0;
  for (double r : replicates) ss += (r - mean) * (r - mean);
  e.standard_error = std::sqrt(ss / static_cast<double>(replicates.size() - 1));
  std::sort(replicates.begin(), replicates.end());
  e.interval = {SortedQuantile(replicates, 0.5 * (1 - confidence)), SortedQuantile(replicates, 0.5 * (1 + confidence))};
  return e;
}

}  // namespace vstcal
