// Count, mean, central moments M2…M4 (sums of powers of deviations), min and max of a stream of
// values, updated one value at a time and merged pairwise (Pébay 2008, "Formulas for robust,
// one-pass parallel computation of covariances and arbitrary-order statistical moments", SAND2008-6212,
// Eq. 1.1–1.4). Numerically stable for a large mean, unlike sums of powers. Floating-point merges are
// not associative, so callers that need identical bits fix the merge order (mc_summary.h).
#pragma once

#include <cstdint>
#include <limits>

namespace vstcal {

struct Moments {
  uint64_t count = 0;
  double mean = 0;
  double m2 = 0, m3 = 0, m4 = 0;  // Σ (x − mean)^k
  double min = std::numeric_limits<double>::infinity();
  double max = -std::numeric_limits<double>::infinity();

  void Add(double x);
  void Merge(const Moments& other);

  double Variance() const;  // unbiased, m2 / (count − 1); 0 below two values
  double StandardDeviation() const;
  double Rms() const;  // √(mean of x²) = √(mean² + m2 / count)
  // Standard error of the sample standard deviation s: √Var(s²) / (2s), with
  // Var(s²) ≈ (μ₄ − σ⁴ (N − 3)/(N − 1)) / N; for normal data μ₄ = 3σ⁴ and this is σ/√(2(N − 1)).
  double StandardDeviationStandardError() const;
};

}  // namespace vstcal
