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
#include "vstcal/handeye/refine.h"

namespace vstcal {
namespace {

constexpr double kNoiseDeg = 0.05, kNoiseMm = 0.2;

// The truth's left-perturbation tangent from the estimate: truth = (Exp(ω), ρ) · estimate.
Eigen::Matrix<double, 6, 1> ErrorTangent(const Rigid3d& estimate, const Rigid3d& truth) {
  const Eigen::Vector3d w = RotvecFromRotation(truth.R * estimate.R.transpose());
  Eigen::Matrix<double, 6, 1> e;
  e << w, truth.t - RotationFromRotvec(w) * estimate.t;
  return e;
}

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
  EXPECT_NEAR(s.tracker_noise->translation.sigma, kNoiseMm, 0.3 * kNoiseMm);
  for (const Rejection& x : s.rejected) EXPECT_GT(x.rms_px, x.threshold_px) << x.view_name;
}

// Over 60 recordings of 16 views: the joint estimate's RMS of (estimate − truth)/σ_predicted over X's
// six tangent components is below 2 and at least three times closer to 1 than the exact-tracker
// solve's (measured: 1.5 against 7.5 over 200); the noise σ's average within 10 % of the truth and
// their 95 % intervals cover it in at least 75 % of the recordings (measured 88 % and 83 %). Not yet
// within 10 % of 1, and δ's σ is understated (RMS 5): docs/math/handeye.md#tracker-noise says why.
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
    const Eigen::Matrix<double, 6, 1> ex = ErrorTangent(s.hmd_from_camera, testing::kHmdFromCamera);
    const Eigen::Matrix<double, 6, 1> ee = ErrorTangent(e.hmd_from_camera, testing::kHmdFromCamera);
    const Eigen::Matrix<double, 6, 1> ez = ErrorTangent(s.tracker_from_board, testing::kTrackerFromBoard);
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

// The cause of δ's understated σ (docs/math/handeye.md#tracker-noise, "Not yet within 10 %"): the
// recordings above put every view on a tracker report (s = 0), where least squares on the
// interpolated noisy poses pulls δ towards s = ½ (the interpolated error's variance w(s) is lowest
// there, and the fit holds w fixed). With the views midway between reports (δ = 35 ms: s = ½, no
// pull) the same solve's predicted σ of δ matches its spread: over 60 recordings RMS z 1.14
// (against 5.2 at s = 0 and 3.5 at s = ¼), X's translation 1.17. The bound allows the sampling
// error of an RMS over 60 (≈ 9 %).
TEST(HandEyeTrackerNoise, DeltaSigmaHoldsWithViewsMidwayBetweenReports) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  constexpr int kRuns = 60;
  constexpr double kDelta = 0.035;
  double zd = 0;
  for (int run = 0; run < kRuns; ++run) {
    HandEyeSpec spec = testing::HandEyeTestSpec(kDelta, 0.2, 1000 + static_cast<uint64_t>(run));
    spec.tracker_noise_deg = kNoiseDeg;
    spec.tracker_noise = kNoiseMm;
    spec.views = 16;
    const testing::HandEyeRecording r = testing::RecordHandEye(spec);
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    ASSERT_TRUE(s.tracker_noise) << run;
    zd += (s.time_offset - kDelta) * (s.time_offset - kDelta) / s.covariance(12, 12) / kRuns;
  }
  ::testing::Test::RecordProperty("delta_rms_z", ::testing::PrintToString(std::sqrt(zd)));
  EXPECT_GT(std::sqrt(zd), 0.75);
  EXPECT_LT(std::sqrt(zd), 1.3);
}

}  // namespace
}  // namespace vstcal
