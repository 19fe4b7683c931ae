// calib-stereo solve's library call: the rotation average against closed forms, the joint solve
// against a synthetic rig's truth, its baseline σ against a Monte Carlo, and, on OpenCV's own
// stereo sample, against cv::stereoCalibrate run on the same corners.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <vector>

#include "support/capture_scenes.h"
#include "support/opencv_views.h"
#include "support/sanitizers.h"
#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/capture/detect_run.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/geometry/rotation_average.h"
#include "vstcal/calib/stereo_solve.h"

namespace vstcal {
namespace {

// The synthetic rig: ZED-mini-like, its lenses limited to the terms solve estimates by default
// (k1, k2, p1, p2), so that the model fits the data exactly.
StereoRig SolvableRig() {
  StereoRig rig = testing::ZedLikeRig();
  rig.left.camera.params.back() = 0;  // k3
  rig.right.camera.params.back() = 0;
  return rig;
}

// Pairs R0 Exp(±ε a): their chordal sum is R0 times a symmetric positive definite matrix, whose
// projection onto SO(3) is I, so the chordal mean is R0 exactly (docs/math/stereo.md#rotation-average).
TEST(RotationAverage, ChordalMeanOfSymmetricPairsIsTheirCentre) {
  const Eigen::Matrix3d R0 = RotationFromRotvec(Eigen::Vector3d(0.3, -0.2, 1.1));
  std::vector<Eigen::Matrix3d> rotations;
  for (const Eigen::Vector3d& a : {Eigen::Vector3d(0.05, 0, 0), Eigen::Vector3d(0, 0.1, 0.02), Eigen::Vector3d(0.01, 0, -0.2)}) {
    rotations.push_back(R0 * RotationFromRotvec(a));
    rotations.push_back(R0 * RotationFromRotvec(Eigen::Vector3d(-a)));
  }
  EXPECT_LT(AngleBetween(ChordalMeanRotation(rotations), R0), 1e-12);
  EXPECT_LT(AngleBetween(GeodesicL1MeanRotation(rotations), R0), 1e-9);
}

// One view 20° off among eight within 0.1° of R0: the L2 mean moves by about 20°/9 ≈ 2.2°, the
// geodesic median barely (it moves by less than the spread of the good views, 0.1°).
TEST(RotationAverage, GeodesicMedianResistsAnOutlyingView) {
  const Eigen::Matrix3d R0 = RotationFromRotvec(Eigen::Vector3d(-0.4, 0.7, 0.1));
  std::vector<Eigen::Matrix3d> rotations;
  const double e = DegToRad(0.1);
  for (int k = 0; k < 8; ++k) {
    const double phi = k * kPi / 4;
    rotations.push_back(R0 * RotationFromRotvec(Eigen::Vector3d(e * std::cos(phi), e * std::sin(phi), 0)));
  }
  rotations.push_back(R0 * RotationFromRotvec(Eigen::Vector3d(0, 0, DegToRad(20))));
  EXPECT_GT(RadToDeg(AngleBetween(ChordalMeanRotation(rotations), R0)), 2.0);
  EXPECT_LT(RadToDeg(AngleBetween(GeodesicL1MeanRotation(rotations), R0)), 0.1);
}

// Same input, same output, wherever the heap puts the solve's blocks. Ceres orders the blocks of
// an elimination group by their addresses; the rig's three global blocks (two lenses and
// right_from_left) were once one group of separate allocations, so a path one character longer
// moved the heap and changed fx in its 16th digit. Here freed chunks of the blocks' sizes
// (recycled last-in first-out) put later allocations below earlier ones, in a different way for
// each count.
TEST(StereoSolve, IsTheSameWhereverTheHeapPutsItsBlocks) {
  testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 6, 3);
  views.left = testing::WithNoise(views.left, 0.2, 1);
  views.right = testing::WithNoise(views.right, 0.2, 2);
  std::optional<StereoSolveResult> first;
  for (int count = 0; count <= 8; ++count) {
    {
      std::vector<std::vector<double>> chunks;
      for (int i = 0; i < count; ++i) {
        for (size_t doubles = 3; doubles <= 16; ++doubles) chunks.emplace_back(doubles, 0.0);
      }
    }  // freed here, in order
    StereoSolveResult r = SolveStereo(views.left, views.right, StereoSolveOptions{});
    ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
    if (!first) {
      first = std::move(r);
      continue;
    }
    SCOPED_TRACE("freed chunks per size: " + std::to_string(count));
    EXPECT_EQ(r.rig.left.camera.params, first->rig.left.camera.params);
    EXPECT_EQ(r.rig.right.camera.params, first->rig.right.camera.params);
    EXPECT_TRUE(r.rig.right_from_left.t == first->rig.right_from_left.t);
    EXPECT_TRUE(r.rig.right_from_left.R == first->rig.right_from_left.R);
  }
}

// Noise-free views of a known rig: the solve returns the rig to rounding.
TEST(StereoSolve, RecoversASyntheticRigFromExactViews) {
  const StereoRig truth = SolvableRig();
  const testing::StereoViews views = testing::SyntheticStereoViews(truth, 10, 1);
  const StereoSolveResult r = SolveStereo(views.left, views.right, StereoSolveOptions{});
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  EXPECT_EQ(r.common_views.size(), 10u);
  EXPECT_LT((r.rig.right_from_left.t - truth.right_from_left.t).norm(), 1e-6);
  EXPECT_LT(AngleBetween(r.rig.right_from_left.R, truth.right_from_left.R), 1e-9);
  for (size_t i = 0; i < truth.left.camera.params.size(); ++i) {
    EXPECT_NEAR(r.rig.left.camera.params[i], truth.left.camera.params[i], 1e-6 * std::max(1.0, std::abs(truth.left.camera.params[i])));
    EXPECT_NEAR(r.rig.right.camera.params[i], truth.right.camera.params[i], 1e-6 * std::max(1.0, std::abs(truth.right.camera.params[i])));
  }
  ASSERT_TRUE(r.rig.fit);
  EXPECT_EQ(r.rig.fit->views.size(), 10u);
  EXPECT_LT(r.rig.fit->epipolar.max_px, 1e-6);
}

// A view seen by one camera only is used for that camera and reported; held intrinsics stay put.
TEST(StereoSolve, UsesOneCameraViewsAndHoldsIntrinsics) {
  const StereoRig truth = SolvableRig();
  testing::StereoViews views = testing::SyntheticStereoViews(truth, 8, 2);
  views.right.views.pop_back();
  Camera start = truth.left.camera;
  start.params[0] += 1.0;  // a held camera 1 px off in fx: the solve must keep it, not fix it
  StereoSolveOptions options;
  options.left_camera = start;
  options.hold_left = true;
  const StereoSolveResult r = SolveStereo(views.left, views.right, options);
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  EXPECT_EQ(r.left_only_views, std::vector<std::string>{"view7"});
  EXPECT_EQ(r.common_views.size(), 7u);
  EXPECT_EQ(r.rig.left.camera.params, start.params);
  EXPECT_FALSE(r.rig.left.covariance);
  ASSERT_TRUE(r.rig.covariance);
  EXPECT_GT(r.sigma_px, 0.01);  // the held error shows in the residuals
}

TEST(StereoSolve, TooFewCommonViewsIsDegenerate) {
  testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 6, 3);
  for (size_t k = 0; k < 4; ++k) views.right.views[k].name += "-other";
  const StereoSolveResult r = SolveStereo(views.left, views.right, StereoSolveOptions{}, "L.json", "R.json");
  EXPECT_EQ(r.exit_code, ExitCode::kDegenerate);
  EXPECT_NE(r.message.find("2 usable views are seen by both cameras"), std::string::npos) << r.message;
}

TEST(StereoSolve, DifferingUnitsAreBadInput) {
  testing::StereoViews views = testing::SyntheticStereoViews(SolvableRig(), 4, 4);
  views.right.length_unit = LengthUnit::kMetre;
  EXPECT_THROW(SolveStereo(views.left, views.right, StereoSolveOptions{}), InputError);
}

// The baseline's σ predicted by the solve's covariance against its spread over noisy repetitions
// of the same views: 150 trials give the empirical σ to 1/√(2·149) ≈ 5.8 % (one standard error),
// so predicted and empirical agree within 10 % unless the covariance is wrong by more than a few
// percent. The prediction averaged over the trials (each scales by its own σ̂).
TEST(StereoSolve, BaselineSigmaMatchesMonteCarlo) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  const StereoRig truth = SolvableRig();
  const testing::StereoViews clean = testing::SyntheticStereoViews(truth, 13, 5);
  constexpr int kTrials = 150;
  constexpr double kNoisePx = 0.3;
  std::vector<double> baselines;
  double predicted = 0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const StereoSolveResult r = SolveStereo(testing::WithNoise(clean.left, kNoisePx, 2 * trial),
                                            testing::WithNoise(clean.right, kNoisePx, 2 * trial + 1), StereoSolveOptions{});
    ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
    baselines.push_back(r.rig.baseline());
    predicted += *BaselineSigma(r.rig) / kTrials;
  }
  double mean = 0, var = 0;
  for (double b : baselines) mean += b / kTrials;
  for (double b : baselines) var += (b - mean) * (b - mean) / (kTrials - 1);
  const double empirical = std::sqrt(var);
  EXPECT_NEAR(predicted / empirical, 1.0, 0.10) << "predicted " << predicted << " mm, empirical " << empirical << " mm";
  EXPECT_NEAR(mean, truth.baseline(), 4 * empirical / std::sqrt(kTrials));
}

namespace fs = std::filesystem;
const fs::path kData = "/usr/share/doc/opencv-doc/examples/data";

// One camera of OpenCV's stereo sample detected by the capture module, views named by their pair
// number ("01") so that the two cameras' views match.
Correspondences DetectSample(const std::string& side) {
  std::vector<CaptureInput> inputs;
  for (int k = 1; k <= 14; ++k) {
    const std::string number = (k < 10 ? "0" : "") + std::to_string(k);
    const fs::path path = kData / (side + number + ".jpg");
    if (fs::exists(path)) inputs.push_back({number, path, std::nullopt});
  }
  DetectRequest request;
  request.target = testing::Chessboard9x6();
  request.camera_name = side;
  request.threads = 1;
  Correspondences c = DetectInFiles(inputs, request).correspondences;
  for (View& v : c.views) {
    v.name = v.image;
    for (Observation& o : v.observations) {  // as OpenCV takes them: float
      o.point = o.point.cast<float>().cast<double>();
      o.pixel = o.pixel.cast<float>().cast<double>();
    }
  }
  return c;
}

// cv::stereoCalibrate minimizes the same reprojection error over the same unknowns (both cameras'
// fx, fy, cx, cy, k1, k2, p1, p2 with k3 fixed, R, T and one left pose per view) on the same
// corners, from calibrateCamera's intrinsics: both must reach the same optimum. The tolerance,
// 0.1 % of each quantity's σ from vstcal's covariance, is far below anything statistically
// meaningful and about 20 times what the two solvers' convergence tolerances leave (≤ 5e-5 σ here).
TEST(StereoSolve, AgreesWithOpenCvStereoCalibrateOnTheOpenCvSample) {
  if (!fs::exists(kData / "left01.jpg")) GTEST_SKIP() << "opencv-doc is not installed (scripts/setup installs it)";
  const Correspondences left = DetectSample("left"), right = DetectSample("right");
  ASSERT_EQ(left.views.size(), 13u);
  ASSERT_EQ(right.views.size(), 13u);
  const StereoSolveResult ours = SolveStereo(left, right, StereoSolveOptions{});
  ASSERT_EQ(ours.exit_code, ExitCode::kOk) << ours.message;
  ASSERT_EQ(ours.common_views.size(), 13u);
  ASSERT_TRUE(ours.rig.covariance);

  const testing::OpenCvViews l = testing::ToOpenCvViews(left), r = testing::ToOpenCvViews(right);
  const cv::Size size(left.image_size.width, left.image_size.height);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 300, 1e-15);
  cv::Mat K1, D1, K2, D2, R, T, E, F;
  std::vector<cv::Mat> rvecs, tvecs;
  cv::calibrateCamera(l.object, l.image, size, K1, D1, rvecs, tvecs, cv::CALIB_FIX_K3, criteria);
  cv::calibrateCamera(r.object, r.image, size, K2, D2, rvecs, tvecs, cv::CALIB_FIX_K3, criteria);
  const double rms = cv::stereoCalibrate(l.object, l.image, r.image, K1, D1, K2, D2, size, R, T, E, F,
                                         cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K3, criteria);
  const double ours_rms = std::sqrt(0.5 * (ours.rms_left_px * ours.rms_left_px + ours.rms_right_px * ours.rms_right_px));
  EXPECT_NEAR(rms, ours_rms, 1e-4);

  const ParameterCovariance& cov = *ours.rig.covariance;
  Eigen::Matrix3d R_cv;
  Eigen::Vector3d T_cv;
  for (int i = 0; i < 3; ++i) {
    T_cv(i) = T.at<double>(i);
    for (int j = 0; j < 3; ++j) R_cv(i, j) = R.at<double>(i, j);
  }
  // The difference as a left perturbation of ours: (ω, ρ) with Exp(ω) R = R_cv, Exp(ω) t + ρ = T_cv.
  const Eigen::Vector3d omega = RotvecFromRotation(R_cv * ours.rig.right_from_left.R.transpose());
  const Eigen::Vector3d rho = T_cv - RotationFromRotvec(omega) * ours.rig.right_from_left.t;
  for (int k = 0; k < 6; ++k) {
    const double d = k < 3 ? omega(k) : rho(k - 3);
    EXPECT_LT(std::abs(d), 1e-3 * std::sqrt(cov.matrix(k, k))) << cov.parameters[k] << " σ " << std::sqrt(cov.matrix(k, k));
  }
  EXPECT_NEAR(ours.rig.left.camera.params[0], K1.at<double>(0, 0), 1e-3 * std::sqrt((*ours.rig.left.covariance).matrix(0, 0)));
  EXPECT_NEAR(ours.rig.right.camera.params[0], K2.at<double>(0, 0), 1e-3 * std::sqrt((*ours.rig.right.covariance).matrix(0, 0)));
  EXPECT_LT(ours.rig.fit->epipolar.rms_px, 0.5);
}

}  // namespace
}  // namespace vstcal
