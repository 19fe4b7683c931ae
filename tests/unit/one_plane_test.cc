// One plane (Tsai's coplanar case) refined: fx/fy held at Tsai's sx and the principal point held
// where Tsai assumed it (docs/math/uncertainty.md#one-plane); the estimate against the truth and
// the reported σ against a Monte Carlo of fresh noise; the camera file's record of what was held
// and why; and --free-principal-point auto, which frees the principal point only when the scaled
// information determines it.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/formats/calib/calibration_io.h"

namespace vstcal {
namespace {

// A 1280×720 camera with its principal point at the image centre, as Tsai assumes, and barrel
// distortion; one 15×11 board (60 mm) tilted by 35° about 0.8 m away.
Camera PlaneCamera(double k1 = -0.15) {
  Eigen::Matrix3d K;
  K << 820, 0, 639.5, 0, 820, 359.5, 0, 0, 1;
  const double d[5] = {k1, 0.03, 0, 0, 0};
  return Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, d);
}

VolumeSpec OnePlane() {
  VolumeSpec spec;
  spec.grid_cols = 15;
  spec.grid_rows = 11;
  spec.spacing = 60;
  spec.near = spec.far = 0;
  spec.camera_distance = 800;
  spec.tilt_deg = 35;
  spec.tilt_direction_deg = 30;
  return spec;
}

Correspondences Noisy(const Correspondences& clean, double sigma, int trial) {
  return testing::WithNoise(clean, sigma, 9000 + static_cast<uint64_t>(trial));
}

double StdDev(const std::vector<double>& v) {
  double mean = 0, ss = 0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

double Mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum / static_cast<double>(v.size());
}

// 150 trials: the standard error of an empirical σ is 5.8 %, so a 20 % band is 3.4 of them; the
// mean must lie within 4 standard errors of the truth (held parameters are true here, so the
// estimate is unbiased to first order).
TEST(OnePlane, RefinedAgainstTheTruthAndItsReportedSigma) {
  const int trials = 150;
  const double sigma = 0.3;
  const Camera truth = PlaneCamera();
  const SyntheticVolume clean = SynthesizeVolume(truth, OnePlane(), {});
  const Eigen::Vector3d point(300, -200, 400);  // in front of the plane, off its centre
  std::vector<double> f, k1, u, v;
  CalibrationResult first;
  for (int t = 0; t < trials; ++t) {
    CalibrationResult r = Calibrate(Noisy(clean.correspondences, sigma, t), CalibrationOptions{});
    ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
    const std::vector<double>& p = r.camera.camera.params;
    ASSERT_EQ(p[0], p[1]);      // fx = sx·fy with Tsai's sx = 1, exactly
    ASSERT_EQ(p[2], 639.5);     // the principal point held where Tsai assumed it
    ASSERT_EQ(p[3], 359.5);
    f.push_back(p[1]);
    k1.push_back(p[5]);
    const Eigen::Vector2d q = *r.camera.camera.Project(*r.camera.camera_from_world * point);
    u.push_back(q.x());
    v.push_back(q.y());
    if (t == 0) first = std::move(r);
  }
  const ParameterCovariance& cov = *first.camera.covariance;
  ASSERT_EQ(cov.parameters[0], "fx");
  ASSERT_EQ(cov.parameters[1], "fy");
  EXPECT_FALSE(cov.Find("cx").has_value());
  const double sigma_f = std::sqrt(cov.matrix(1, 1));
  const double sigma_k1 = std::sqrt(cov.matrix(*cov.Find("k1"), *cov.Find("k1")));
  const Eigen::Matrix2d projected = ProjectionUncertaintyAtWorldPoint(first.camera, point)->covariance;
  const std::pair<double, double> checks[] = {{StdDev(f), sigma_f}, {StdDev(k1), sigma_k1},
                                              {StdDev(u), std::sqrt(projected(0, 0))}, {StdDev(v), std::sqrt(projected(1, 1))}};
  const char* names[] = {"f", "k1", "u", "v"};
  for (int i = 0; i < 4; ++i) {
    ::testing::Test::RecordProperty(std::string("empirical/predicted ") + names[i], ::testing::PrintToString(checks[i].first / checks[i].second));
    EXPECT_LT(std::abs(checks[i].first / checks[i].second - 1), 0.2) << names[i] << ": " << checks[i].first << " vs " << checks[i].second;
  }
  EXPECT_LT(std::abs(Mean(f) - truth.params[1]), 4 * sigma_f / std::sqrt(trials));
  EXPECT_LT(std::abs(Mean(k1) - truth.params[5]), 4 * sigma_k1 / std::sqrt(trials));

  // The camera file says what was held and why.
  const OrderedJson blocks = CalibrationBlocksToJson(first, CalibrationOptions{});
  const OrderedJson& held = blocks["refinement"]["held"];
  auto find = [&](const std::string& name) -> const OrderedJson* {
    for (const auto& h : held) {
      if (h["parameter"] == name) return &h;
    }
    return nullptr;
  };
  ASSERT_NE(find("fx/fy"), nullptr) << held.dump();
  EXPECT_EQ((*find("fx/fy"))["value"], 1.0);
  EXPECT_NE((*find("fx/fy"))["because"].get<std::string>().find("one plane"), std::string::npos);
  ASSERT_NE(find("cx"), nullptr) << held.dump();
  EXPECT_EQ((*find("cx"))["value"], 639.5);
  EXPECT_NE((*find("cy"))["because"].get<std::string>().find("--free-principal-point"), std::string::npos);
  EXPECT_EQ(blocks["refinement"]["one_plane"]["principal_point"], "held");
  EXPECT_EQ(blocks["refinement"]["free_intrinsics"], OrderedJson({"fx", "fy", "k1", "k2", "p1", "p2"}));
}

// auto: a pinhole's principal point is not determined by one plane (the homography has 8 degrees
// of freedom, the pose and f take 7 and the principal point would need 2 more), so it stays held
// and says why; a strongly distorted lens determines it through the distortion centre, so it is
// freed, with its σ within the limit.
TEST(OnePlane, AutoFreesThePrincipalPointOnlyWhenDetermined) {
  CalibrationOptions options;
  options.plane_principal_point = CalibrationOptions::PlanePrincipalPoint::kAuto;
  options.refinement.free_distortion = {};
  const Eigen::Matrix3d K = PlaneCamera().K();
  const Camera pinhole = Camera::FromK(K, ImageSize{1280, 720});
  VolumeSpec steep = OnePlane();
  steep.tilt_deg = 45;
  CalibrationResult r = Calibrate(Noisy(SynthesizeVolume(pinhole, steep, {}).correspondences, 0.2, 1), options);
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_TRUE(r.plane_principal_point.has_value());
  EXPECT_FALSE(r.plane_principal_point->freed);
  EXPECT_FALSE(r.plane_principal_point->sigma_if_free_px.has_value());
  EXPECT_NE(r.plane_principal_point->because.find("not determined by these points"), std::string::npos)
      << r.plane_principal_point->because;
  EXPECT_EQ(r.camera.camera.params[2], 639.5);

  // Forced free, the same pinhole plane is unobservable, and the message names the principal point.
  options.plane_principal_point = CalibrationOptions::PlanePrincipalPoint::kFree;
  // (Whether the solver then stops or wanders along the null direction, no covariance is given.)
  r = Calibrate(Noisy(SynthesizeVolume(pinhole, steep, {}).correspondences, 0.2, 1), options);
  EXPECT_FALSE(r.camera.covariance.has_value());
  ASSERT_TRUE(r.refinement.has_value());
  EXPECT_NE(r.refinement->message.find("the information matrix is singular"), std::string::npos) << r.refinement->message;
  EXPECT_NE(r.refinement->message.find("cx"), std::string::npos) << r.refinement->message;

  // Through the distortion: k1 = −0.25 puts the principal point to about 1 px (freed, and found
  // within 4σ of the truth, 8 px and 6 px off the image centre); k1 = −0.02 would leave it to
  // more than the limit (held, saying by how much).
  options = CalibrationOptions{};
  options.plane_principal_point = CalibrationOptions::PlanePrincipalPoint::kAuto;
  options.refinement.free_distortion = {"k1", "k2"};
  VolumeSpec near = OnePlane();
  near.camera_distance = 650;
  for (const double k1 : {-0.25, -0.02}) {
    Camera lens = PlaneCamera(k1);
    lens.params[2] = 647.5;
    lens.params[3] = 353.5;
    r = Calibrate(Noisy(SynthesizeVolume(lens, near, {}).correspondences, 0.2, 2), options);
    ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
    const PlanePrincipalPointDecision& d = *r.plane_principal_point;
    ASSERT_TRUE(d.sigma_if_free_px.has_value()) << d.because;
    ::testing::Test::RecordProperty("sigma_if_free_px at k1 " + std::to_string(k1), ::testing::PrintToString(d.sigma_if_free_px->transpose()));
    EXPECT_NEAR(d.limit_px, 0.005 * std::hypot(1280, 720), 1e-12);
    if (k1 == -0.25) {
      ASSERT_TRUE(d.freed) << d.because;
      EXPECT_LT(d.sigma_if_free_px->maxCoeff(), d.limit_px);
      const ParameterCovariance& cov = *r.camera.covariance;
      ASSERT_TRUE(cov.Find("cx").has_value());
      const double sx = std::sqrt(cov.matrix(*cov.Find("cx"), *cov.Find("cx")));
      const double sy = std::sqrt(cov.matrix(*cov.Find("cy"), *cov.Find("cy")));
      EXPECT_LT(std::abs(r.camera.camera.params[2] - 647.5), 4 * sx);
      EXPECT_LT(std::abs(r.camera.camera.params[3] - 353.5), 4 * sy);
    } else {
      EXPECT_FALSE(d.freed) << d.because;
      EXPECT_GT(d.sigma_if_free_px->maxCoeff(), d.limit_px);
      EXPECT_EQ(d.because.rfind("held: its sigma with it free would be", 0), 0u) << d.because;
      EXPECT_EQ(r.camera.camera.params[2], 639.5);
    }
  }
}

}  // namespace
}  // namespace vstcal
