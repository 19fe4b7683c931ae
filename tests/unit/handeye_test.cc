// The closed-form hand-eye start (issue 22, docs/math/handeye.md) against OpenCV's
// calibrateHandEye (all five methods) and calibrateRobotWorldHandEye (Shah, Li) on the same
// samples in the same test: exact on noise-free samples, as accurate as the best of them under
// noise, and refusing motion about one axis with the motion to add.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/handeye/closed_form.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/tracker_noise.h"
#include "support/handeye_scenes.h"
#include "support/sanitizers.h"

namespace vstcal {
namespace {

using testing::kHmdFromCamera;
using testing::kTrackerFromBoard;

double AngleDeg(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return RotvecFromRotation(a * b.transpose()).norm() * 180 / M_PI; }

// n samples of a headset turned about varied axes (up to ±`max_deg` about each) and moved about a
// metre from the board; noise: the tracker's and the board pose's rotation (deg) and translation (mm).
std::vector<HandEyeSample> Samples(int n, uint64_t seed, double noise_deg = 0, double noise_mm = 0, bool one_axis = false,
                                   double max_deg = 30) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g(0, 1);
  const auto noise = [&](double deg, double mm) {
    return Rigid3d::FromRotvec(Eigen::Vector3d(g(rng), g(rng), g(rng)) * deg * M_PI / 180, Eigen::Vector3d(g(rng), g(rng), g(rng)) * mm);
  };
  std::vector<HandEyeSample> out;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d turn = one_axis ? Eigen::Vector3d(0, 0, u(rng)) : Eigen::Vector3d(u(rng), u(rng), u(rng));
    // The headset looks at the board from about 1 m: tracker_from_hmd = Z · board_from_hmd.
    const Rigid3d board_from_hmd = Rigid3d::FromRotvec(turn * max_deg * M_PI / 180, Eigen::Vector3d(200 * u(rng), 200 * u(rng), -1000 + 100 * u(rng)));
    HandEyeSample s;
    s.tracker_from_hmd = kTrackerFromBoard * board_from_hmd;
    s.camera_from_board = (s.tracker_from_hmd * kHmdFromCamera).inverse() * kTrackerFromBoard;
    if (noise_deg > 0 || noise_mm > 0) {
      s.tracker_from_hmd = noise(noise_deg, noise_mm) * s.tracker_from_hmd;
      s.camera_from_board = noise(noise_deg, noise_mm) * s.camera_from_board;
    }
    out.push_back(s);
  }
  return out;
}

struct OpenCvInputs {
  std::vector<cv::Mat> R_gripper2base, t_gripper2base, R_target2cam, t_target2cam, R_base2gripper, t_base2gripper;
};

// OpenCV's names: gripper = the HMD, base = the tracker, target = the board, world = the board.
OpenCvInputs ToOpenCv(const std::vector<HandEyeSample>& samples) {
  OpenCvInputs in;
  const auto add = [](std::vector<cv::Mat>* Rs, std::vector<cv::Mat>* ts, const Rigid3d& p) {
    cv::Mat R, t;
    cv::eigen2cv(p.R, R);
    cv::eigen2cv(p.t, t);
    Rs->push_back(R);
    ts->push_back(t);
  };
  for (const HandEyeSample& s : samples) {
    add(&in.R_gripper2base, &in.t_gripper2base, s.tracker_from_hmd);
    add(&in.R_target2cam, &in.t_target2cam, s.camera_from_board);
    add(&in.R_base2gripper, &in.t_base2gripper, s.tracker_from_hmd.inverse());
  }
  return in;
}

Rigid3d FromCv(const cv::Mat& R, const cv::Mat& t) {
  Rigid3d p;
  cv::cv2eigen(R, p.R);
  cv::cv2eigen(t, p.t);
  return p;
}

TEST(HandEyeClosedForm, ExactOnNoiseFreeSamplesLikeOpenCv) {
  const std::vector<HandEyeSample> samples = Samples(12, 1);
  const HandEyeStart start = SolveHandEyeClosedForm(samples);
  EXPECT_LT(AngleDeg(start.hmd_from_camera.R, kHmdFromCamera.R), 1e-9);
  EXPECT_LT((start.hmd_from_camera.t - kHmdFromCamera.t).norm(), 1e-8);
  EXPECT_LT(AngleDeg(start.tracker_from_board.R, kTrackerFromBoard.R), 1e-9);
  EXPECT_LT((start.tracker_from_board.t - kTrackerFromBoard.t).norm(), 1e-8);
  const OpenCvInputs in = ToOpenCv(samples);
  for (cv::HandEyeCalibrationMethod method : {cv::CALIB_HAND_EYE_TSAI, cv::CALIB_HAND_EYE_PARK, cv::CALIB_HAND_EYE_HORAUD,
                                              cv::CALIB_HAND_EYE_ANDREFF, cv::CALIB_HAND_EYE_DANIILIDIS}) {
    cv::Mat R, t;
    cv::calibrateHandEye(in.R_gripper2base, in.t_gripper2base, in.R_target2cam, in.t_target2cam, R, t, method);
    const Rigid3d x = FromCv(R, t);
    EXPECT_LT(AngleDeg(x.R, start.hmd_from_camera.R), 1e-5) << method;
    EXPECT_LT((x.t - start.hmd_from_camera.t).norm(), 1e-3) << method;
  }
  cv::Mat R_base2world, t_base2world, R_gripper2cam, t_gripper2cam;
  cv::calibrateRobotWorldHandEye(in.R_target2cam, in.t_target2cam, in.R_base2gripper, in.t_base2gripper, R_base2world, t_base2world,
                                 R_gripper2cam, t_gripper2cam, cv::CALIB_ROBOT_WORLD_HAND_EYE_SHAH);
  const Rigid3d board_from_tracker = FromCv(R_base2world, t_base2world), camera_from_hmd = FromCv(R_gripper2cam, t_gripper2cam);
  EXPECT_LT(AngleDeg(camera_from_hmd.R, start.hmd_from_camera.inverse().R), 1e-5);
  EXPECT_LT((board_from_tracker.inverse().t - start.tracker_from_board.t).norm(), 1e-3);
}

// Under noise (0.1° and 0.5 mm on every tracker and board pose), over 20 seeds: the closed form's
// median errors are within 1.5× of the best OpenCV method's (it is the start of the maximum-
// likelihood refinement, not its end).
TEST(HandEyeClosedForm, AsAccurateAsOpenCvUnderNoise) {
  std::vector<double> ours_deg, ours_mm, best_deg, best_mm;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<HandEyeSample> samples = Samples(30, 100 + seed, 0.1, 0.5);
    const HandEyeStart start = SolveHandEyeClosedForm(samples);
    ours_deg.push_back(AngleDeg(start.hmd_from_camera.R, kHmdFromCamera.R));
    ours_mm.push_back((start.hmd_from_camera.t - kHmdFromCamera.t).norm());
    const OpenCvInputs in = ToOpenCv(samples);
    double bd = 1e9, bm = 1e9;
    for (cv::HandEyeCalibrationMethod method : {cv::CALIB_HAND_EYE_TSAI, cv::CALIB_HAND_EYE_PARK, cv::CALIB_HAND_EYE_HORAUD,
                                                cv::CALIB_HAND_EYE_ANDREFF, cv::CALIB_HAND_EYE_DANIILIDIS}) {
      cv::Mat R, t;
      cv::calibrateHandEye(in.R_gripper2base, in.t_gripper2base, in.R_target2cam, in.t_target2cam, R, t, method);
      const Rigid3d x = FromCv(R, t);
      bd = std::min(bd, AngleDeg(x.R, kHmdFromCamera.R));
      bm = std::min(bm, (x.t - kHmdFromCamera.t).norm());
    }
    best_deg.push_back(bd);
    best_mm.push_back(bm);
  }
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  ::testing::Test::RecordProperty("ours_deg", ::testing::PrintToString(median(ours_deg)));
  ::testing::Test::RecordProperty("best_opencv_deg", ::testing::PrintToString(median(best_deg)));
  ::testing::Test::RecordProperty("ours_mm", ::testing::PrintToString(median(ours_mm)));
  ::testing::Test::RecordProperty("best_opencv_mm", ::testing::PrintToString(median(best_mm)));
  EXPECT_LT(median(ours_deg), 1.5 * median(best_deg));
  EXPECT_LT(median(ours_mm), 1.5 * median(best_mm));
}

TEST(HandEyeClosedForm, RefusesMotionAboutOneAxisAndTooFewPoses) {
  try {
    SolveHandEyeClosedForm(Samples(10, 3, 0, 0, /*one_axis=*/true));
    ADD_FAILURE() << "no error";
  } catch (const DegenerateError& e) {
    EXPECT_NE(std::string(e.what()).find("turned about one axis only"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("tilt or roll it as well as turning it"), std::string::npos) << e.what();
  }
  EXPECT_THROW(SolveHandEyeClosedForm(Samples(2, 4)), DegenerateError);
}

}  // namespace
}  // namespace vstcal

namespace vstcal {
namespace {

using testing::HandEyeRecording;
HandEyeRecording Record(double delta, double noise_px, uint64_t seed) { return testing::RecordHandEye(delta, noise_px, seed); }

TEST(HandEyeRefinement, RecoversTheTimeOffsetAndBothPosesWithoutNoise) {
  const HandEyeRecording r = Record(0.03, 0, 1);
  const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  EXPECT_NEAR(s.start_time_offset, 0.03, 0.0051);  // the coarse search's step
  EXPECT_NEAR(s.time_offset, 0.03, 2e-4);
  EXPECT_LT(AngleDeg(s.hmd_from_camera.R, kHmdFromCamera.R), 2e-3);
  EXPECT_LT((s.hmd_from_camera.t - kHmdFromCamera.t).norm(), 0.05);
  EXPECT_LT((s.tracker_from_board.t - kTrackerFromBoard.t).norm(), 0.05);
  EXPECT_LT(s.rms_px, 0.01);  // what remains is the geodesic interpolation between 100 Hz reports
}

// With 0.2 px of corner noise: each estimate within 3.5σ of the truth by its own covariance, and —
// over 80 recordings — the spread of δ and of X's translation within 25 % of the predicted σ (the
// standard error of an empirical σ from 80 draws is 8 %; 150 recordings gave 1.02 and 0.94).
TEST(HandEyeRefinement, PredictedSigmasMatchTheSpread) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  std::vector<double> deltas, xs;
  double predicted_delta = 0, predicted_x = 0;
  constexpr int kRuns = 80;
  for (int run = 0; run < kRuns; ++run) {
    const HandEyeRecording r = Record(0.03, 0.2, 10 + static_cast<uint64_t>(run));
    const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
    ASSERT_EQ(s.covariance.rows(), 15);  // X, Z, δ and the tracker noise σ's
    // X's translation moves with the left perturbation as dt = −[t]× ω + ρ.
    Eigen::Matrix<double, 3, 6> dt_d_tangent;
    dt_d_tangent << -Hat(s.hmd_from_camera.t), Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d cov_t = dt_d_tangent * s.covariance.topLeftCorner<6, 6>() * dt_d_tangent.transpose();
    const double sd = std::sqrt(s.covariance(12, 12)), sx = std::sqrt(cov_t(0, 0));
    EXPECT_LT(std::abs(s.time_offset - 0.03), 3.5 * sd) << run;
    deltas.push_back(s.time_offset);
    xs.push_back(s.hmd_from_camera.t.x());
    predicted_delta += sd / kRuns;
    predicted_x += sx / kRuns;
    EXPECT_NEAR(s.sigma_px, 0.2, 0.02);
  }
  const auto sd = [](const std::vector<double>& v) {
    double m = 0, ss = 0;
    for (double x : v) m += x / static_cast<double>(v.size());
    for (double x : v) ss += (x - m) * (x - m);
    return std::sqrt(ss / static_cast<double>(v.size() - 1));
  };
  ::testing::Test::RecordProperty("delta_empirical_over_predicted", ::testing::PrintToString(sd(deltas) / predicted_delta));
  ::testing::Test::RecordProperty("x_empirical_over_predicted", ::testing::PrintToString(sd(xs) / predicted_x));
  EXPECT_NEAR(sd(deltas) / predicted_delta, 1.0, 0.25);
  EXPECT_NEAR(sd(xs) / predicted_x, 1.0, 0.25);
}

// Two bad frames among 30: one whose corners are 3 px off (a smeared or mislabelled board), one
// whose tracker reports around its time jumped 8 mm (a tracker glitch). Both are dropped, nothing
// else is, and the solution is then within its own covariance of the truth — which, with both
// kept, it is not.
TEST(HandEyeRefinement, DropsBadFramesAndStaysWithinItsCovariance) {
  HandEyeRecording r = Record(0.03, 0.2, 7);
  for (Observation& o : r.views[5].observations) o.pixel.x() += 3;
  const double glitch_time = r.views[12].time + 0.03;
  for (TrackedPose& p : r.log) {
    if (std::abs(p.time - glitch_time) < 0.025) p.tracker_from_hmd.t += Eigen::Vector3d(8, 0, 0);
  }
  const auto x_error_in_sigmas = [](const HandEyeSolution& s) {
    Eigen::Matrix<double, 3, 6> dt_d_tangent;
    dt_d_tangent << -Hat(s.hmd_from_camera.t), Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d cov_t = dt_d_tangent * s.covariance.topLeftCorner<6, 6>() * dt_d_tangent.transpose();
    const Eigen::Vector3d e = s.hmd_from_camera.t - kHmdFromCamera.t;
    return std::sqrt(e.dot(cov_t.ldlt().solve(e)));  // Mahalanobis distance, 3 dof
  };
  const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
  ASSERT_EQ(s.rejected.size(), 2u);
  std::vector<std::string> names = {s.rejected[0].view_name, s.rejected[1].view_name};
  std::sort(names.begin(), names.end());
  std::vector<std::string> expected = {r.views[5].name, r.views[12].name};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(names, expected);
  EXPECT_EQ(s.views, 28u);
  EXPECT_NEAR(s.sigma_px, 0.2, 0.03);
  EXPECT_LT(x_error_in_sigmas(s), 3.0);  // χ²₃'s 99 % point is 3.37²
  EXPECT_LT(std::abs(s.time_offset - 0.03), 3 * std::sqrt(s.covariance(12, 12)));

  HandEyeOptions keep_all;
  keep_all.rejection.enabled = false;
  const HandEyeSolution kept = SolveHandEye(r.camera, r.log, r.views, keep_all);
  EXPECT_TRUE(kept.rejected.empty());
  EXPECT_GT(kept.sigma_px, 2 * s.sigma_px);  // the bad frames dominate the fit
}

// Clean recordings lose no view: over 20 recordings with 0.2 px of corner noise, at most one view
// is dropped in all (the test's false-alarm rate is 1 % per calibration).
TEST(HandEyeRefinement, KeepsEveryViewOfCleanRecordings) {
  size_t dropped = 0;
  for (uint64_t seed = 40; seed < 60; ++seed) {
    const HandEyeRecording r = Record(0.03, 0.2, seed);
    dropped += SolveHandEye(r.camera, r.log, r.views).rejected.size();
  }
  EXPECT_LE(dropped, 1u);
}

TEST(HandEyeRefinement, RefusesAViewOutsideTheLogAndAnUnsortedLog) {
  HandEyeRecording r = Record(0.0, 0, 2);
  r.views.back().time = 20;
  EXPECT_THROW(SolveHandEye(r.camera, r.log, r.views), InputError);
  r = Record(0.0, 0, 2);
  std::swap(r.log[5], r.log[6]);
  EXPECT_THROW(SolveHandEye(r.camera, r.log, r.views), InputError);
}

}  // namespace
}  // namespace vstcal

namespace vstcal {
namespace {

// A held headset: 2,000 reports of one pose with isotropic jitter (0.05° per axis, 0.2 mm per
// axis), then it moves.
std::vector<TrackedPose> StaticLog(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0, 1);
  const Rigid3d held = Rigid3d::FromRotvec(Eigen::Vector3d(0.3, -0.1, 1.2), Eigen::Vector3d(500, -200, 1200));
  std::vector<TrackedPose> log;
  for (int k = 0; k < 2000; ++k) {
    const Eigen::Vector3d w(g(rng), g(rng), g(rng)), r(g(rng), g(rng), g(rng));
    // The rotation's jitter turns the body about its own position: t jitters by r alone.
    log.push_back({0.005 * k, Rigid3d{RotationFromRotvec(Eigen::Vector3d(w * (0.05 * M_PI / 180))) * held.R, held.t + r * 0.2}});
  }
  for (int k = 0; k < 100; ++k) log.push_back({10 + 0.005 * k, Rigid3d::FromRotvec(Eigen::Vector3d(0, 0, 0.01 * k), held.t) * held});
  return log;
}

TEST(TrackerNoise, RecoversTheJitterWithAnIntervalThatCoversIt) {
  int covered_rotation = 0, covered_translation = 0;
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    const TrackerNoise n = EstimateTrackerNoise(StaticLog(seed), 0, 9.999, 10);
    EXPECT_EQ(n.reports, 2000u);
    EXPECT_NEAR(n.rotation.sigma * 180 / M_PI, 0.05, 0.003);
    EXPECT_NEAR(n.translation.sigma, 0.2, 0.012);
    covered_rotation += n.rotation.lower <= 0.05 * M_PI / 180 && 0.05 * M_PI / 180 <= n.rotation.upper;
    covered_translation += n.translation.lower <= 0.2 && 0.2 <= n.translation.upper;
    EXPECT_LT(n.translation.lower, n.translation.sigma);
    EXPECT_GT(n.translation.upper, n.translation.sigma);
  }
  // A 95 % interval misses about once in 20; three misses or more has probability 0.08.
  EXPECT_GE(covered_rotation, 17);
  EXPECT_GE(covered_translation, 17);
}

TEST(TrackerNoise, RefusesASegmentInWhichTheHeadsetMovedOrTooFewReports) {
  EXPECT_THROW(EstimateTrackerNoise(StaticLog(1), 0, 10.4, 10), DegenerateError);
  EXPECT_THROW(EstimateTrackerNoise(StaticLog(1), 0, 0.02, 10), InputError);
}

}  // namespace
}  // namespace vstcal
