// The tracker's noise estimated jointly with X, Z and δ (docs/math/handeye.md#tracker-noise):
// every report of the synthetic log carries rotation and translation noise of known σ's, the
// corners 0.2 px. The noise σ's are recovered with intervals that mostly cover them, and X's
// predicted σ's come far closer to its spread than with the tracker taken as exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "support/handeye_scenes.h"
#include "support/sanitizers.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/handeye/noise_components.h"
#include "vstcal/handeye/refine.h"

namespace vstcal {
namespace {

constexpr double kNoiseDeg = 0.05, kNoiseMm = 0.2;

testing::HandEyeRecording NoisyTracker(uint64_t seed, int views = 30) {
  HandEyeSpec spec = testing::HandEyeTestSpec(0.03, 0.2, seed);
  spec.tracker_noise_deg = kNoiseDeg;
  spec.tracker_noise = kNoiseMm;
  spec.views = views;
  return testing::RecordHandEye(spec);
}

// A log without noise: the estimated σ's are small beside the truth of the noisy case and the
// solution is the exact-tracker one's.
TEST(HandEyeTrackerNoise, AnExactTrackerIsFoundExact) {
  const testing::HandEyeRecording r = testing::RecordHandEye(0.03, 0.2, 3);
  const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  ASSERT_TRUE(s.tracker_noise);
  EXPECT_LT(s.tracker_noise->rotation.upper * 180 / M_PI, 0.3 * kNoiseDeg);
  EXPECT_LT(s.tracker_noise->translation.upper, 0.3 * kNoiseMm);
  EXPECT_NEAR(s.tracker_noise->corner_px.sigma, 0.2, 0.01);
  ASSERT_EQ(s.covariance.rows(), 15);
  ASSERT_EQ(s.names.size(), 15u);
  EXPECT_EQ(s.names[13], "tracker_noise.rotation");
  HandEyeOptions exact;
  exact.estimate_tracker_noise = false;
  const HandEyeSolution e = SolveHandEye(r.camera, r.log, r.views, exact);
  EXPECT_FALSE(e.tracker_noise);
  EXPECT_EQ(e.covariance.rows(), 13);
  EXPECT_LT((s.hmd_from_camera.t - e.hmd_from_camera.t).norm(), 0.1 * std::sqrt(e.covariance(3, 3)));
}

// Taking a noisy tracker as exact understates X's σ: the noise of each view's pose is not the
// corners' scatter that σ̂ inflates. The joint estimate's σ is larger, and it is the right one
// (the Monte Carlo test below).
TEST(HandEyeTrackerNoise, ANoisyTrackerWidensTheCovariance) {
  const testing::HandEyeRecording r = NoisyTracker(5);
  const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  HandEyeOptions exact;
  exact.estimate_tracker_noise = false;
  const HandEyeSolution e = SolveHandEye(r.camera, r.log, r.views, exact);
  ASSERT_TRUE(s.tracker_noise);
  EXPECT_GT(s.covariance(3, 3), 1.5 * e.covariance(3, 3));
  EXPECT_NEAR(s.tracker_noise->rotation.sigma * 180 / M_PI, kNoiseDeg, 0.3 * kNoiseDeg);
  EXPECT_NEAR(s.tracker_noise->translation.sigma, kNoiseMm, 0.3 * kNoiseMm);
}

// The bad-frame test weighs each view's residuals by the tracker's noise as well as the corners'
// (docs/math/handeye.md#bad-frames): clean recordings from a noisy tracker lose no view — 12 of 30
// views and one of 500 (false alarm 1 % a recording: at most one drop in all) — where the test with
// the tracker taken as exact drops views of the same recordings (the pose noise of a view is six
// numbers shared by its corners, not independent scatter).
TEST(HandEyeTrackerNoise, KeepsEveryViewOfCleanRecordingsFromANoisyTracker) {
  size_t dropped = 0;
  for (uint64_t seed = 60; seed < 72; ++seed) {
    const testing::HandEyeRecording r = NoisyTracker(seed);
    dropped += SolveHandEye(r.camera, r.log, r.views).rejected.size();
  }
  size_t dropped_exact = 0;
  for (uint64_t seed = 80; seed < 81; ++seed) {
    const testing::HandEyeRecording r = NoisyTracker(seed, 500);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    dropped += s.rejected.size();
    HandEyeOptions exact;
    exact.estimate_tracker_noise = false;
    dropped_exact += SolveHandEye(r.camera, r.log, r.views, exact).rejected.size();
  }
  ::testing::Test::RecordProperty("dropped_tracker_exact", ::testing::PrintToString(dropped_exact));
  EXPECT_LE(dropped, 1u);
  EXPECT_GE(dropped_exact, 1u);
}

// Genuinely bad frames of a noisy tracker's recording are still dropped, and only they: a board
// mislabelled by one column (its corners 30 mm off on the board), a view paired with the pose of
// another time (0.2 s later), and a view with two corners' labels swapped.
TEST(HandEyeTrackerNoise, DropsBadFramesOfANoisyTrackersRecording) {
  testing::HandEyeRecording r = NoisyTracker(7);
  for (Observation& o : r.views[5].observations) o.point.x() += 30;
  r.views[12].time += 0.2;
  std::swap(r.views[20].observations[0].pixel, r.views[20].observations[10].pixel);
  const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  std::vector<std::string> names;
  for (const Rejection& x : s.rejected) names.push_back(x.view_name);
  std::sort(names.begin(), names.end());
  std::vector<std::string> expected = {r.views[12].name, r.views[20].name, r.views[5].name};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(names, expected);
  ASSERT_TRUE(s.tracker_noise);
  EXPECT_NEAR(s.tracker_noise->rotation.sigma * 180 / M_PI, kNoiseDeg, 0.3 * kNoiseDeg);
  // The translation's σ is the less determined of the two (its own standard error is ~45 % here: the
  // board's corners see a rotation's error at the lever of their distance, a translation's only as
  // itself), so it is checked against its own 95 % interval rather than a fixed 30 %.
  EXPECT_LE(s.tracker_noise->translation.lower, kNoiseMm);
  EXPECT_GE(s.tracker_noise->translation.upper, kNoiseMm);
  EXPECT_LT(s.tracker_noise->translation.sigma_sigma, 0.5 * s.tracker_noise->translation.sigma);
  for (const Rejection& x : s.rejected) EXPECT_GT(x.rms_px, x.threshold_px) << x.view_name;
}

// Noise-free corners (what calib-synth writes without --noise) and a noisy tracker: the corners'
// variance would fall towards the linearisation's remainder (~1e-6 px²) and, before its floor, the
// scoring stopped short there — the tracker taken as exact and δ 5-15 σ from the truth on calib-synth's
// recordings. With the floor (kMinCornerVariance) the noise is estimated, the corners' σ is reported as
// the upper limit it is, and over 6 recordings (calib-synth's seeds 1-6, where seed 1 stopped short) every δ is within 3.5 of its own σ of the truth (the
// RMS of 15 such calib-synth recordings: 1.00) and the tracker's σ's within 30 % of theirs.
TEST(HandEyeTrackerNoise, NoiseFreeCornersHoldTheCornersNoiseAtItsFloor) {
  for (uint64_t seed = 1; seed < 7; ++seed) {
    HandEyeSpec spec = testing::HandEyeTestSpec(0.03, 0.0, seed);
    spec.distance = 800;  // calib-synth's demo recording, where the scoring stopped short
    spec.tracker_noise_deg = kNoiseDeg;
    spec.tracker_noise = kNoiseMm;
    const testing::HandEyeRecording r = testing::RecordHandEye(spec);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    ASSERT_TRUE(s.tracker_noise) << seed;
    EXPECT_EQ(s.tracker_noise->corner_px.sigma, std::sqrt(kMinCornerVariance)) << seed;
    EXPECT_EQ(s.tracker_noise->corner_px.lower, 0) << seed;
    ASSERT_FALSE(s.warnings.empty()) << seed;
    EXPECT_NE(s.warnings.back().find("reached its floor"), std::string::npos) << s.warnings.back();
    EXPECT_LT(std::abs(s.time_offset - 0.03), 3.5 * std::sqrt(s.covariance(12, 12))) << seed;
    EXPECT_NEAR(s.tracker_noise->rotation.sigma * 180 / M_PI, kNoiseDeg, 0.3 * kNoiseDeg) << seed;
    EXPECT_NEAR(s.tracker_noise->translation.sigma, kNoiseMm, 0.3 * kNoiseMm) << seed;
  }
}

// Over 60 recordings of 16 views: the joint estimate's RMS of (estimate − truth)/σ_predicted over X's
// six tangent components is below 2 and at least three times closer to 1 than the exact-tracker
// solve's (measured over these 60: 1.07 against 7.57; 1.5 over 200 before w followed δ in the cost
// and the covariance was the sandwich); the noise σ's average within 10 % of the truth and their 95 % intervals cover
// it in at least 75 % of the recordings (measured 93 % and 77 %). δ: DeltaSigmaMatchesItsSpread… .
TEST(HandEyeTrackerNoise, PredictedSigmasApproachTheSpreadAndTheNoiseIsRecovered) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  constexpr int kRuns = 60;
  double zx = 0, zx_exact = 0, zz = 0, zd = 0, mean_r = 0, mean_t = 0;
  int covered_r = 0, covered_t = 0;
  const double truth_r = kNoiseDeg * M_PI / 180;
  HandEyeOptions exact;
  exact.estimate_tracker_noise = false;
  for (int run = 0; run < kRuns; ++run) {
    const testing::HandEyeRecording r = NoisyTracker(1000 + static_cast<uint64_t>(run), 16);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    const HandEyeSolution e = SolveHandEye(r.camera, r.log, r.views, exact);
    ASSERT_TRUE(s.tracker_noise) << run;
    const Eigen::Matrix<double, 6, 1> ex = LeftPerturbationBetween(s.hmd_from_camera, testing::kHmdFromCamera);
    const Eigen::Matrix<double, 6, 1> ee = LeftPerturbationBetween(e.hmd_from_camera, testing::kHmdFromCamera);
    const Eigen::Matrix<double, 6, 1> ez = LeftPerturbationBetween(s.tracker_from_board, testing::kTrackerFromBoard);
    for (int i = 0; i < 6; ++i) {
      zx += ex[i] * ex[i] / s.covariance(i, i) / (6 * kRuns);
      zx_exact += ee[i] * ee[i] / e.covariance(i, i) / (6 * kRuns);
      zz += ez[i] * ez[i] / s.covariance(6 + i, 6 + i) / (6 * kRuns);
    }
    zd += (s.time_offset - 0.03) * (s.time_offset - 0.03) / s.covariance(12, 12) / kRuns;
    const JointTrackerNoise& n = *s.tracker_noise;
    mean_r += n.rotation.sigma / truth_r / kRuns;
    mean_t += n.translation.sigma / kNoiseMm / kRuns;
    covered_r += n.rotation.lower <= truth_r && truth_r <= n.rotation.upper;
    covered_t += n.translation.lower <= kNoiseMm && kNoiseMm <= n.translation.upper;
  }
  ::testing::Test::RecordProperty("x_rms_z", ::testing::PrintToString(std::sqrt(zx)));
  ::testing::Test::RecordProperty("x_rms_z_tracker_exact", ::testing::PrintToString(std::sqrt(zx_exact)));
  ::testing::Test::RecordProperty("z_rms_z", ::testing::PrintToString(std::sqrt(zz)));
  ::testing::Test::RecordProperty("delta_rms_z", ::testing::PrintToString(std::sqrt(zd)));
  ::testing::Test::RecordProperty("rotation_mean_over_truth", ::testing::PrintToString(mean_r));
  ::testing::Test::RecordProperty("translation_mean_over_truth", ::testing::PrintToString(mean_t));
  ::testing::Test::RecordProperty("covered", ::testing::PrintToString(std::vector<int>{covered_r, covered_t}));
  EXPECT_LT(std::sqrt(zx), 2.0);
  EXPECT_LT(std::abs(std::sqrt(zx) - 1), (std::sqrt(zx_exact) - 1) / 3);
  EXPECT_GE(covered_r, 45);
  EXPECT_GE(covered_t, 45);
  EXPECT_NEAR(mean_r, 1.0, 0.1);
  EXPECT_NEAR(mean_t, 1.0, 0.1);
}

// δ's estimate and σ over recordings of 16 views from a noisy tracker (0.05°, 0.2 mm a report),
// the views all at one fraction s of the tracker's report interval.
struct DeltaSpread {
  double mean_error = 0;   // mean δ̂ − δ, s
  double spread = 0;       // standard deviation of δ̂, s
  double mean_sigma = 0;   // mean of the predicted σ_δ, s
  double ratio_se = 0;     // standard error of spread/mean_sigma (relative)
  double rms_z = 0;
};

DeltaSpread DeltaMonteCarlo(double delta, int runs, uint64_t first_seed) {
  std::vector<double> error, sigma;
  for (int run = 0; run < runs; ++run) {
    HandEyeSpec spec = testing::HandEyeTestSpec(delta, 0.2, first_seed + static_cast<uint64_t>(run));
    spec.tracker_noise_deg = kNoiseDeg;
    spec.tracker_noise = kNoiseMm;
    spec.views = 16;
    const testing::HandEyeRecording r = testing::RecordHandEye(spec);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    EXPECT_TRUE(s.tracker_noise) << run;
    error.push_back(s.time_offset - delta);
    sigma.push_back(std::sqrt(s.covariance(12, 12)));
  }
  const double n = runs;
  DeltaSpread d;
  double m2 = 0, m4 = 0, sigma_var = 0;
  for (double e : error) d.mean_error += e / n;
  for (double x : sigma) d.mean_sigma += x / n;
  for (int k = 0; k < runs; ++k) {
    const double e = error[k] - d.mean_error;
    m2 += e * e / n;
    m4 += e * e * e * e / n;
    sigma_var += (sigma[k] - d.mean_sigma) * (sigma[k] - d.mean_sigma) / (n - 1);
    d.rms_z += error[k] * error[k] / (sigma[k] * sigma[k]) / n;
  }
  d.spread = std::sqrt(m2 * n / (n - 1));
  d.rms_z = std::sqrt(d.rms_z);
  // The sample standard deviation's relative standard error is √((κ − 1)/(4n)), κ the kurtosis (δ̂
  // is not Gaussian: the profile likelihood has cusps at the reports); the mean predicted σ's is
  // its spread over √n. Independent recordings: they add in quadrature.
  const double kurtosis = m4 / (m2 * m2);
  d.ratio_se = std::sqrt((kurtosis - 1) / (4 * n) + sigma_var / n / (d.mean_sigma * d.mean_sigma));
  return d;
}

// docs/math/handeye.md#delta-likelihood: with the weight w(s(δ)) of each view's pose error
// recomputed from δ inside the cost, δ̂ is unbiased wherever the views fall between the tracker's
// reports (s = 0, ¼, ½: δ = 30, 32.5, 35 ms), and the sandwich covariance predicts its spread. With
// w held fixed during the solve (before), views on a report were pulled towards s = ½: a spread
// 1.8× the sandwich's σ at s = 0 and a bias of 0.97 ms (5.5 standard errors) at s = ¼ over these
// seeds. Each spread must be within 10 % of the mean predicted σ — or within three standard errors
// of this Monte Carlo when that is wider (δ̂ is not Gaussian: with every view on a report a fifth of
// the recordings put it exactly there, at the profile likelihood's cusp) — and the mean within three
// standard errors of the truth. 100 recordings each; over 400 the spreads
// are 0.92, 1.02 and 1.15 of the predicted σ (the math page's table: not within 10 % midway).
TEST(HandEyeTrackerNoise, DeltaSigmaMatchesItsSpreadOnAndBetweenReports) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  constexpr int kRuns = 100;
  for (const double delta : {0.030, 0.0325, 0.035}) {
    const DeltaSpread d = DeltaMonteCarlo(delta, kRuns, 3000);
    const double ratio = d.spread / d.mean_sigma;
    const std::string at = std::string("delta_").append(std::to_string(static_cast<int>(std::lround(delta * 1e4))));
    ::testing::Test::RecordProperty(at + "_spread_ms", ::testing::PrintToString(d.spread * 1e3));
    ::testing::Test::RecordProperty(at + "_mean_sigma_ms", ::testing::PrintToString(d.mean_sigma * 1e3));
    ::testing::Test::RecordProperty(at + "_mean_error_ms", ::testing::PrintToString(d.mean_error * 1e3));
    ::testing::Test::RecordProperty(at + "_ratio_se", ::testing::PrintToString(d.ratio_se));
    ::testing::Test::RecordProperty(at + "_rms_z", ::testing::PrintToString(d.rms_z));
    EXPECT_LT(std::abs(ratio - 1), std::max(0.1, 3 * d.ratio_se)) << "δ = " << delta << ": spread " << d.spread << " s, predicted " << d.mean_sigma;
    EXPECT_LT(std::abs(d.mean_error), 3 * d.spread / std::sqrt(kRuns)) << "δ = " << delta;
  }
}

}  // namespace
}  // namespace vstcal
