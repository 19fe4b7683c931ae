// Maximum-likelihood refinement: recovery of a distorted camera from planar views (Zhang init)
// and from a volume (DLT init), agreement with OpenCV's calibrateCamera on the same data (the
// same objective, so the same optimum), outliers, and refusals.
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include <algorithm>

#include "support/opencv_views.h"
#include "support/scenes.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/calib/refine.h"
#include "vstcal/calib/zhang.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

Camera DistortedCamera() { return testing::DistortedWideCamera(); }

SyntheticViews PlanarData(double noise, uint64_t seed, int views = 15) {
  PlanarViewsSpec spec;
  spec.noise_px = noise;
  spec.seed = seed;
  spec.num_views = views;
  return SynthesizePlanarViews(DistortedCamera(), spec);
}

// cv::calibrateCamera takes float32 points: the comparisons give both solvers the same rounded data.
void RoundToFloat(Correspondences* c) {
  for (View& v : c->views) {
    for (Observation& o : v.observations) {
      o.point = o.point.cast<float>().cast<double>();
      o.pixel = o.pixel.cast<float>().cast<double>();
    }
  }
}

using OpenCvData = testing::OpenCvViews;

// One OpenCV "view" per planar view; a volume rig is one view of all its points.
OpenCvData ToOpenCv(const Correspondences& c) { return testing::ToOpenCvViews(c); }

// fx, fy, cx, cy and the first `terms` distortion coefficients (OpenCV's order is ours: k1, k2,
// p1, p2, k3, k4, k5, k6) of OpenCV's result against ours, within 1 % of our σ.
void ExpectSameOptimum(const Refinement& r, const cv::Mat& K, const cv::Mat& dist, int terms = 4) {
  std::vector<double> opencv = {K.at<double>(0, 0), K.at<double>(1, 1), K.at<double>(0, 2), K.at<double>(1, 2)};
  std::vector<int> ours = {0, 1, 2, 3};
  for (int i = 0; i < terms; ++i) {
    opencv.push_back(dist.at<double>(i));
    ours.push_back(kNumIntrinsicParams + i);
  }
  const auto names = LensModelParamNames(r.camera.model);
  for (size_t i = 0; i < ours.size(); ++i) {
    const size_t index = *r.covariance.Find(names[ours[i]]);
    const double sigma = std::sqrt(r.covariance.matrix(index, index));
    EXPECT_LT(std::abs(r.camera.params[ours[i]] - opencv[i]), 0.01 * sigma) << names[ours[i]];
  }
}

Refinement RefinePlanar(const Correspondences& c, const RefineOptions& options = {}) {
  const ZhangResult init = ZhangInitialization(c);
  EXPECT_TRUE(init.ok) << init.message;
  return Refine(c, init.camera, init.camera_from_board, options);
}

// Every free intrinsic within 5σ of the truth, σ from the refinement's own covariance: a test of
// the estimate and of the covariance together.
void ExpectWithinSigma(const Refinement& r, const Camera& truth, double k = 5.0) {
  const auto names = LensModelParamNames(r.camera.model);
  ASSERT_FALSE(r.covariance.parameters.empty()) << r.message;
  for (size_t i = 0; i < names.size(); ++i) {
    const auto index = r.covariance.Find(names[i]);
    if (!index) continue;
    const double sigma = std::sqrt(r.covariance.matrix(*index, *index));
    EXPECT_LT(std::abs(r.camera.params[i] - truth.params[i]), k * sigma) << names[i] << " σ=" << sigma;
  }
}

TEST(Refine, NoiseFreePlanarViewsRecoverTheDistortedCameraExactly) {
  const SyntheticViews data = PlanarData(0.0, 1);
  const Refinement r = RefinePlanar(data.correspondences);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  const Camera truth = DistortedCamera();
  for (size_t i = 0; i < truth.params.size(); ++i) EXPECT_NEAR(r.camera.params[i], truth.params[i], 1e-7 * (1 + std::abs(truth.params[i]))) << i;
  EXPECT_LT(r.fit.overall.max_px, 1e-7);
  for (size_t v = 0; v < r.poses.size(); ++v) {
    EXPECT_LT(AngleBetween(r.poses[v].R, data.camera_from_board[v].R), 1e-9);
    EXPECT_LT((r.poses[v].t - data.camera_from_board[v].t).norm(), 1e-6);
  }
}

TEST(Refine, NoisyPlanarViewsWithinTheirOwnUncertainty) {
  const SyntheticViews data = PlanarData(0.3, 2);
  const Refinement r = RefinePlanar(data.correspondences);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  ExpectWithinSigma(r, DistortedCamera());
  // σ̂ estimates the per-coordinate noise with 2N − p degrees of freedom.
  EXPECT_NEAR(r.sigma_px, 0.3, 5 * 0.3 / std::sqrt(2.0 * r.dof));
  // The intrinsics are named parameters; each view's pose is a block of its own (linear in views).
  EXPECT_EQ(r.covariance.parameters.size(), 8u);
  EXPECT_EQ(r.covariance.parameters[0], "fx");
  EXPECT_EQ(r.covariance.parameters[7], "p2");
  ASSERT_EQ(r.covariance.poses.size(), data.correspondences.views.size());
  EXPECT_EQ(r.covariance.poses[0].pose, "views[0].camera_from_board");
  EXPECT_EQ(r.covariance.poses[0].with_parameters.cols(), 8);
  EXPECT_TRUE(r.outliers.empty());
}

// Peer: OpenCV's calibrateCamera minimizes the same reprojection error over the same model (k3
// fixed as vstcal's default); both must land on the same optimum. The tolerance is 1 % of the
// parameter's own standard deviation: far below anything statistically meaningful, far above the
// two solvers' convergence tolerances.
TEST(Refine, PlanarViewsAgreeWithOpenCvCalibrateCamera) {
  SyntheticViews data = PlanarData(0.3, 3);
  RoundToFloat(&data.correspondences);
  const Refinement r = RefinePlanar(data.correspondences);
  ASSERT_EQ(r.status, RefineStatus::kConverged);
  const OpenCvData d = ToOpenCv(data.correspondences);
  cv::Mat K, dist;
  std::vector<cv::Mat> rvecs, tvecs;
  const double rms = cv::calibrateCamera(d.object, d.image, cv::Size(1280, 720), K, dist, rvecs, tvecs, cv::CALIB_FIX_K3,
                                         cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 200, 1e-15));
  EXPECT_NEAR(rms, r.fit.overall.rms_px, 1e-6);
  ExpectSameOptimum(r, K, dist);
}

// The rational model against OpenCV's CALIB_RATIONAL_MODEL on the same views of a wide lens whose
// distortion is a ratio (k1, k2, p1, p2, k4 free in both; k3, k5, k6 held at 0 — with all six
// radial terms free, numerator and denominator share a nearly flat valley that neither solver
// crosses to 1 % of σ): the same optimum, within 1 % of our σ, and the truth within 5σ.
TEST(Refine, RationalModelAgreesWithOpenCvRationalModel) {
  Eigen::Matrix3d K0;
  K0 << 600.5, 0, 643.2, 0, 599.8, 358.1, 0, 0, 1;
  const double d[8] = {-0.02, 0.01, 0.0006, -0.0003, 0, 0.16, 0, 0};
  const Camera truth = Camera::FromK(K0, ImageSize{1280, 720}, RationalModel{}, d);
  PlanarViewsSpec spec;
  spec.num_views = 25;
  spec.noise_px = 0.2;
  spec.seed = 12;
  SyntheticViews data = SynthesizePlanarViews(truth, spec);
  RoundToFloat(&data.correspondences);
  RefineOptions options;
  options.free_distortion = {"k1", "k2", "p1", "p2", "k4"};
  const Refinement r = RefinePlanar(data.correspondences, options);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  ::testing::Test::RecordProperty("smallest scaled eigenvalue", ::testing::PrintToString(r.smallest_scaled_eigenvalue));
  ASSERT_EQ(LensModelName(r.camera.model), "rational");
  ASSERT_FALSE(r.covariance.empty()) << r.message;
  const OpenCvData cv_data = ToOpenCv(data.correspondences);
  cv::Mat K, dist;
  std::vector<cv::Mat> rvecs, tvecs;
  const double rms = cv::calibrateCamera(cv_data.object, cv_data.image, cv::Size(1280, 720), K, dist, rvecs, tvecs,
                                         cv::CALIB_RATIONAL_MODEL | cv::CALIB_FIX_K3 | cv::CALIB_FIX_K5 | cv::CALIB_FIX_K6,
                                         cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 500, 1e-15));
  ASSERT_GE(dist.total(), 8u);  // OpenCV returns 14 (its tilted-sensor terms, 0 here)
  EXPECT_NEAR(rms, r.fit.overall.rms_px, 1e-6);
  ExpectSameOptimum(r, K, dist, 4);
  const double k4 = dist.at<double>(5);
  const double sigma_k4 = std::sqrt(r.covariance.matrix(*r.covariance.Find("k4"), *r.covariance.Find("k4")));
  EXPECT_LT(std::abs(r.camera.params[10] - k4), 0.01 * sigma_k4);
  ExpectWithinSigma(r, truth);
}

// A volume rig: DLT start, then refinement with distortion. OpenCV accepts non-planar points only
// with CALIB_USE_INTRINSIC_GUESS; given vstcal's DLT K it must reach the same optimum.
TEST(Refine, VolumeFromDltAgreesWithOpenCvIntrinsicGuess) {
  VolumeSpec spec = testing::NearWideVolumeSpec();
  spec.noise_px = 0.2;
  spec.seed = 4;
  const Camera truth = DistortedCamera();
  SyntheticVolume volume = SynthesizeVolume(truth, spec, {});
  RoundToFloat(&volume.correspondences);
  const Correspondences& c = volume.correspondences;
  const DltResult dlt = SolveDlt(AllObservations(c));
  ASSERT_EQ(dlt.status, DltStatus::kOk) << dlt.message;
  const auto init = *DecomposeProjection(dlt.P);
  Camera start = Camera::FromK(init.K, c.image_size);
  start.params[4] = 0;  // OpenCV has no skew: start both from the same zero-skew K
  const Refinement r = Refine(c, start, {init.camera_from_world}, RefineOptions{});
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  ExpectWithinSigma(r, truth);

  const OpenCvData d = ToOpenCv(c);
  cv::Mat K = (cv::Mat_<double>(3, 3) << start.params[0], 0, start.params[2], 0, start.params[1], start.params[3], 0, 0, 1);
  cv::Mat dist = cv::Mat::zeros(5, 1, CV_64F);
  std::vector<cv::Mat> rvecs, tvecs;
  const double rms = cv::calibrateCamera(d.object, d.image, cv::Size(1280, 720), K, dist, rvecs, tvecs,
                                         cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K3,
                                         cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 500, 1e-15));
  EXPECT_NEAR(rms, r.fit.overall.rms_px, 1e-6);
  ExpectSameOptimum(r, K, dist);
}

// Gross errors on a few corners: listed as outliers (never dropped), and a robust loss keeps the
// estimate where the clean data put it.
TEST(Refine, OutliersAreListedAndRobustLossResistsThem) {
  SyntheticViews data = PlanarData(0.2, 5);
  Correspondences& c = data.correspondences;
  const std::vector<std::pair<size_t, size_t>> corrupted = {{1, 7}, {4, 20}, {9, 33}};
  for (const auto& [v, k] : corrupted) c.views[v].observations[k].pixel += Eigen::Vector2d(15, -12);
  const Refinement plain = RefinePlanar(c);
  RefineOptions robust_options;
  robust_options.loss = RefineOptions::Loss::kCauchy;
  robust_options.loss_scale_px = 1.0;
  const Refinement robust = RefinePlanar(c, robust_options);
  // The robust fit ignores the gross errors: exactly they are listed. Least squares is dragged by
  // them, so a few honest neighbours may exceed the threshold too, but the corrupted ones are
  // listed and stand out most.
  ASSERT_EQ(robust.status, RefineStatus::kConverged) << robust.message;
  ASSERT_EQ(robust.outliers.size(), corrupted.size());
  for (size_t i = 0; i < corrupted.size(); ++i) {
    EXPECT_EQ(robust.outliers[i].view, corrupted[i].first);
    EXPECT_EQ(robust.outliers[i].point, corrupted[i].second);
    EXPECT_GT(robust.outliers[i].normalized, 20);
  }
  ASSERT_EQ(plain.status, RefineStatus::kConverged) << plain.message;
  std::vector<Outlier> worst = plain.outliers;
  std::sort(worst.begin(), worst.end(), [](const Outlier& a, const Outlier& b) { return a.normalized > b.normalized; });
  ASSERT_GE(worst.size(), corrupted.size());
  for (size_t i = 0; i < corrupted.size(); ++i) {
    EXPECT_NE(std::find_if(corrupted.begin(), corrupted.end(),
                           [&](const auto& bad) { return bad.first == worst[i].view && bad.second == worst[i].point; }),
              corrupted.end());
  }
  for (const Refinement* r : {&plain, &robust}) EXPECT_EQ(r->fit.overall.n_points, NumObservations(c));  // nothing dropped
  const Camera truth = DistortedCamera();
  EXPECT_LT(std::abs(robust.camera.params[0] - truth.params[0]), std::abs(plain.camera.params[0] - truth.params[0]) + 0.05);
  ExpectWithinSigma(robust, truth);
}

// Under a robust loss the outlier barely weighs in the fit, so it must not weigh in σ̂ either: σ̂
// comes from the other points (dof 2·N_inliers − p) and matches the true noise, and the covariance
// is that of the clean data. Counted in, one +40 px corner would double σ̂ and quadruple the
// covariance.
TEST(Refine, RobustSigmaAndCovarianceLeaveTheOutlierOut) {
  const double noise = 0.5;
  SyntheticViews data = PlanarData(noise, 11);
  RefineOptions huber;
  huber.loss = RefineOptions::Loss::kHuber;
  huber.loss_scale_px = 1.5;
  const Refinement clean = RefinePlanar(data.correspondences, huber);
  data.correspondences.views[3].observations[12].pixel.x() += 40;
  const Refinement dirty = RefinePlanar(data.correspondences, huber);
  ASSERT_EQ(clean.status, RefineStatus::kConverged) << clean.message;
  ASSERT_EQ(dirty.status, RefineStatus::kConverged) << dirty.message;
  ASSERT_EQ(dirty.outliers.size(), 1u);
  EXPECT_TRUE(dirty.sigma_inliers_only);
  EXPECT_EQ(dirty.dof, clean.dof - 2);
  EXPECT_NEAR(dirty.sigma_px, noise, 5 * noise / std::sqrt(2.0 * dirty.dof));
  EXPECT_NEAR(dirty.sigma_px, clean.sigma_px, 0.01 * clean.sigma_px);
  ASSERT_EQ(dirty.covariance.parameters, clean.covariance.parameters);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(dirty.covariance.matrix(i, i), clean.covariance.matrix(i, i), 0.03 * clean.covariance.matrix(i, i))
        << clean.covariance.parameters[i];
  }
  // Least squares keeps the outlier in the fit, and in σ̂.
  const Refinement plain = RefinePlanar(data.correspondences);
  EXPECT_FALSE(plain.sigma_inliers_only);
  EXPECT_EQ(plain.dof, clean.dof);
}

TEST(Refine, SelectedTermsOnlyAndUnknownNamesRefused) {
  const SyntheticViews data = PlanarData(0.2, 6);
  RefineOptions options;
  options.free_distortion = {"k1"};
  const Refinement r = RefinePlanar(data.correspondences, options);
  ASSERT_EQ(r.status, RefineStatus::kConverged);
  EXPECT_EQ(r.camera.params[6], 0.0);  // k2 held at its start
  EXPECT_FALSE(r.covariance.Find("k2").has_value());
  EXPECT_TRUE(r.covariance.Find("k1").has_value());
  options.free_distortion = {"k1", "k7"};
  try {
    RefinePlanar(data.correspondences, options);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown term \"k7\""), std::string::npos) << e.what();
  }
}

TEST(Refine, MoreParametersThanResidualsIsRefusedBeforeSolving) {
  auto scene = testing::RandomVolumeScene(7, 0.1, 1);  // 14 residuals < 8 intrinsics + 6 pose + …
  Correspondences c;
  c.image_size = scene.camera.image_size;
  View& view = c.views.emplace_back();
  view.name = "v";
  view.observations = scene.observations;
  RefineOptions options;
  options.free_distortion = {"k1", "k2", "p1", "p2", "k3"};
  options.free_skew = true;
  const Refinement r = Refine(c, scene.camera, {scene.camera_from_world}, options);
  EXPECT_EQ(r.status, RefineStatus::kTooFewPoints);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NE(r.message.find("7 points give 14 for 16"), std::string::npos) << r.message;
}

// One board seen once cannot fix a pinhole's fx, fy, cx and cy together (Zhang 2000, §3.1): the
// information matrix is singular, so no covariance is given and the message says why, whether or
// not the solver stopped. With distortion free, the distortion's centre barely ties the principal
// point down: the solver wanders, and its message names what the points barely determine.
TEST(Refine, UnobservableParametersAreReported) {
  const SyntheticViews data = PlanarData(0.2, 8, 1);
  ASSERT_EQ(data.correspondences.views.size(), 1u);
  const ZhangResult zhang = ZhangInitialization(PlanarData(0.2, 8, 4).correspondences);
  ASSERT_TRUE(zhang.ok) << zhang.message;
  RefineOptions pinhole;
  pinhole.free_distortion = {};
  const Refinement r = Refine(data.correspondences, zhang.camera, {zhang.camera_from_board[0]}, pinhole);
  EXPECT_NE(r.status, RefineStatus::kFailed) << r.message;
  EXPECT_TRUE(r.covariance.empty());
  EXPECT_NE(r.message.find("the information matrix is singular: "), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("not determined by these points"), std::string::npos) << r.message;
  if (r.status == RefineStatus::kNotConverged) {
    EXPECT_EQ(r.message.rfind("the refinement did not converge in 100 iterations: ", 0), 0u) << r.message;
  }
  const Refinement d = Refine(data.correspondences, zhang.camera, {zhang.camera_from_board[0]}, RefineOptions{});
  ASSERT_EQ(d.status, RefineStatus::kNotConverged) << d.message;
  EXPECT_LT(d.smallest_scaled_eigenvalue, 1e-6);
  EXPECT_EQ(d.message.rfind("the refinement did not converge in 100 iterations: ", 0), 0u) << d.message;
  EXPECT_NE(d.message.find("barely determined by these points"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("add views of the board tilted about other axes"), std::string::npos) << d.message;
}

// Noise-free views of a zero-skew pinhole: the closed form is exact (Zhang 2000, §3.1), so K and
// every board pose come back to rounding, against calib-synth's ground truth.
TEST(Zhang, RecoversKAndPosesExactlyFromNoiseFreeViews) {
  Eigen::Matrix3d K;
  K << 700.2, 0, 641.3, 0, 698.4, 361.7, 0, 0, 1;
  const Camera truth = Camera::FromK(K, ImageSize{1280, 720}, PinholeModel{}, {});
  PlanarViewsSpec spec;
  spec.num_views = 8;
  const SyntheticViews data = SynthesizePlanarViews(truth, spec);
  ASSERT_EQ(data.camera_from_board.size(), 8u);
  const ZhangResult r = ZhangInitialization(data.correspondences);
  ASSERT_TRUE(r.ok) << r.message;
  const Eigen::Matrix3d got = r.camera.K();
  for (const auto& [row, col] : {std::pair{0, 0}, {1, 1}, {0, 2}, {1, 2}}) {
    EXPECT_LT(std::abs(got(row, col) - K(row, col)), 1e-8 * K(row, col)) << row << col << "\n" << got;
  }
  EXPECT_EQ(got(0, 1), 0.0);  // zero skew imposed
  ASSERT_EQ(r.camera_from_board.size(), data.camera_from_board.size());
  for (size_t v = 0; v < data.camera_from_board.size(); ++v) {
    const Rigid3d& want = data.camera_from_board[v];
    EXPECT_LT(AngleBetween(r.camera_from_board[v].R, want.R), 1e-8) << v;
    EXPECT_LT((r.camera_from_board[v].t - want.t).norm(), 1e-8 * want.t.norm()) << v;
  }
}

TEST(Zhang, RefusesParallelBoardsAndTooFewViews) {
  SyntheticViews data = PlanarData(0.0, 7, 3);
  Correspondences one = data.correspondences;
  one.views.resize(1);
  const ZhangResult r1 = ZhangInitialization(one);
  EXPECT_FALSE(r1.ok);
  EXPECT_NE(r1.message.find("at least 2 views"), std::string::npos);
  // Two copies of one view: parallel boards do not constrain K.
  Correspondences parallel = data.correspondences;
  parallel.views.resize(2);
  parallel.views[1] = parallel.views[0];
  const ZhangResult r2 = ZhangInitialization(parallel);
  EXPECT_FALSE(r2.ok);
  Correspondences sparse = data.correspondences;
  sparse.views[1].observations.resize(4);
  const auto warnings = DropSparseViews(&sparse, kMinPointsPerPlanarView);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("view-01"), std::string::npos);
  EXPECT_EQ(sparse.views.size(), 2u);
}

}  // namespace
}  // namespace vstcal
