// Counter-based random numbers: Random123's known-answer vectors and basic statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

// Random123 kat_vectors, philox4x32 with 10 rounds: counter, key → output.
TEST(Philox, KnownAnswers) {
  EXPECT_EQ(Philox4x32({0, 0, 0, 0}, {0, 0}), (PhiloxCounter{0x6627e8d5, 0xe169c58d, 0xbc57ac4c, 0x9b00dbd8}));
  EXPECT_EQ(Philox4x32({0xffffffff, 0xffffffff, 0xffffffff, 0xffffffff}, {0xffffffff, 0xffffffff}),
            (PhiloxCounter{0x408f276d, 0x41c83b0e, 0xa20bc7c6, 0x6d5451fd}));
  EXPECT_EQ(Philox4x32({0x243f6a88, 0x85a308d3, 0x13198a2e, 0x03707344}, {0xa4093822, 0x299f31d0}),
            (PhiloxCounter{0xd16cfe09, 0x94fdcceb, 0x5001e420, 0x24126ea1}));
  static_assert(Philox4x32({0, 0, 0, 0}, {0, 0})[0] == 0x6627e8d5, "usable at compile time");
}

TEST(Philox, DrawsArePureFunctionsOfTheirKey) {
  const CounterRng a(42, 3), b(42, 3), other_stream(42, 4), other_seed(43, 3);
  EXPECT_EQ(a.Normal2(123456789, 2), b.Normal2(123456789, 2));
  EXPECT_NE(a.Normal2(5, 0), other_stream.Normal2(5, 0));
  EXPECT_NE(a.Normal2(5, 0), other_seed.Normal2(5, 0));
  EXPECT_NE(a.Normal2(5, 0), a.Normal2(5, 1));
  EXPECT_NE(a.Normal2(5, 0), a.Normal2(1ull << 40 | 5, 0));  // the index's high word matters
}

// 200,000 normals: mean within 5 standard errors of 0, variance within 5 standard errors of 1
// (SE of the variance of N normals ≈ √(2/N)), uniforms inside (0, 1), and the pair uncorrelated.
TEST(Philox, NormalMomentsAndUniformRange) {
  const CounterRng rng(2026, 0);
  const int n = 100000;
  double sum = 0, sum2 = 0, cross = 0, lo = 1, hi = 0;
  for (int i = 0; i < n; ++i) {
    const auto z = rng.Normal2(i, 0);
    sum += z[0] + z[1];
    sum2 += z[0] * z[0] + z[1] * z[1];
    cross += z[0] * z[1];
    const auto u = rng.Uniform2(i, 1);
    lo = std::min({lo, u[0], u[1]});
    hi = std::max({hi, u[0], u[1]});
  }
  const double count = 2.0 * n;
  EXPECT_LT(std::abs(sum / count), 5 / std::sqrt(count));
  EXPECT_LT(std::abs(sum2 / count - 1), 5 * std::sqrt(2 / count));
  EXPECT_LT(std::abs(cross / n), 5 / std::sqrt(static_cast<double>(n)));
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi, 1.0);
  EXPECT_LT(lo, 1e-4);
  EXPECT_GT(hi, 1 - 1e-4);
}

}  // namespace
}  // namespace vstcal
