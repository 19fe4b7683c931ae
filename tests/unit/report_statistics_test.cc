// lib/vstcal/report: statistics and the image grid, on cases computed by hand
// (docs/math/report-statistics.md).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/report/statistics.h"

namespace vstcal {
namespace {

TEST(ErrorStats, FourValuesByHand) {
  const std::vector<double> x = {4, 1, 3, 2};  // unsorted on purpose
  const auto s = ComputeErrorStats(x);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->n, 4u);
  EXPECT_DOUBLE_EQ(s->mean, 2.5);
  EXPECT_DOUBLE_EQ(s->rms, std::sqrt(30.0 / 4));  // (16 + 1 + 9 + 4) / 4
  EXPECT_DOUBLE_EQ(s->median, 2.5);               // h = 1.5: between 2 and 3
  EXPECT_DOUBLE_EQ(s->p95, 3.85);                 // h = 0.95·3 = 2.85: 3 + 0.85·(4 − 3)
  EXPECT_DOUBLE_EQ(s->max, 4);
}

TEST(ErrorStats, OddCountMedianIsTheMiddleValue) {
  const std::vector<double> x = {10, 0, 7, 1, 2};
  const auto s = ComputeErrorStats(x);
  ASSERT_TRUE(s);
  EXPECT_DOUBLE_EQ(s->median, 2);
  EXPECT_DOUBLE_EQ(s->p95, 7 + 0.8 * 3);  // h = 3.8 → 7 + 0.8·(10 − 7)
  EXPECT_DOUBLE_EQ(s->mean, 4);
}

TEST(ErrorStats, OneValueAndNone) {
  const std::vector<double> one = {0.25};
  const auto s = ComputeErrorStats(one);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->median, 0.25);
  EXPECT_EQ(s->p95, 0.25);
  EXPECT_EQ(s->rms, 0.25);
  EXPECT_FALSE(ComputeErrorStats(std::vector<double>{}));
}

TEST(ErrorStats, NonFiniteIsABug) {
  const std::vector<double> x = {1, NAN};
  EXPECT_THROW(ComputeErrorStats(x), InternalError);
}

TEST(ImageGrid, CellEdgesAreHalfAPixelOutsideTheCentres) {
  const ImageGrid g{{640, 480}, 2, 2};
  EXPECT_EQ(g.CellOf({-0.5, -0.5}), 0u);
  EXPECT_EQ(g.CellOf({319.49, 0}), 0u);
  EXPECT_EQ(g.CellOf({319.5, 0}), 1u);  // u + 0.5 = 320: the second column starts here
  EXPECT_EQ(g.CellOf({0, 239.5}), 2u);
  EXPECT_EQ(g.CellOf({639.4, 479.4}), 3u);
  EXPECT_FALSE(g.CellOf({639.5, 0}));  // the image's right edge belongs to no cell
  EXPECT_FALSE(g.CellOf({-0.51, 0}));
  EXPECT_FALSE(g.CellOf({NAN, 0}));
}

TEST(ImageGrid, StatisticsPerCell) {
  const ImageGrid g{{100, 100}, 2, 1};
  const std::vector<Eigen::Vector2d> px = {{10, 10}, {20, 90}, {80, 50}, {200, 50}};
  const std::vector<double> e = {1, 3, 5, 100};  // the last one is outside the image: no cell
  const auto cells = ComputeGridStats(g, px, e);
  ASSERT_EQ(cells.size(), 2u);
  ASSERT_TRUE(cells[0] && cells[1]);
  EXPECT_EQ(cells[0]->n, 2u);
  EXPECT_DOUBLE_EQ(cells[0]->mean, 2);
  EXPECT_EQ(cells[1]->n, 1u);
  EXPECT_DOUBLE_EQ(cells[1]->max, 5);
}

}  // namespace
}  // namespace vstcal
