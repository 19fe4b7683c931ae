// The statistics of the CI checks against closed forms: calib-compare's disagreement in σ
// (DisagreementSigma, CompareCameras' max_sigma), err-sim check's rise judged with the Monte Carlo
// standard errors (JudgeRise, CheckMetrics), and the JUnit XML they write (XmlEscape, JUnitXml).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "vstcal/calib/compare.h"
#include "vstcal/core/error.h"
#include "vstcal/errsim/report_check.h"
#include "vstcal/files/junit_xml.h"
#include "vstcal/sensitivity/rise_check.h"

namespace vstcal {
namespace {

// --- DisagreementSigma: √(dᵀ (Σa + Σb)⁻¹ d) -------------------------------------------------------

TEST(DisagreementSigma, DiagonalCovariances) {
  // Σ = diag(2, 8): 3²/2 + 4²/8 = 4.5 + 2 = 6.5.
  const Eigen::Matrix2d a = Eigen::Vector2d(1, 4).asDiagonal(), b = Eigen::Vector2d(1, 4).asDiagonal();
  EXPECT_NEAR(DisagreementSigma({3, 4}, a, b), std::sqrt(6.5), 1e-14);
}

TEST(DisagreementSigma, AlongAnAxisOfARotatedEllipse) {
  // Σ = R diag(9, 1) Rᵀ with R a 30° rotation: a difference of 6 along the major axis is 2 σ,
  // 6 along the minor one 6 σ.
  const double c = std::cos(kPi / 6), s = std::sin(kPi / 6);
  Eigen::Matrix2d R;
  R << c, -s, s, c;
  const Eigen::Matrix2d sigma = R * Eigen::Vector2d(9, 1).asDiagonal() * R.transpose();
  EXPECT_NEAR(DisagreementSigma(6 * R.col(0), sigma / 2, sigma / 2), 2.0, 1e-12);
  EXPECT_NEAR(DisagreementSigma(6 * R.col(1), sigma / 4, 3 * sigma / 4), 6.0, 1e-12);
}

TEST(DisagreementSigma, SingularCovariance) {
  // Only u is uncertain: a difference in u is measured in its σ, one in v is infinitely unlikely.
  const Eigen::Matrix2d a = Eigen::Vector2d(1, 0).asDiagonal();
  EXPECT_NEAR(DisagreementSigma({2, 0}, a, a), std::sqrt(2.0), 1e-14);
  EXPECT_EQ(DisagreementSigma({2, 1e-6}, a, a), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(DisagreementSigma({2, 1e-12}, a, a), std::sqrt(2.0), 1e-14);  // rounding, not a difference
  EXPECT_EQ(DisagreementSigma({0, 0}, Eigen::Matrix2d::Zero(), Eigen::Matrix2d::Zero()), 0.0);
}

// --- CompareCameras' max_sigma ---------------------------------------------------------------------

CalibratedCamera Camera1280(double fx, double cx, bool posed, const std::vector<std::string>& names,
                            const Eigen::VectorXd& variances) {
  Eigen::Matrix3d K;
  K << fx, 0, cx, 0, 1000, 360, 0, 0, 1;
  CalibratedCamera c;
  c.camera = Camera::FromK(K, ImageSize{1280, 720});
  if (posed) c.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, 0.2, -0.1), Eigen::Vector3d(5, -10, 2500));
  c.covariance = ParameterCovariance{names, variances.asDiagonal(), {}};
  return c;
}

// A principal point 1.5 px apart, each known to σ = 0.5 px in u and v: the difference (1.5, 0) has
// covariance diag(0.5, 0.5), so it is 1.5/√0.5 = 2.1213 σ at every grid point — posed (intrinsics
// and pose varying; the pose is not in the covariance) or not (intrinsics only).
TEST(CompareCamerasSigma, PrincipalPointShiftInItsOwnSigma) {
  for (const bool posed : {true, false}) {
    const Eigen::Vector2d v(0.25, 0.25);
    const CameraComparison c =
        CompareCameras(Camera1280(1000, 640, posed, {"cx", "cy"}, v), Camera1280(1000, 641.5, posed, {"cx", "cy"}, v), 1800.0);
    ASSERT_TRUE(c.max_sigma) << posed;
    EXPECT_NEAR(*c.max_sigma, 1.5 / std::sqrt(0.5), 1e-9) << posed;
    EXPECT_NEAR(c.max_px, 1.5, 1e-9);
  }
}

// fx 2 px apart, each with σ_fx = 1: at a point of normalized x the difference is (2x, 0) with
// covariance diag(2x², 0) — singular in v, where the difference is 0 — so √2 σ at every grid point.
TEST(CompareCamerasSigma, FocalLengthShiftThroughASingularCovariance) {
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 1.0);
  const CameraComparison c = CompareCameras(Camera1280(1000, 640, true, {"fx"}, v), Camera1280(1002, 640, true, {"fx"}, v));
  ASSERT_TRUE(c.max_sigma);
  EXPECT_NEAR(*c.max_sigma, std::sqrt(2.0), 1e-9);
}

TEST(CompareCamerasSigma, NoneWithoutBothCovariances) {
  CalibratedCamera b = Camera1280(1000, 641.5, true, {"cx"}, Eigen::VectorXd::Constant(1, 0.25));
  b.covariance.reset();
  EXPECT_FALSE(CompareCameras(Camera1280(1000, 640, true, {"cx"}, Eigen::VectorXd::Constant(1, 0.25)), b).max_sigma);
}

// --- JudgeRise --------------------------------------------------------------------------------------

// Standard errors 0.03 and 0.04 make the difference's 0.05 (3-4-5); allowed 0.1, z = 3: a rise up to
// 0.1 passes, up to 0.1 + 3·0.05 = 0.25 is within noise, beyond fails.
TEST(JudgeRise, PassWithinNoiseFail) {
  RiseJudgement j = JudgeRise(1.0, 0.03, 1.08, 0.04, 0.1, 3);
  EXPECT_EQ(j.verdict, CheckVerdict::kPass);
  EXPECT_NEAR(j.rise, 0.08, 1e-15);
  EXPECT_NEAR(j.noise, 0.05, 1e-16);
  EXPECT_EQ(JudgeRise(1.0, 0.03, 0.7, 0.04, 0.1, 3).verdict, CheckVerdict::kPass);  // fell
  EXPECT_EQ(JudgeRise(1.0, 0.03, 1.2, 0.04, 0.1, 3).verdict, CheckVerdict::kWithinNoise);
  EXPECT_EQ(JudgeRise(1.0, 0.03, 1.3, 0.04, 0.1, 3).verdict, CheckVerdict::kFail);
  // The same rise of 0.2 fails at z = 1.5 (0.1 + 0.075 < 0.2) and is within noise at z = 2.5.
  EXPECT_EQ(JudgeRise(1.0, 0.03, 1.2, 0.04, 0.1, 1.5).verdict, CheckVerdict::kFail);
  EXPECT_EQ(JudgeRise(1.0, 0.03, 1.2, 0.04, 0.1, 2.5).verdict, CheckVerdict::kWithinNoise);
  // Exact Monte Carlo (no noise): any rise beyond the allowance fails.
  EXPECT_EQ(JudgeRise(1.0, 0, 1.1 + 1e-9, 0, 0.1, 3).verdict, CheckVerdict::kFail);
}

TEST(RiseAllowance, AmountOrFraction) {
  EXPECT_DOUBLE_EQ((RiseAllowance{0.1, true}).Of(2.5), 0.25);
  EXPECT_DOUBLE_EQ((RiseAllowance{0.1, false}).Of(2.5), 0.1);
}

// --- CheckMetrics -----------------------------------------------------------------------------------

std::vector<MonteCarloMetric> Metrics(double a, double b) {
  return {{"p", "image.left.pixel_px", a, 0.01}, {"p", "misregistration.linear", b, 0.02}, {"q", "misregistration.linear", b, 0.02}};
}

TEST(CheckMetrics, RulesByMetricThenMeasureThenDefault) {
  // Accepted 1.0 / 2.0, new 1.2 / 2.3: rises 0.2 and 0.3 with noise √2·0.01 and √2·0.02.
  const std::vector<RiseRule> rules = {{"misregistration.linear", {0.5, false}}, {"q.misregistration.linear", {0.1, true}}};
  const auto checks = CheckMetrics(Metrics(1.0, 2.0), Metrics(1.2, 2.3), RiseAllowance{0.1, true}, rules, 3);
  ASSERT_EQ(checks.size(), 3u);
  // p.image: default 10 % of 1.0 = 0.1; excess 0.1 > 3·0.01414 → fail.
  EXPECT_NEAR(checks[0].judgement.allowed, 0.1, 1e-15);
  EXPECT_EQ(checks[0].judgement.verdict, CheckVerdict::kFail);
  // p.misregistration: the measure's 0.5 → pass.
  EXPECT_EQ(checks[1].judgement.allowed, 0.5);
  EXPECT_EQ(checks[1].judgement.verdict, CheckVerdict::kPass);
  // q.misregistration: its own 10 % of 2.0 = 0.2; excess 0.1 > 3·0.0283 = 0.085 → fail.
  EXPECT_NEAR(checks[2].judgement.allowed, 0.2, 1e-15);
  EXPECT_EQ(checks[2].judgement.verdict, CheckVerdict::kFail);
  EXPECT_EQ(checks[2].result.name, "q.misregistration.linear");
  EXPECT_NE(checks[2].result.message.find("rise 0.3"), std::string::npos) << checks[2].result.message;
}

TEST(CheckMetrics, MissingFromTheNewReportFails) {
  std::vector<MonteCarloMetric> fresh = Metrics(1.0, 2.0);
  fresh.pop_back();
  const auto checks = CheckMetrics(Metrics(1.0, 2.0), fresh, RiseAllowance{}, {}, 3);
  EXPECT_EQ(checks[1].judgement.verdict, CheckVerdict::kPass);
  EXPECT_FALSE(checks[2].present);
  EXPECT_EQ(checks[2].judgement.verdict, CheckVerdict::kFail);
  EXPECT_NE(checks[2].result.message.find("missing from the new report"), std::string::npos);
}

TEST(CheckMetrics, UnknownOrRepeatedNamesAreRefused) {
  const std::vector<RiseRule> typo = {{"misregistration.linaer", {0.1, true}}};
  try {
    CheckMetrics(Metrics(1, 2), Metrics(1, 2), RiseAllowance{}, typo, 3);
    FAIL() << "accepted an unknown measure";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean \"misregistration.linear\""), std::string::npos) << e.what();
  }
  const std::vector<RiseRule> twice = {{"p.misregistration.linear", {0.1, true}}, {"p.misregistration.linear", {0.2, true}}};
  EXPECT_THROW(CheckMetrics(Metrics(1, 2), Metrics(1, 2), RiseAllowance{}, twice, 3), InputError);
}

TEST(CheckMetrics, TheMeasuresAreTheStatisticsDocumentedWithAStandardError) {
  // docs/tools/err-sim.md#check's table, spelled here from the format's documentation: the list
  // itself is derived from errsim/outputs.h's kMeasures.
  const std::vector<std::string> documented = {
      "image.left.pixel_px",       "image.right.pixel_px",        "misregistration.linear",    "misregistration.lateral",
      "misregistration.depth_abs", "misregistration.angular_deg", "misperception.linear",      "misperception.lateral",
      "misperception.depth_abs",   "misperception.angular_deg",   "occlusion.left.wrong_rate", "occlusion.right.wrong_rate"};
  std::vector<std::string> derived;
  for (const CheckedMeasure& m : CheckedMeasures()) derived.push_back(m.name);
  EXPECT_EQ(derived, documented);
}

// --- JUnit XML --------------------------------------------------------------------------------------

TEST(XmlEscape, MarkupControlCharactersAndBadUtf8) {
  EXPECT_EQ(XmlEscape("a<b & 'c' \"d\" > e"), "a&lt;b &amp; &apos;c&apos; &quot;d&quot; &gt; e");
  EXPECT_EQ(XmlEscape("σ ≤ 3 \t\n"), "σ ≤ 3 \t\n");
  EXPECT_EQ(XmlEscape(std::string("x\x01y\x7f", 4)), "x\\x01y\\x7f");
  EXPECT_EQ(XmlEscape("\xff\xc3("), "\\xff\\xc3(");           // not UTF-8
  EXPECT_EQ(XmlEscape("\xed\xa0\x80"), "\\xed\\xa0\\x80");   // a surrogate
  EXPECT_EQ(XmlEscape("\xc0\xaf"), "\\xc0\\xaf");             // overlong '/'
}

TEST(JUnitXml, OneTestcasePerCheckAndAFailureElementPerFailedOne) {
  const std::vector<CheckResult> results = {{"grid px", CheckVerdict::kPass, "0.1 px ≤ 0.5"},
                                            {"a<b", CheckVerdict::kFail, "2 > 1 & more"},
                                            {"c", CheckVerdict::kWithinNoise, "close"}};
  const std::string xml = JUnitXml("calib-compare", results);
  EXPECT_EQ(xml.rfind("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", 0), 0u);
  EXPECT_NE(xml.find("<testsuite name=\"calib-compare\" tests=\"3\" failures=\"1\" errors=\"0\" skipped=\"0\">"),
            std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"calib-compare\" name=\"a&lt;b\">\n      <failure message=\"fail: 2 &gt; 1 &amp; more\""),
            std::string::npos) << xml;
  EXPECT_NE(xml.find("<system-out>within noise: close</system-out>"), std::string::npos) << xml;
  size_t failures = 0;
  for (size_t at = xml.find("<failure "); at != std::string::npos; at = xml.find("<failure ", at + 1)) ++failures;
  EXPECT_EQ(failures, 1u);
}

}  // namespace
}  // namespace vstcal
