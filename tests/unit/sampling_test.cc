// Points of the unit cube: addressed by index (any split gives the same bits), Philox keyed as
// documented, Sobol points forming a digitally shifted (t, m, s)-net; the parameter space.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"
#include "vstcal/sensitivity/parameter_space.h"
#include "vstcal/sensitivity/unit_points.h"

namespace vstcal {
namespace {

std::vector<double> FillAll(const UnitPoints& points, uint64_t first, size_t count) {
  std::vector<double> out(count * points.dimensions());
  points.Fill(first, count, out.data());
  return out;
}

class UnitPointsTest : public ::testing::TestWithParam<SamplingMethod> {};

TEST_P(UnitPointsTest, AnySplitGivesTheSameBits) {
  const UnitPoints points({GetParam(), 42, 3}, 7);
  const std::vector<double> whole = FillAll(points, 0, 300);
  std::vector<double> pieces;
  for (auto [first, count] : {std::pair<uint64_t, size_t>{0, 1}, {1, 128}, {129, 5}, {134, 166}}) {
    const std::vector<double> part = FillAll(points, first, count);
    pieces.insert(pieces.end(), part.begin(), part.end());
  }
  EXPECT_EQ(whole, pieces);
  for (double u : whole) {
    EXPECT_GT(u, 0.0);
    EXPECT_LT(u, 1.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, UnitPointsTest,
                         ::testing::Values(SamplingMethod::kPseudoRandom, SamplingMethod::kSobol));

TEST(UnitPoints, PhiloxCoordinateIsKeyedBySampleAndParameter) {
  const UnitPoints points({SamplingMethod::kPseudoRandom, 7, 2}, 5);
  const CounterRng rng(7, 2);
  const std::vector<double> u = FillAll(points, 1000, 1);
  EXPECT_EQ(u[0], rng.Uniform2(1000, 0)[0]);
  EXPECT_EQ(u[1], rng.Uniform2(1000, 0)[1]);
  EXPECT_EQ(u[4], rng.Uniform2(1000, 2)[0]);
}

// The first 2^m points of a digitally shifted Sobol sequence are a (t, m, s)-net: in the first
// two dimensions (t = 0) every elementary box of area 2^-m holds exactly one point, whatever the
// shift. Dropping point 0 (as Boost's sequence does) or a wrong shift would break this.
TEST(UnitPoints, SobolPointsFormAShiftedNet) {
  const int m = 10;
  const size_t n = size_t{1} << m;
  for (uint64_t seed : {0u, 1u, 99u}) {
    const UnitPoints points({SamplingMethod::kSobol, seed, 0}, 4);
    const std::vector<double> u = FillAll(points, 0, n);
    for (int split = 0; split <= m; ++split) {  // boxes 2^-split × 2^-(m − split)
      std::vector<int> count(n, 0);
      for (size_t i = 0; i < n; ++i) {
        const size_t a = static_cast<size_t>(std::ldexp(u[4 * i], split));
        const size_t b = static_cast<size_t>(std::ldexp(u[4 * i + 1], m - split));
        count[(a << (m - split)) | b]++;
      }
      for (size_t box = 0; box < n; ++box) ASSERT_EQ(count[box], 1) << "seed " << seed << " split " << split;
    }
  }
}

TEST(UnitPoints, SobolShiftDependsOnTheSeed) {
  const std::vector<double> a = FillAll(UnitPoints({SamplingMethod::kSobol, 1, 0}, 3), 0, 4);
  const std::vector<double> b = FillAll(UnitPoints({SamplingMethod::kSobol, 2, 0}, 3), 0, 4);
  EXPECT_NE(a, b);
}

TEST(UnitPoints, RefusesBadDimensions) {
  EXPECT_THROW(UnitPoints({SamplingMethod::kPseudoRandom, 0, 0}, 0), InputError);
  EXPECT_THROW(UnitPoints({SamplingMethod::kSobol, 0, 0}, 4000), InputError);
  EXPECT_NO_THROW(UnitPoints({SamplingMethod::kPseudoRandom, 0, 0}, 4000));
  EXPECT_EQ(ParseSamplingMethod("sobol"), SamplingMethod::kSobol);
  EXPECT_EQ(SamplingMethodName(SamplingMethod::kPseudoRandom), "pseudo-random");
  EXPECT_THROW(ParseSamplingMethod("halton"), InputError);
}

TEST(ParameterSpace, GroupsInOrderOfFirstAppearance) {
  ParameterSpace space({{"a", "tracking", Distribution::MakeNormal(0, 1), {}},
                        {"b", "display", Distribution::MakeUniform(1, 3), {}},
                        {"c", "tracking", Distribution::MakeFixed(0.5), 0.0}});
  EXPECT_EQ(space.group_names(), (std::vector<std::string>{"tracking", "display"}));
  EXPECT_EQ(space.GroupMembers(0), (std::vector<size_t>{0, 2}));
  EXPECT_EQ(space.GroupOf(1), 1u);
  EXPECT_EQ(space.Nominal(), (std::vector<double>{0, 2, 0}));
  EXPECT_EQ(space.Mean(), (std::vector<double>{0, 2, 0.5}));
  EXPECT_EQ(space.IndexOf("c"), 2u);
  EXPECT_THROW(space.IndexOf("d"), InputError);
  EXPECT_THROW(space.Add({"a", "x", Distribution::MakeFixed(0), {}}), InputError);
  EXPECT_THROW(space.Add({"", "x", Distribution::MakeFixed(0), {}}), InputError);
  EXPECT_THROW(space.Add({"e", "", Distribution::MakeFixed(0), {}}), InputError);
}

}  // namespace
}  // namespace vstcal
