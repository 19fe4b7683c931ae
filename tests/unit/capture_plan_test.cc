// calib-capture plan (lib/vstcal/capture/plan.h): the geometry against closed forms of a
// fronto-parallel pinhole view, and the predicted σ's and projection uncertainty against the
// Monte Carlo spread of real refinements (calib/refine.h) of the planned corners with fresh noise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Eigenvalues>

#include "support/sanitizers.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/calib/refine.h"
#include "vstcal/capture/plan.h"
#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

constexpr double kF = 1400;

Target Chessboard(int cols, int rows, double square) {
  Target t;
  t.cols = cols;
  t.rows = rows;
  t.square_size = square;
  t.margin = square;
  return t;
}

PlanRequest VolumeRequest() {
  PlanRequest r;
  r.camera = Camera::FromK((Eigen::Matrix3d() << kF, 0, 639.5, 0, kF, 511.5, 0, 0, 1).finished(), ImageSize{1280, 1024});
  r.target = Chessboard(13, 9, 100);
  r.rig = Rig::kVolume;
  r.volume.near = 0;
  r.volume.far = 2000;
  r.volume.interval = 500;
  r.volume.camera_distance = 3000;
  return r;
}

// Overlap of [a0, a1] and [b0, b1].
double Overlap(double a0, double a1, double b0, double b1) { return std::max(0.0, std::min(a1, b1) - std::max(a0, b0)); }

TEST(CapturePlan, FrontoParallelGeometryMatchesClosedForms) {
  const PlanRequest r = VolumeRequest();
  const CapturePlan plan = PlanCapture(r);
  ASSERT_EQ(plan.positions.size(), 5u);
  for (const PositionPlan& p : plan.positions) {
    // At tilt 0 the camera sits camera_distance before the near plane on the template's axis.
    const double depth = *p.plane_offset + r.volume.camera_distance;
    const double pw = kF * 1400 / depth, ph = kF * 1000 / depth;  // (cols + 1)·s, (rows + 1)·s
    EXPECT_NEAR(p.coverage, pw * ph / (1280.0 * 1024.0), 1e-9) << p.name;
    EXPECT_NEAR(p.smallest_square_px, kF * 100 / depth, 1e-6) << p.name;
    EXPECT_EQ(p.corners_outside, 0);
    EXPECT_NEAR(p.obliquity_deg, 0, 1e-6);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double x0 = -0.5 + j * 1280.0 / 3, y0 = -0.5 + i * 1024.0 / 3;
        const double area = Overlap(639.5 - pw / 2, 639.5 + pw / 2, x0, x0 + 1280.0 / 3) *
                            Overlap(511.5 - ph / 2, 511.5 + ph / 2, y0, y0 + 1024.0 / 3);
        EXPECT_NEAR(p.region_coverage(i, j), area / (1280.0 * 1024.0 / 9), 1e-9) << p.name << " region " << i << "," << j;
      }
    }
    EXPECT_TRUE(p.warnings.empty()) << p.warnings.front();
  }
}

TEST(CapturePlan, CornersLeavingTheImageAreCountedAndTheChessboardViewDropped) {
  PlanRequest r = VolumeRequest();
  r.volume.camera_distance = 1000;  // the near plane's 1200 mm of corners span 1680 px > 1280
  const CapturePlan plan = PlanCapture(r);
  const PositionPlan& p = plan.positions.front();
  const double depth = 1000;
  int outside = 0;
  double farthest = 0;
  for (int c = 0; c < 13; ++c) {
    for (int row = 0; row < 9; ++row) {
      const double u = 639.5 + kF * (c - 6) * 100 / depth, v = 511.5 + kF * (row - 4) * 100 / depth;
      const double beyond = std::max({-0.5 - u, u - 1279.5, -0.5 - v, v - 1023.5});
      if (beyond > 0) ++outside;
      farthest = std::max(farthest, beyond);
    }
  }
  ASSERT_GT(outside, 0);
  EXPECT_EQ(p.corners_outside, outside);
  EXPECT_NEAR(p.outside_px, farthest, 1e-6);
  EXPECT_FALSE(p.used);
  ASSERT_FALSE(p.warnings.empty());
  EXPECT_NE(p.warnings.front().find("leave the image"), std::string::npos);
  EXPECT_EQ(plan.corners.views.size(), static_cast<size_t>(std::count_if(plan.positions.begin(), plan.positions.end(),
                                                                          [](const PositionPlan& q) { return q.used; })));
}

TEST(CapturePlan, ObliquityOfTheMiddlePlaneIsTheTilt) {
  PlanRequest r = VolumeRequest();
  r.volume.tilt_deg = 30;
  const CapturePlan plan = PlanCapture(r);
  // The camera looks at the volume centre, the middle plane's centre, from 30° off its normal.
  EXPECT_NEAR(plan.positions[2].obliquity_deg, 30, 1e-9);
}

TEST(CapturePlan, WarnsAboutSmallSquaresObliqueViewsAndDefocus) {
  PlanRequest r = VolumeRequest();
  r.target = Chessboard(13, 9, 20);  // 20 mm squares at 3000 mm: 9.3 px
  r.volume.tilt_deg = 65;
  r.sharp_near = 2500;
  r.sharp_far = 3500;
  const CapturePlan plan = PlanCapture(r);
  const auto has = [](const PositionPlan& p, const char* text) {
    return std::any_of(p.warnings.begin(), p.warnings.end(), [&](const std::string& w) { return w.find(text) != std::string::npos; });
  };
  EXPECT_TRUE(has(plan.positions.back(), "12 px"));
  EXPECT_TRUE(has(plan.positions[2], "off its normal"));
  EXPECT_TRUE(has(plan.positions.back(), "depth of field"));
}

struct Spread {
  std::vector<double> parameter_sd;  // per plan.sigmas entry that is a lens parameter
  double point_major_sd = 0;         // of the projected test point (with poses)
};

// Refines the planned corners with N fresh noise draws from the true camera and poses; returns
// the sample standard deviations of the lens parameters and the major axis of the projected test
// point's scatter (through the refined intrinsics and pose: the with-poses uncertainty).
Spread MonteCarlo(const CapturePlan& plan, const RefineOptions& options, int n, const Eigen::Vector3d& test_point) {
  const size_t np = LensModelParamNames(plan.prediction.model).size();
  std::vector<Eigen::VectorXd> params;
  std::vector<Eigen::Vector2d> pixels;
  for (int trial = 0; trial < n; ++trial) {
    Correspondences c = plan.corners;
    const CounterRng rng(1000 + trial, 0);
    uint64_t index = 0;
    for (View& v : c.views) {
      for (Observation& o : v.observations) {
        const auto z = rng.Normal2(index++, 0);
        o.pixel += plan.request.pixel_sigma * Eigen::Vector2d(z[0], z[1]);
      }
    }
    const Refinement fit = Refine(c, plan.request.camera, plan.poses, options);
    EXPECT_EQ(fit.status, RefineStatus::kConverged) << fit.message;
    params.push_back(Eigen::Map<const Eigen::VectorXd>(fit.camera.params.data(), static_cast<Eigen::Index>(np)));
    if (plan.request.rig == Rig::kVolume) pixels.push_back(*fit.camera.Project(fit.poses.front() * test_point));
  }
  Spread s;
  const auto names = LensModelParamNames(plan.prediction.model);
  for (const ParameterSigma& sigma : plan.sigmas) {
    const auto at = std::find(names.begin(), names.end(), sigma.name);
    if (at == names.end()) continue;
    const auto k = at - names.begin();
    double mean = 0, sq = 0;
    for (const Eigen::VectorXd& p : params) mean += p[k] / n;
    for (const Eigen::VectorXd& p : params) sq += (p[k] - mean) * (p[k] - mean);
    s.parameter_sd.push_back(std::sqrt(sq / (n - 1)));
  }
  if (!pixels.empty()) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const Eigen::Vector2d& q : pixels) mean += q / n;
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (const Eigen::Vector2d& q : pixels) cov += (q - mean) * (q - mean).transpose() / (n - 1);
    s.point_major_sd = std::sqrt(Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(cov).eigenvalues()(1));
  }
  return s;
}

// The sample σ of N Gaussian draws has relative standard error ≈ 1/√(2(N − 1)): 0.050 for
// N = 200. A ratio within 4 standard errors (0.2) of 1 fails by chance with probability < 1e-4
// per parameter; a wrong information matrix (a missing pose, a wrong σ) is off by far more.
constexpr int kTrials = 200;
const double kTolerance = 4 / std::sqrt(2.0 * (kTrials - 1));

// Compares every lens parameter's predicted σ with its Monte Carlo spread (in plan.sigmas' order,
// as MonteCarlo lists them); returns how many were compared.
size_t ExpectLensSigmasMatch(const CapturePlan& plan, const Spread& mc) {
  const auto names = LensModelParamNames(plan.prediction.model);
  size_t k = 0;
  for (const ParameterSigma& s : plan.sigmas) {
    if (std::find(names.begin(), names.end(), s.name) == names.end()) continue;  // a pose tangent
    if (k >= mc.parameter_sd.size()) break;
    EXPECT_NEAR(mc.parameter_sd[k] / s.sigma, 1, kTolerance) << s.name << ": predicted " << s.sigma << ", Monte Carlo " << mc.parameter_sd[k];
    ++k;
  }
  EXPECT_EQ(k, mc.parameter_sd.size());
  return k;
}

TEST(CapturePlan, VolumePredictionMatchesTheMonteCarloSpreadOfRefinements) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  PlanRequest r = VolumeRequest();
  r.pixel_sigma = 0.3;
  r.test_points = {{"Left", Eigen::Vector3d(-1040, 0, 1000), std::nullopt}};
  const CapturePlan plan = PlanCapture(r);
  ASSERT_TRUE(plan.prediction.observable) << plan.prediction.message;
  const Spread mc = MonteCarlo(plan, r.options, kTrials, r.test_points.front().point_in_world);
  EXPECT_EQ(ExpectLensSigmasMatch(plan, mc), 8u);  // fx fy cx cy k1 k2 p1 p2
  ASSERT_EQ(plan.points.size(), 1u);
  EXPECT_NEAR(mc.point_major_sd / plan.points.front().with_poses_px, 1, kTolerance);
}

TEST(CapturePlan, PlanarViewsPredictionMatchesTheMonteCarloSpreadOfRefinements) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  PlanRequest r = VolumeRequest();
  r.rig = Rig::kPlanarViews;
  r.target = Chessboard(10, 7, 30);
  r.views.num_views = 12;
  r.views.distance = 700;
  r.pixel_sigma = 0.3;
  r.options.free_distortion = {"k1", "k2"};
  const CapturePlan plan = PlanCapture(r);
  ASSERT_TRUE(plan.prediction.observable) << plan.prediction.message;
  ASSERT_GE(plan.corners.views.size(), 8u);
  const Spread mc = MonteCarlo(plan, r.options, kTrials, Eigen::Vector3d::Zero());
  EXPECT_EQ(ExpectLensSigmasMatch(plan, mc), 6u);  // fx fy cx cy k1 k2
}

// One plane under calib-tsai (docs/math/uncertainty.md#one-plane): the plan predicts the solve
// calib-tsai runs by default, the principal point under its prior. That posterior σ is the spread
// of the error when the true principal point is itself drawn from the prior, so each trial draws
// one, renders the plane through it with fresh noise and runs calib-tsai's whole pipeline.
TEST(CapturePlan, TsaiOnOnePlanePredictsTheSpreadUnderItsPrior) {
  VSTCAL_STATISTICAL_TEST_RELEASE_ONLY();
  PlanRequest r = VolumeRequest();
  r.volume.far = 0;
  r.volume.tilt_deg = 30;  // a fronto-parallel plane cannot tell f from the distance
  r.method = "tsai";
  r.pixel_sigma = 0.3;
  const CapturePlan plan = PlanCapture(r);
  ASSERT_TRUE(plan.prediction.observable) << plan.prediction.message;
  ASSERT_EQ(plan.corners.views.size(), 1u);
  const double prior_sigma = 0.05 * std::hypot(1280.0, 1024.0);
  std::optional<double> predicted[2];
  for (const ParameterSigma& s : plan.sigmas) {
    if (s.name == "cx") predicted[0] = s.sigma;
    if (s.name == "cy") predicted[1] = s.sigma;
  }
  ASSERT_TRUE(predicted[0] && predicted[1]) << "the prior's principal point is estimated, so it has a sigma";
  // A plane tilted about one axis tells the principal point's other coordinate (here cy, to a few
  // px) and leaves the first to the prior: a posterior σ never exceeds the prior's.
  for (const std::optional<double>& p : predicted) EXPECT_LE(*p, prior_sigma * (1 + 1e-9));
  EXPECT_NEAR(*predicted[0], prior_sigma, 0.01 * prior_sigma);
  EXPECT_LT(*predicted[1], 0.2 * prior_sigma);
  std::vector<Eigen::Vector2d> errors;
  for (int trial = 0; trial < kTrials; ++trial) {
    const CounterRng rng(5000 + trial, 0);
    uint64_t index = 0;
    const auto shift = rng.Normal2(index++, 0);
    Camera truth = r.camera;
    truth.params[intrinsic::kCx] += prior_sigma * shift[0];
    truth.params[intrinsic::kCy] += prior_sigma * shift[1];
    Correspondences c = plan.corners;
    for (Observation& o : c.views.front().observations) {
      const auto z = rng.Normal2(index++, 0);
      o.pixel = *truth.Project(plan.camera_from_world * o.point) + r.pixel_sigma * Eigen::Vector2d(z[0], z[1]);
    }
    const CalibrationResult fit = Calibrate(c, CalibrationOptions{});
    ASSERT_EQ(fit.exit_code, ExitCode::kOk) << fit.message;
    errors.emplace_back(fit.camera.camera.params[intrinsic::kCx] - truth.params[intrinsic::kCx],
                        fit.camera.camera.params[intrinsic::kCy] - truth.params[intrinsic::kCy]);
  }
  for (int k = 0; k < 2; ++k) {
    double sq = 0;
    for (const Eigen::Vector2d& e : errors) sq += e[k] * e[k];
    const double rms = std::sqrt(sq / kTrials);
    EXPECT_NEAR(rms / *predicted[k], 1, kTolerance) << (k ? "cy" : "cx") << ": predicted " << *predicted[k] << ", spread " << rms;
  }
}

TEST(CapturePlan, TsaiOnOnePlaneHoldsThePrincipalPointWhereTheOptionsHoldIt) {
  PlanRequest r = VolumeRequest();
  r.volume.far = 0;
  r.volume.tilt_deg = 30;
  r.method = "tsai";
  r.options.free_principal_point = false;
  const CapturePlan plan = PlanCapture(r);
  ASSERT_TRUE(plan.prediction.observable) << plan.prediction.message;
  std::vector<std::string> names;
  for (const ParameterSigma& s : plan.sigmas) names.push_back(s.name);
  EXPECT_EQ(std::count(names.begin(), names.end(), "cx"), 0);
  r.options.free_principal_point = true;
  r.method = "dlt";  // one plane with everything free: the principal point is not determined
  EXPECT_FALSE(PlanCapture(r).prediction.observable);
}

TEST(CapturePlan, RefusesImpossibleRequests) {
  PlanRequest r = VolumeRequest();
  r.pixel_sigma = 0;
  EXPECT_THROW(PlanCapture(r), InputError);
  r = VolumeRequest();
  r.volume.interval = -1;
  EXPECT_THROW(PlanCapture(r), InputError);
  r = VolumeRequest();
  r.sharp_near = 3000;
  r.sharp_far = 2000;
  EXPECT_THROW(PlanCapture(r), InputError);
}

}  // namespace
}  // namespace vstcal
