// The parametric bootstrap's σ_δ (docs/math/handeye.md#delta-bootstrap) against the spread of δ̂
// over recordings, where the first-order sandwich is farthest off: every view midway between two
// tracker reports (s = ½).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "support/handeye_scenes.h"
#include "support/sanitizers.h"
#include "vstcal/handeye/bootstrap.h"
#include "vstcal/handeye/refine.h"

namespace vstcal {
namespace {

// Recordings small enough that many fit in the test's budget: BOOTSTRAP_VIEWS views of a
// BOOTSTRAP_COLS × BOOTSTRAP_ROWS board, the tracker's every report with 0.05° and 0.2 mm per axis,
// 0.2 px on the corners, δ = 35 ms (the views at 0.5 + k·0.6 s + δ, midway between 100 Hz reports).
constexpr int kBootstrapViews = 16, kBootstrapCols = 9, kBootstrapRows = 6;
constexpr double kBootstrapDelta = 0.035;

struct BootstrapSpread {
  double spread = 0;         // standard deviation of δ̂ over the recordings, s
  double bootstrap_rms = 0;  // √(mean over recordings of the bootstrap's σ_δ²), s
  double first_order_rms = 0;
  double ratio_se = 0;       // relative standard error of spread / bootstrap_rms
};

BootstrapSpread BootstrapMonteCarlo(int runs, int replicates, uint64_t first_seed) {
  std::vector<double> error, boot, first;
  for (int run = 0; run < runs; ++run) {
    HandEyeSpec spec = testing::HandEyeTestSpec(kBootstrapDelta, 0.2, first_seed + static_cast<uint64_t>(run));
    spec.tracker_noise_deg = 0.05;
    spec.tracker_noise = 0.2;
    spec.views = kBootstrapViews;
    spec.grid_cols = kBootstrapCols;
    spec.grid_rows = kBootstrapRows;
    const testing::HandEyeRecording r = testing::RecordHandEye(spec);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    const HandEyeBootstrap b = BootstrapHandEye(r.camera, r.log, r.views, s, {}, {replicates, 500 + static_cast<uint64_t>(run), 1});
    EXPECT_EQ(b.solved, replicates) << run;
    error.push_back(s.time_offset - kBootstrapDelta);
    boot.push_back(b.covariance(12, 12));
    first.push_back(s.covariance(12, 12));
  }
  const double n = runs;
  double mean_error = 0, e2 = 0, b2 = 0, f2 = 0;
  for (int k = 0; k < runs; ++k) {
    mean_error += error[k] / n;
    b2 += boot[k] / n;
    f2 += first[k] / n;
  }
  for (double e : error) e2 += (e - mean_error) * (e - mean_error) / n;
  // spread / bootstrap_rms = √(mean e² / mean σ_b²): by the delta method Var log(ratio) =
  // ¼ Var(e²/E e² − σ_b²/E σ_b²)/n, a recording's e² and σ_b² correlated or not.
  double log_var = 0;
  for (int k = 0; k < runs; ++k) {
    const double e = error[k] - mean_error, u = e * e / e2 - boot[k] / b2;
    log_var += u * u / (n - 1);
  }
  BootstrapSpread d;
  d.spread = std::sqrt(e2 * n / (n - 1));
  d.bootstrap_rms = std::sqrt(b2);
  d.first_order_rms = std::sqrt(f2);
  d.ratio_se = 0.5 * std::sqrt(log_var / n);
  return d;
}

// docs/math/handeye.md#delta-bootstrap: midway between reports the cost's own δ̂ (stop 39's) had a
// sandwich σ_δ ~15 % below its spread (16 views), the bootstrap's within 10 %; the instrumented δ̂
// (docs/math/handeye.md#delta-instrumented) is 1.8 × tighter and both its σ's are within ~10 %. The bootstrap's sample variance is
// unbiased for its world's variance at any B ≥ 2, so few replicates per recording and many
// recordings test its mean best for a given number of solves (B sets only each recording's noise,
// 2/(B − 1) of the variance, which the RMS over recordings averages out). The ratio's standard
// error, Var log(ratio) ≈ [(κ − 1)/4 + (2/(B − 1) + CV²)/4]/n (κ ≈ 3 δ̂'s kurtosis, CV ≈ 0.25 the
// bootstrap's σ² over recordings), is ≈ 0.08 at n = 100, B = 4 (0.107 measured with the
// instrumented δ, whose kurtosis is higher; so n = 150, 750 solves, ~16 s of one core at 21 ms a
// solve): ±10 % is 1.2 of it, too tight to assert. So the bound is the larger of 10 % and
// three measured standard errors (~0.25), and the standard error itself must stay below 0.1 — a
// check that the bootstrap is not grossly off (the raw reports as its motion gave 2×), not yet the
// ±10 % claim, which needs ~6× the recordings (mc_handeye_bootstrap).
TEST(HandEyeBootstrap, DeltaSigmaMatchesTheSpreadMidwayBetweenReports) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  constexpr int kRuns = 150, kReplicates = 4;
  const BootstrapSpread d = BootstrapMonteCarlo(kRuns, kReplicates, 3000);
  const double ratio = d.spread / d.bootstrap_rms;
  ::testing::Test::RecordProperty("spread_ms", ::testing::PrintToString(d.spread * 1e3));
  ::testing::Test::RecordProperty("bootstrap_rms_ms", ::testing::PrintToString(d.bootstrap_rms * 1e3));
  ::testing::Test::RecordProperty("first_order_rms_ms", ::testing::PrintToString(d.first_order_rms * 1e3));
  ::testing::Test::RecordProperty("ratio", ::testing::PrintToString(ratio));
  ::testing::Test::RecordProperty("ratio_se", ::testing::PrintToString(ratio * d.ratio_se));
  EXPECT_LT(d.ratio_se, 0.1);
  EXPECT_LT(std::abs(ratio - 1), std::max(0.1, 3 * d.ratio_se)) << "spread " << d.spread << " s, bootstrap " << d.bootstrap_rms << " s, SE "
                                                                 << d.ratio_se;
}

}  // namespace
}  // namespace vstcal
