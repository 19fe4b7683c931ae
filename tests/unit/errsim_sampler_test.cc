// err-sim's fast sampler: the ziggurat's layer table has equal areas and the normal's tail, its
// normal deviates follow Φ (CDF at 13 points including both sides of the tail edge r = 4.0388,
// moments up to the kurtosis) within 5 standard errors, uniforms
// stay in their bounds, constants are never drawn, and a row does not depend on the batch it is
// drawn in.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>

#include "support/vst_scenes.h"
#include "vstcal/errsim/sampler.h"

namespace vstcal {
namespace {

namespace table {
#include "vstcal/errsim/ziggurat_table.inc"
}

// The frozen table (scripts/golden/ziggurat_table.py, 60-digit arithmetic) against libm in double:
// f(x) = exp(−x²/2) at every edge; every layer's rectangle x[i]·(f(x[i+1]) − f(x[i])) and the base
// strip's x[0]·f(r) have one area v; and v = r f(r) + ∫_r^∞ f, the base strip holding the tail.
TEST(ZigguratTable, LayersOfEqualAreaAndTheNormalTail) {
  const auto& x = table::kZigX;
  const auto& f = table::kZigF;
  constexpr size_t n = x.size() - 1;
  ASSERT_EQ(n, size_t{1} << table::kZigLayerBits);
  EXPECT_EQ(x[1], table::kR);
  EXPECT_EQ(x[n], 0.0);
  EXPECT_EQ(f[n], 1.0);
  for (size_t i = 0; i <= n; ++i) EXPECT_NEAR(f[i], std::exp(-0.5 * x[i] * x[i]), 4e-16) << i;
  const double r = table::kR;
  const double v = r * f[1] + std::sqrt(std::numbers::pi / 2) * std::erfc(r / std::numbers::sqrt2);
  EXPECT_NEAR(x[0] * f[1], v, 1e-14 * v);
  for (size_t i = 1; i < n; ++i) EXPECT_NEAR(x[i] * (f[i + 1] - f[i]), v, 1e-11 * v) << "layer " << i;
  for (size_t i = 1; i < n; ++i) EXPECT_GT(x[i], x[i + 1]);
}

TEST(ZigguratNormal, FollowsTheNormalDistribution) {
  const CounterRng rng(99, 1);
  const int n = 2000000;
  const std::vector<double> edges = {-4.3, -4.0, -3.7, -2.0, -1.0, -0.3, 0.0, 0.5, 1.5, 2.5, 3.6542, 4.0388, 4.3};
  std::vector<int> below(edges.size());
  double s1 = 0, s2 = 0, s4 = 0;
  for (int i = 0; i < n; ++i) {
    const PhiloxCounter b = rng.Bits(i, 0);
    const double z = ZigguratNormal(uint64_t{b[0]} << 32 | b[1], rng, i, 0);
    s1 += z;
    s2 += z * z;
    s4 += z * z * z * z;
    for (size_t k = 0; k < edges.size(); ++k) below[k] += z < edges[k];
  }
  EXPECT_NEAR(s1 / n, 0.0, 5 / std::sqrt(n));
  EXPECT_NEAR(s2 / n, 1.0, 5 * std::sqrt(2.0 / n));
  EXPECT_NEAR(s4 / n, 3.0, 5 * std::sqrt(96.0 / n));  // Var(z⁴) = 105 − 9 = 96
  for (size_t k = 0; k < edges.size(); ++k) {
    const double p = 0.5 * std::erfc(-edges[k] / std::sqrt(2.0));
    EXPECT_NEAR(static_cast<double>(below[k]) / n, p, 5 * std::sqrt(p * (1 - p) / n) + 1e-7) << "z < " << edges[k];
  }
}

TEST(ThetaSampler, DrawsOnlyRandomParametersAndRowsDoNotDependOnTheBatch) {
  ChainModel m = ChainModel::WithZeroErrors(testing::ParallelRig({{0, 0, 0}}));
  m.parameters[0].distribution = Distribution::MakeNormal(1.0, 2.0);
  m.parameters[5].distribution = Distribution::MakeUniform(-3.0, 5.0);
  m.parameters[7].distribution = Distribution::MakeFixed(0.25);
  const ThetaSampler sampler(m, 42);
  EXPECT_EQ(sampler.num_random(), 2u);
  const size_t n = sampler.size(), count = 1000;
  std::vector<double> batch(count * n), one(n);
  sampler.Fill(5000, count, batch.data());
  double lo = 1e9, hi = -1e9;
  for (size_t s = 0; s < count; ++s) {
    sampler.Fill(5000 + s, 1, one.data());
    for (size_t j = 0; j < n; ++j) ASSERT_EQ(batch[s * n + j], one[j]);
    EXPECT_EQ(one[7], 0.25);
    EXPECT_EQ(one[1], 0.0);
    lo = std::min(lo, one[5]);
    hi = std::max(hi, one[5]);
  }
  EXPECT_GT(lo, -3.0);
  EXPECT_LT(hi, 5.0);
  EXPECT_LT(lo, -2.9);
  EXPECT_GT(hi, 4.9);
  // Another seed, other numbers.
  const ThetaSampler other(m, 43);
  other.Fill(5000, 1, one.data());
  EXPECT_NE(one[0], batch[0]);
}

}  // namespace
}  // namespace vstcal
