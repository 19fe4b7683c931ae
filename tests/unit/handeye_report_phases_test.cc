// Where the views fall between the tracker's reports (ViewReportPhases,
// docs/math/handeye.md#report-phases): the phases computed by hand for regular and irregular
// reports, the circular mean across the report (0.95 and 0.05 average to 0, not ½), distinct times
// only, and a solve's own phases for views locked to the reports and for views spread by jitter.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/handeye_scenes.h"
#include "vstcal/handeye/report_phases.h"

namespace vstcal {
namespace {

std::vector<TrackedPose> Reports(const std::vector<double>& times) {
  std::vector<TrackedPose> log;
  for (double t : times) log.push_back({t, Rigid3d::Identity()});
  return log;
}

TEST(HandEyeReportPhases, PhasesByHand) {
  std::vector<double> grid;
  for (int k = 0; k <= 1000; ++k) grid.push_back(k * 0.01);
  const std::vector<TrackedPose> log = Reports(grid);
  // Every 0.6 s with δ = 35 ms: half-way through each 10 ms interval.
  std::vector<double> times;
  for (int i = 0; i < 16; ++i) times.push_back(0.5 + 0.6 * i);
  ReportPhases p = ViewReportPhases(log, times, 0.035);
  EXPECT_EQ(p.instants, 16u);
  EXPECT_NEAR(p.concentration, 1, 1e-9);
  EXPECT_NEAR(p.mean, 0.5, 1e-9);
  EXPECT_TRUE(p.Locked());
  // s = 0.95 and 0.05: across a report, the circular mean is the report (0), the length cos(0.1π).
  p = ViewReportPhases(log, std::vector<double>{1.0095, 2.0005}, 0);
  EXPECT_EQ(p.instants, 2u);
  EXPECT_NEAR(p.concentration, std::cos(0.1 * M_PI), 1e-9);
  EXPECT_NEAR(std::min(p.mean, 1 - p.mean), 0, 1e-9);
  // Four views at s = 0, ¼, ½, ¾: spread evenly, length 0.
  p = ViewReportPhases(log, std::vector<double>{1.0, 2.0025, 3.005, 4.0075}, 0);
  EXPECT_NEAR(p.concentration, 0, 1e-9);
  EXPECT_FALSE(p.Locked());
  // A time twice (a rig's pair) counts once; times whose t + δ is outside the log not at all.
  p = ViewReportPhases(log, std::vector<double>{1.0025, 1.0025, -1, 20}, 0);
  EXPECT_EQ(p.instants, 1u);
  EXPECT_NEAR(p.mean, 0.25, 1e-9);
  EXPECT_EQ(ViewReportPhases(log, std::vector<double>{}, 0).instants, 0u);
}

// Irregular reports: s is measured in the interval that holds t + δ, whatever its length.
TEST(HandEyeReportPhases, IrregularReports) {
  const std::vector<TrackedPose> log = Reports({0, 0.01, 0.03, 0.04});
  const ReportPhases p = ViewReportPhases(log, std::vector<double>{0.015}, 0.01);  // 0.025 in [0.01, 0.03)
  EXPECT_EQ(p.instants, 1u);
  EXPECT_NEAR(p.mean, 0.75, 1e-9);
}

// A solve reports them: 16 views 0.6 s apart (the tracker at 100 Hz) sit at one place, δ's share of
// the interval; with a report interval of jitter on the camera's clock they spread.
TEST(HandEyeReportPhases, SolveReportsLockedAndSpreadViews) {
  HandEyeSpec spec = testing::HandEyeTestSpec(0.0325, 0.2, 11);
  spec.views = 16;
  testing::HandEyeRecording r = testing::RecordHandEye(spec);
  HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  EXPECT_EQ(s.report_phases.instants, 16u);
  EXPECT_GT(s.report_phases.concentration, 0.99);
  EXPECT_NEAR(s.report_phases.mean, 0.25, 0.05);
  spec.view_jitter = 0.01;
  r = testing::RecordHandEye(spec);
  s = SolveHandEye(r.camera, r.log, r.views);
  EXPECT_FALSE(s.report_phases.Locked()) << s.report_phases.concentration;
}

// In doubt: locked, within 0.2 of the middle, the first-order σ spanning 0.1 … 0.4 of an interval.
TEST(HandEyeReportPhases, InDoubtOnlyForLockedViewsNearTheMiddleAtTheMeasuredSpans) {
  ReportPhases p;
  p.concentration = 1;
  p.mean = 0.45;
  p.instants = 16;
  EXPECT_TRUE(OffsetSigmaInDoubt(p, 0.15));
  EXPECT_TRUE(OffsetSigmaInDoubt(p, 0.29));
  EXPECT_FALSE(OffsetSigmaInDoubt(p, 0.05));  // both σ's within 10 % there
  EXPECT_FALSE(OffsetSigmaInDoubt(p, 0.48));
  p.mean = 0.25;  // outside the band (0.3, 0.7)
  EXPECT_FALSE(OffsetSigmaInDoubt(p, 0.15));
  p.mean = 0.65;
  p.concentration = 0.3;  // not locked
  EXPECT_FALSE(OffsetSigmaInDoubt(p, 0.15));
}

// The solve warns where the Monte Carlo of docs/math/handeye.md#report-phases found σ_δ 16 … 22 %
// low — 16 views locked midway, 0.05° and 0.2 mm a report, σ_δ 0.15 of an interval — and not where
// it found both σ's within 5 %: the same with 0.02° and 0.1 mm (0.05 of an interval), or with the
// views jittered over a report interval.
TEST(HandEyeReportPhases, SolveWarnsWhereTheOffsetsSigmaIsKnownLow) {
  const auto solve = [](double noise_deg, double noise_mm, double jitter) {
    HandEyeSpec spec = testing::HandEyeTestSpec(0.035, 0.2, 5001);
    spec.views = 16;
    spec.tracker_noise_deg = noise_deg;
    spec.tracker_noise = noise_mm;
    spec.view_jitter = jitter;
    const testing::HandEyeRecording r = testing::RecordHandEye(spec);
    return SolveHandEye(r.camera, r.log, r.views);
  };
  const auto warned = [](const HandEyeSolution& s) {
    for (const std::string& w : s.warnings) {
      if (w.find("its σ came out up to 20 % too small") != std::string::npos) return true;
    }
    return false;
  };
  const HandEyeSolution noisy = solve(0.05, 0.2, 0);
  EXPECT_TRUE(noisy.report_phases.LockedMidway());
  EXPECT_GT(noisy.slope_excess, 0.8);  // ~1.5 over recordings (the Monte Carlo's mean)
  EXPECT_LT(noisy.slope_excess, 3);
  EXPECT_NEAR(std::sqrt(noisy.covariance(12, 12)), 0.0015, 0.0005);  // 0.15 of the 10 ms interval
  EXPECT_TRUE(warned(noisy)) << ::testing::PrintToString(noisy.warnings);
  const HandEyeSolution quiet = solve(0.02, 0.1, 0);
  EXPECT_TRUE(quiet.report_phases.LockedMidway());
  EXPECT_FALSE(warned(quiet)) << quiet.slope_excess;
  const HandEyeSolution jittered = solve(0.05, 0.2, 0.01);
  EXPECT_FALSE(jittered.report_phases.Locked());
  EXPECT_FALSE(warned(jittered));
}

}  // namespace
}  // namespace vstcal
