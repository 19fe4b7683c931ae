// Hand-eye calibration of a stereo rig on the headset (docs/math/handeye.md#rig): the right
// camera's corners projected through right_from_left (held) join the left camera's in the one
// maximum-likelihood solve of X = hmd_from_camera (left), Z and δ. Exact on noise-free views; under
// noise its X within its covariance of the truth, and its σ's smaller than the left camera's alone.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "support/handeye_scenes.h"
#include "support/sanitizers.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/handeye/refine.h"

namespace vstcal {
namespace {

using testing::kHmdFromCamera;
using testing::kTrackerFromBoard;

// Ten views, 1 s apart, at times whose tracker time (t + δ) falls on a 100 Hz report: no
// interpolation error, so noise-free views give X, Z and δ to the solver's tolerance.
TEST(HandEyeRig, ExactOnNoiseFreeViews) {
  const testing::HandEyeRigRecording r = testing::RecordHandEyeRig(0.03, 0, 1, 10);
  ASSERT_EQ(r.rig.views.size(), 10u);
  const HandEyeSolution s = SolveHandEye(r.left.camera, r.left.log, r.left.views, {}, &r.rig);
  EXPECT_EQ(s.views, 20u);
  EXPECT_EQ(s.right_views, 10u);
  size_t right_corners = 0;
  for (const TimedView& v : r.rig.views) right_corners += v.observations.size();
  EXPECT_EQ(s.right_corners, right_corners);
  ASSERT_TRUE(s.right_from_left);
  EXPECT_TRUE(s.rejected.empty());
  const Eigen::Matrix<double, 6, 1> ex = LeftPerturbationBetween(s.hmd_from_camera, kHmdFromCamera);
  EXPECT_LT(ex.head<3>().norm(), 1e-8) << ex.transpose();
  EXPECT_LT(ex.tail<3>().norm(), 1e-6) << ex.transpose();
  EXPECT_LT((s.tracker_from_board.t - kTrackerFromBoard.t).norm(), 1e-6);
  EXPECT_NEAR(s.time_offset, 0.03, 1e-9);
  EXPECT_LT(s.rms_px, 1e-7);
}

// A right camera that is not where the rig says cannot be fitted: its corners then disagree with
// the left camera's by its error, which the residuals show.
TEST(HandEyeRig, AWrongRigShowsInTheResiduals) {
  testing::HandEyeRigRecording r = testing::RecordHandEyeRig(0.03, 0, 2, 10);
  r.rig.right_from_left.t.x() += 5;  // 5 mm of baseline wrong
  HandEyeOptions keep;
  keep.rejection.enabled = false;
  const HandEyeSolution s = SolveHandEye(r.left.camera, r.left.log, r.left.views, keep, &r.rig);
  EXPECT_GT(s.rms_px, 0.5);
}

// 0.2 px on every corner of both cameras, over 15 recordings: the Mahalanobis distance of X's
// error (6 dof) by the solve's own covariance sums to χ²₉₀ (its 0.5 % and 99.5 % points are 59
// and 128), and every recording's σ's of X are smaller with the rig than with the left camera alone.
TEST(HandEyeRig, WithinItsCovarianceAndTighterThanTheLeftCameraAlone) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  double chi2 = 0;
  double ratio_sum = 0;
  constexpr int kRuns = 15;
  for (int run = 0; run < kRuns; ++run) {
    const testing::HandEyeRigRecording r = testing::RecordHandEyeRig(0.03, 0.2, 100 + static_cast<uint64_t>(run));
    const HandEyeSolution rig = SolveHandEye(r.left.camera, r.left.log, r.left.views, {}, &r.rig);
    const HandEyeSolution left = SolveHandEye(r.left.camera, r.left.log, r.left.views);
    ASSERT_EQ(rig.covariance.rows(), 15);
    const Eigen::Matrix<double, 6, 1> e = LeftPerturbationBetween(rig.hmd_from_camera, kHmdFromCamera);
    const Eigen::Matrix<double, 6, 6> cov = rig.covariance.topLeftCorner<6, 6>();
    chi2 += e.dot(cov.ldlt().solve(e));
    for (int i = 0; i < 6; ++i) {
      EXPECT_LT(rig.covariance(i, i), left.covariance(i, i)) << run << " " << i;
      ratio_sum += std::sqrt(rig.covariance(i, i) / left.covariance(i, i)) / (6 * kRuns);
    }
    EXPECT_LT(std::sqrt(rig.covariance(12, 12)), std::sqrt(left.covariance(12, 12))) << run;
  }
  ::testing::Test::RecordProperty("chi2_90", ::testing::PrintToString(chi2));
  ::testing::Test::RecordProperty("sigma_rig_over_left", ::testing::PrintToString(ratio_sum));
  EXPECT_GT(chi2, 59);
  EXPECT_LT(chi2, 128);
}

}  // namespace
}  // namespace vstcal
