// The nonparametric bootstrap (Efron & Tibshirani 1993): resample the N rows with replacement,
// recompute the estimate, and read its spread off R replicates. Deterministic: replicate r's row
// choices are Philox draws keyed by (seed, r), so intervals are the same for any thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace vstcal {

struct Interval {
  double lo = 0;
  double hi = 0;
};

// A point estimate with its bootstrap standard error and percentile interval.
struct Estimate {
  double value = 0;
  double standard_error = 0;  // standard deviation of the replicates (0 with no replicates)
  Interval interval;          // [value, value] with no replicates
};

// Rows of bootstrap replicate r: N indices in [0, N), uniform with replacement.
void BootstrapRows(uint64_t seed, uint64_t replicate, size_t num_rows, std::vector<size_t>& rows);

// Sample quantile of `sorted` (ascending, non-empty) at probability p ∈ [0, 1], linear
// interpolation between order statistics (Hyndman & Fan type 7, R's and NumPy's default).
double SortedQuantile(std::span<const double> sorted, double p);

// value ± the replicates' spread: SE = their standard deviation, interval = their
// (1 − confidence)/2 and (1 + confidence)/2 quantiles (the percentile interval).
Estimate SummarizeReplicates(double value, std::vector<double> replicates, double confidence);

}  // namespace vstcal
