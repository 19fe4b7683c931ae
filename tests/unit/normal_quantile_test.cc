// Φ⁻¹ (AS 241): published quantiles, the closed form Φ(x) = erfc(−x/√2)/2, symmetry, refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "vstcal/core/error.h"
#include "vstcal/sensitivity/distribution.h"
#include "vstcal/sensitivity/normal_quantile.h"

namespace vstcal {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Reference quantiles at the double nearest each p, to 20 digits (mpmath, 60-digit arithmetic:
// the root of log(erfc(∓x/√2)/2) = log(p)). The first five are the familiar table values.
TEST(NormalQuantile, MatchesHighPrecisionReferenceQuantiles) {
  struct Case {
    double p, x;
  };
  const Case cases[] = {
      {0.75, 0.6744897501960817432},       {0.975, 1.9599639845400538556},
      {0.995, 2.5758293035489004539},      {0.999, 3.0902323061678132778},
      {0.9999999, 5.1993375822906610937},  {0.02425, -1.9729610513118848376},
      {0.3, -0.52440051270804081597},      {1e-5, -4.2648907939228246102},
      {1e-10, -6.3613409024040561991},     {1e-20, -9.2623400897984075796},
      {1e-300, -37.047096299361199237},
  };
  for (const Case& c : cases) {
    // AS 241 is accurate to about 1e-16 relative; allow 4 ulps.
    EXPECT_NEAR(NormalQuantile(c.p), c.x, 4 * kEps * std::abs(c.x)) << "p = " << c.p;
  }
  EXPECT_EQ(NormalQuantile(0.5), 0.0);
}

// Φ⁻¹(Φ(x)) = x through the closed form Φ(x) = erfc(−x/√2)/2 (std::erfc, a few ulps), over the
// three branches of the algorithm (central |p − ½| ≤ 0.425, tail r ≤ 5, far tail). Error budget:
// AS 241's own ≈ 1e-16 relative on x, plus p's rounding carried through dx = dp/φ(x) — relative
// dp ≈ ε on the lower side gives ≲ ε·Φ(x)/φ(x) ≤ ε; absolute dp ≈ ε near p = 1 gives ε/φ(x),
// which grows in the upper tail. A wrong coefficient digit moves x by far more than this.
TEST(NormalQuantile, InvertsTheClosedFormCdf) {
  int checked = 0;
  for (double x = -37.5; x <= 8.0; x += 0.0625) {
    const double p = 0.5 * std::erfc(-x / std::sqrt(2.0));
    if (!(p > 0 && p < 1)) continue;
    const double density = std::exp(-0.5 * x * x) / std::sqrt(2 * 3.14159265358979323846);
    const double tolerance = 8 * kEps * std::max(1.0, std::abs(x)) + (x > 0 ? kEps / density : 0.0);
    EXPECT_NEAR(NormalQuantile(p), x, tolerance) << "x = " << x;
    ++checked;
  }
  EXPECT_GT(checked, 700);
}

// For p = k/2²⁰, 1 − p is exact, and the algorithm treats p and 1 − p identically.
TEST(NormalQuantile, IsExactlySymmetric) {
  for (int k = 1; k < (1 << 20); k += 997) {
    const double p = std::ldexp(static_cast<double>(k), -20);
    EXPECT_EQ(NormalQuantile(1 - p), -NormalQuantile(p)) << "p = " << p;
  }
}

TEST(NormalQuantile, IsMonotone) {
  double previous = NormalQuantile(1e-12);
  for (double p = 1e-12; p < 1; p = p < 0.5 ? p * 1.37 : 1 - (1 - p) / 1.37) {
    const double x = NormalQuantile(p);
    EXPECT_GE(x, previous) << "p = " << p;
    previous = x;
    if (1 - p < 1e-12) break;
  }
}

TEST(NormalQuantile, RefusesProbabilitiesOutsideTheOpenInterval) {
  EXPECT_THROW(NormalQuantile(0.0), InputError);
  EXPECT_THROW(NormalQuantile(1.0), InputError);
  EXPECT_THROW(NormalQuantile(-0.1), InputError);
  EXPECT_THROW(NormalQuantile(std::nan("")), InputError);
}

TEST(Distribution, QuantilesMeansAndVariances) {
  const Distribution normal = Distribution::MakeNormal(2.0, 0.5);
  EXPECT_DOUBLE_EQ(normal.Quantile(0.975), 2.0 + 0.5 * 1.9599639845400538556);
  EXPECT_EQ(normal.Mean(), 2.0);
  EXPECT_EQ(normal.Variance(), 0.25);
  const Distribution uniform = Distribution::MakeUniform(-1.0, 3.0);
  EXPECT_EQ(uniform.Quantile(0.25), 0.0);
  EXPECT_EQ(uniform.Mean(), 1.0);
  EXPECT_DOUBLE_EQ(uniform.Variance(), 16.0 / 12.0);
  const Distribution fixed = Distribution::MakeFixed(0.3);
  EXPECT_EQ(fixed.Quantile(0.01), 0.3);
  EXPECT_EQ(fixed.Quantile(0.99), 0.3);
  EXPECT_TRUE(fixed.IsConstant());
  EXPECT_FALSE(normal.IsConstant());
  EXPECT_EQ(normal.Describe(), "normal(2, 0.5)");
}

TEST(Distribution, RefusesBadArguments) {
  EXPECT_THROW(Distribution::MakeNormal(0, -1), InputError);
  EXPECT_THROW(Distribution::MakeNormal(std::nan(""), 1), InputError);
  EXPECT_THROW(Distribution::MakeUniform(2, 1), InputError);
  EXPECT_THROW(Distribution::MakeFixed(std::numeric_limits<double>::infinity()), InputError);
  EXPECT_THROW(Distribution::MakeUniform(0, 1).Quantile(1.0), InputError);
}

}  // namespace
}  // namespace vstcal
