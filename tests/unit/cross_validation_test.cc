// Cross-validation of two calibrations (issue 23 item 5; calib-compare --cross-validate): two
// calibrations of one camera from independent views and noise agree at the test's stated rate —
// the joint statistic is χ² with its degrees of freedom, checked over many seeds — and a lens
// model that cannot fit the data (k1, k2 fitted to a strongly rational lens) is caught, because
// each half's systematic error depends on where its boards were.
#include <gtest/gtest.h>

#include <cmath>

#include "support/sanitizers.h"
#include "support/scenes.h"
#include "vstcal/calib/compare.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/capture/synthetic_views.h"

namespace vstcal {
namespace {

Camera WideCamera(bool rational) {
  Eigen::Matrix3d K;
  K << 640, 0, 642.1, 0, 640, 357.8, 0, 0, 1;
  if (!rational) {
    const double d[5] = {-0.12, 0.02, 0, 0, 0};
    return Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, d);
  }
  // OpenCV's rational model with a strong denominator: k1, k2 alone leave residuals of ~1 px at the edges.
  const double d[8] = {0.35, -0.05, 0.0005, -0.0003, 0.0, 0.6, 0.0, 0.0};
  return Camera::FromK(K, ImageSize{1280, 720}, RationalModel{}, d);
}

// One calibration from its own views (poses and noise both from `seed`), refined with `terms`.
CalibratedCamera Calibrated(const Camera& truth, uint64_t seed, double noise_px, std::vector<std::string> terms) {
  PlanarViewsSpec spec;
  spec.num_views = 10;
  spec.seed = seed;
  const SyntheticViews clean = SynthesizePlanarViews(truth, spec);
  CalibrationOptions options;
  options.refinement.free_distortion = std::move(terms);
  const CalibrationResult r = Calibrate(testing::WithNoise(clean.correspondences, noise_px, 9000 + seed), options);
  EXPECT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  return r.camera;
}

// 60 pairs of calibrations of one camera, each from its own 10 views: under the model the joint
// p-value is uniform, so p < 0.05 about 3 times (P(≥ 9) = 0.001 for Binomial(60, 0.05)), and
// χ²/dof averages 1 (its standard error over 60 pairs is √(2/dof/60) ≈ 0.065 for dof 8).
TEST(CrossValidation, TwoCalibrationsOfOneCameraAgreeAtTheStatedRate) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  const Camera truth = WideCamera(false);
  const std::vector<std::string> terms = {"k1", "k2", "p1", "p2"};
  int below_5_percent = 0, disagree = 0;
  double ratio_sum = 0;
  constexpr int kPairs = 60;
  for (int k = 0; k < kPairs; ++k) {
    const CalibratedCamera a = Calibrated(truth, 2 * k + 1, 0.3, terms), b = Calibrated(truth, 2 * k + 2, 0.3, terms);
    const CrossValidation v = CrossValidate(a, b);
    ASSERT_TRUE(v.p_value.has_value());
    EXPECT_EQ(v.tested, 12u);
    EXPECT_EQ(v.dof, 8);  // fx, fy, cx, cy, k1, k2, p1, p2
    below_5_percent += *v.p_value < 0.05;
    disagree += !v.agree;
    ratio_sum += v.chi2 / v.dof;
  }
  ::testing::Test::RecordProperty("below_5_percent", below_5_percent);
  ::testing::Test::RecordProperty("disagree", disagree);
  ::testing::Test::RecordProperty("mean_chi2_per_dof", ::testing::PrintToString(ratio_sum / kPairs));
  EXPECT_LE(below_5_percent, 8);
  EXPECT_LE(disagree, 3);  // alpha 0.01: 0.6 expected, P(≥ 4) = 0.003
  EXPECT_NEAR(ratio_sum / kPairs, 1.0, 0.2);
}

TEST(CrossValidation, DetectsALensModelThatDoesNotFit) {
  const Camera truth = WideCamera(true);
  const CalibratedCamera a = Calibrated(truth, 11, 0.1, {"k1", "k2"}), b = Calibrated(truth, 12, 0.1, {"k1", "k2"});
  const CrossValidation v = CrossValidate(a, b);
  ASSERT_TRUE(v.p_value.has_value());
  ::testing::Test::RecordProperty("chi2", ::testing::PrintToString(v.chi2));
  EXPECT_FALSE(v.agree);
  EXPECT_LT(*v.p_value, 1e-6) << "χ² " << v.chi2 << " dof " << v.dof;
}

// A difference of exactly the predicted kind: b is a with cx moved by δ, and both carry the same
// covariance with cx's variance s²: one region's m is δ/(s√2), and the joint χ² is (δ/s)²/2 with
// one direction of disagreement among the parameters.
TEST(CrossValidation, PrincipalPointShiftGivesTheClosedFormStatistic) {
  CalibratedCamera a;
  a.camera = WideCamera(false);
  ParameterCovariance cov;
  cov.parameters = {"cx"};
  cov.matrix = Eigen::MatrixXd::Constant(1, 1, 0.25);  // s = 0.5 px
  a.covariance = cov;
  CalibratedCamera b = a;
  b.camera.params[2] += 1.5;  // δ = 1.5 px
  const CrossValidation v = CrossValidate(a, b);
  ASSERT_TRUE(v.p_value.has_value());
  EXPECT_EQ(v.dof, 1);
  EXPECT_NEAR(v.chi2, 1.5 * 1.5 / (2 * 0.25), 1e-6);
  for (const RegionAgreement& r : v.regions) {
    ASSERT_TRUE(r.sigma.has_value());
    EXPECT_NEAR(*r.sigma, 1.5 / std::sqrt(2 * 0.25), 1e-6);
    EXPECT_NEAR(*r.distance_px, 1.5, 1e-6);
  }
  EXPECT_NEAR(*v.p_value, std::erfc(std::sqrt(4.5 / 2)), 1e-9);  // P(χ²₁ ≥ 4.5)
  EXPECT_TRUE(v.agree);                                          // p 0.034 ≥ 0.01
  b.camera.params[2] = a.camera.params[2] + 3;
  EXPECT_FALSE(CrossValidate(a, b).agree);  // χ² 18, p 2e-5
}

TEST(CrossValidation, RefusesACameraWithoutCovariance) {
  CalibratedCamera a;
  a.camera = WideCamera(false);
  EXPECT_THROW(CrossValidate(a, a), InputError);
}

}  // namespace
}  // namespace vstcal
