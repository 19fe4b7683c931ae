// reprojection_report: residuals, lateral and angular registration error in closed form
// (issue 13 item 7), exclusions counted, cameras that do not go with the correspondences refused,
// and residuals normalized by a refined camera's own covariance consistent with the noise drawn.
#include <gtest/gtest.h>

#include <cmath>

#include "support/scenes.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/pages/charts.h"
#include "vstcal/report/reprojection_report.h"

namespace vstcal {
namespace {

constexpr double kF = 500, kCx = 319.5, kCy = 239.5;

Camera Pinhole() {
  Eigen::Matrix3d K;
  K << kF, 0, kCx, 0, kF, kCy, 0, 0, 1;
  return Camera::FromK(K, {640, 480});
}

Eigen::Vector2d PixelOf(const Eigen::Vector3d& p) { return {kCx + kF * p.x() / p.z(), kCy + kF * p.y() / p.z()}; }

// A 3×3 grid on each of three planes 1000, 1200, 1400 mm in front of a camera at the world origin,
// seen by the true camera (identity pose), each pixel moved by `shift`.
Correspondences Volume(const Eigen::Vector2d& shift) {
  Correspondences c;
  c.image_size = {640, 480};
  for (int k = 0; k < 3; ++k) {
    View v;
    v.name = "plane-" + std::to_string(k);
    for (int i = -1; i <= 1; ++i)
      for (int j = -1; j <= 1; ++j) {
        const Eigen::Vector3d p(200.0 * i, 150.0 * j, 1000.0 + 200 * k);
        v.observations.push_back({p, PixelOf(p) + shift, 1.0});
      }
    c.views.push_back(v);
  }
  return c;
}

ReportCamera Model(const Rigid3d& camera_from_world) {
  ReportCamera rc;
  rc.file = "model.json";
  rc.camera.camera = Pinhole();
  rc.camera.camera_from_world = camera_from_world;
  return rc;
}

// The test-point chart colours each bar by its side of the measured volume: a point of a
// calibration whose points span no volume is neither inside (blue) nor outside (red) but grey.
TEST(ReprojReportCharts, TestPointBarsColouredByTheirSideOfTheVolume) {
  ReprojReport r;
  r.cameras.resize(1);
  for (const auto& [name, side] : {std::pair{"a", std::optional<bool>(true)}, std::pair{"b", std::optional<bool>(false)},
                                   std::pair{"c", std::optional<bool>()}}) {
    TestPointReport t;
    t.name = name;
    t.error.error_px = 1.5;
    t.error.lateral = 0.25;
    t.inside_volume = side;
    r.cameras[0].test_points.push_back(t);
  }
  const std::string script = TestPointsScript(r);
  EXPECT_NE(script.find("\"0:a (inside)\" 1.5 0.25 1\n"), std::string::npos) << script;
  EXPECT_NE(script.find("\"0:b (outside)\" 1.5 0.25 2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("\"0:c (no hull)\" 1.5 0.25 0\n"), std::string::npos) << script;
  EXPECT_NE(script.find("($4 == 1 ? 0x1f77b4 : $4 == 2 ? 0xd62728 : 0x7f7f7f)"), std::string::npos) << script;
}

TEST(ReprojReport, ShiftedPixelsGiveTheirLateralErrorAtEachDepth) {
  const Eigen::Vector2d shift(3, 4);  // |r| = 5 px everywhere
  const ReportCamera rc = Model(Rigid3d());
  const ReprojReport report = BuildReprojReport({&rc, 1}, Volume(shift), "corr.json");
  const CameraReport& cam = report.cameras.at(0);
  ASSERT_TRUE(cam.overall.error_px);
  EXPECT_EQ(cam.overall.error_px->n, 27u);
  EXPECT_NEAR(cam.overall.error_px->max, 5, 1e-9);
  EXPECT_NEAR(cam.overall.error_px->median, 5, 1e-9);
  for (const ViewReport& v : cam.views) {
    for (size_t i = 0; i < v.points.size(); ++i) {
      const PointError& e = v.points[i];
      ASSERT_EQ(e.excluded, Exclusion::kNone);
      // Independently: the angle between the point's direction and the measured pixel's ray, and
      // the ray's offset in the plane through the point normal to the sight line, d·tan θ.
      const Eigen::Vector3d ray((e.measured.x() - kCx) / kF, (e.measured.y() - kCy) / kF, 1);
      const Eigen::Vector3d p = Eigen::Vector3d((e.measured.x() - shift.x() - kCx) / kF,
                                                (e.measured.y() - shift.y() - kCy) / kF, 1) * 1.0;
      const double theta = std::acos(ray.normalized().dot(p.normalized()));
      EXPECT_NEAR(e.angular_rad, theta, 1e-9);
      EXPECT_NEAR(e.lateral, e.depth * std::tan(theta), 1e-9 * e.depth);
    }
  }
  // On the axis of the middle plane (X = Y = 0, Z = 1200): θ = atan(5/f), lateral = Z·5/f.
  const PointError& axis = cam.views[1].points[4];
  EXPECT_NEAR(axis.depth, 1200, 1e-12);
  EXPECT_NEAR(axis.angular_rad, std::atan(5 / kF), 1e-15);
  EXPECT_NEAR(axis.lateral, 1200 * 5 / kF, 1e-10);
  EXPECT_EQ(report.volume.status, "ok");
}

TEST(ReprojReport, RotationAboutTheCentreGivesDTanTheta) {
  // The model's pose is rotated by Δθ about y; test points in the x–z plane are seen Δθ away.
  const double dtheta = 0.01;
  Correspondences c = Volume({0, 0});
  const std::vector<Eigen::Vector3d> tests = {{0, 0, 800}, {150, 0, 1300}, {-300, 0, 2500}};
  for (size_t i = 0; i < tests.size(); ++i) c.test_points.push_back({"t" + std::to_string(i), tests[i], PixelOf(tests[i])});
  const ReportCamera rc = Model(Rigid3d{RotationFromRotvec(Eigen::Vector3d(0, dtheta, 0)), Eigen::Vector3d::Zero()});
  const ReprojReport report = BuildReprojReport({&rc, 1}, c, "corr.json");
  const CameraReport& cam = report.cameras.at(0);
  ASSERT_EQ(cam.test_points.size(), 3u);
  for (size_t i = 0; i < tests.size(); ++i) {
    const PointError& e = cam.test_points[i].error;
    ASSERT_EQ(e.excluded, Exclusion::kNone);
    EXPECT_NEAR(e.angular_rad, dtheta, 1e-12);
    EXPECT_NEAR(e.lateral, tests[i].norm() * std::tan(dtheta), 1e-9);
  }
  EXPECT_TRUE(*cam.test_points[1].inside_volume);   // (150, 0, 1300) lies within the planes' box
  EXPECT_FALSE(*cam.test_points[0].inside_volume);  // in front of the first plane
  EXPECT_FALSE(*cam.test_points[2].inside_volume);  // beyond the last
  ASSERT_TRUE(cam.test_inside.lateral && cam.test_outside.lateral);
  EXPECT_EQ(cam.test_inside.lateral->n, 1u);
  EXPECT_EQ(cam.test_outside.lateral->n, 2u);
}

TEST(ReprojReport, TranslationAcrossTheSightLineGivesDeltaTAtAnyDepth) {
  // The model's camera is displaced by a across the line of sight of on-axis test points: the
  // lateral error is a (to (a/d)²) and the angular error a/d, at every depth d.
  const double a = 1.0;
  Correspondences c = Volume({0, 0});
  for (const double d : {500.0, 1000.0, 4000.0}) c.test_points.push_back({"d", {0, 0, d}, PixelOf({0, 0, d})});
  const ReportCamera rc = Model(Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(a, 0, 0)});
  const ReprojReport report = BuildReprojReport({&rc, 1}, c, "corr.json");
  for (const TestPointReport& t : report.cameras.at(0).test_points) {
    const double d = t.point_in_world.z();
    // Exactly: X_c = (a, 0, d) and the measured ray is the axis: θ = atan(a/d), lateral = |X_c|·a/d.
    EXPECT_NEAR(t.error.angular_rad, std::atan(a / d), 1e-15);
    EXPECT_NEAR(t.error.lateral, std::hypot(a, d) * a / d, 1e-12);
    EXPECT_NEAR(t.error.lateral, a, a * a / (d * d));
  }
}

TEST(ReprojReport, PointsBehindTheCameraAreCountedNotMeasured) {
  Correspondences c = Volume({1, 0});
  c.views[0].observations[0].point = {0, 0, -500};
  const ReportCamera rc = Model(Rigid3d());
  const ReprojReport report = BuildReprojReport({&rc, 1}, c, "corr.json");
  const CameraReport& cam = report.cameras.at(0);
  EXPECT_EQ(cam.n_behind_camera, 1u);
  EXPECT_EQ(cam.views[0].points[0].excluded, Exclusion::kBehindCamera);
  EXPECT_EQ(cam.overall.error_px->n, 26u);
  EXPECT_EQ(cam.views[0].error_px->n, 8u);
}

TEST(ReprojReport, CamerasThatDoNotGoWithTheCorrespondencesAreRefused) {
  ReportCamera rc = Model(Rigid3d());
  rc.camera.camera.image_size = {1280, 720};
  try {
    BuildReprojReport({&rc, 1}, Volume({0, 0}), "corr.json");
    FAIL() << "accepted another image size";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("model.json: image_size: 1280x720 differs from corr.json's 640x480"),
              std::string::npos)
        << e.what();
  }
  rc = Model(Rigid3d());
  rc.camera.length_unit = LengthUnit::kMetre;
  EXPECT_THROW(BuildReprojReport({&rc, 1}, Volume({0, 0}), "corr.json"), InputError);
  rc = Model(Rigid3d());
  rc.camera.camera_from_world.reset();
  EXPECT_THROW(BuildReprojReport({&rc, 1}, Volume({0, 0}), "corr.json"), InputError);
}

TEST(ReprojReport, TwoCamerasSideBySide) {
  const ReportCamera cams[2] = {Model(Rigid3d()), Model(Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, 0)})};
  ReportCamera shifted = cams[1];
  Eigen::Matrix3d K = shifted.camera.camera.K();
  K(0, 2) += 2;  // the second camera's principal point is 2 px to the right: every prediction moves 2 px
  shifted.camera.camera = Camera::FromK(K, {640, 480});
  const ReportCamera both[2] = {cams[0], shifted};
  const ReprojReport report = BuildReprojReport(both, Volume({0, 0}), "corr.json");
  ASSERT_EQ(report.differences.size(), 1u);
  const CameraDifference& d = report.differences[0];
  EXPECT_EQ(d.camera, 1u);
  ASSERT_TRUE(d.prediction_shift_px);
  EXPECT_NEAR(d.prediction_shift_px->mean, 2, 1e-9);
  EXPECT_NEAR(d.prediction_shift_px->max, 2, 1e-9);
  EXPECT_NEAR(*d.rms_change_px, 2, 1e-9);  // the first camera reprojects exactly, the second 2 px off
}

TEST(ReprojReport, NormalizedResidualsOfARefinedCameraMatchItsCovariance) {
  // Refined with its covariance on 120 points with σ = 0.5 px: the residuals normalized by
  // σ̂²I − Σ_p have E[z²] = 2, so chi2_per_dof ≈ 1; the same residuals against a σ twice too
  // large come out ≈ 1/4 (a report that cannot tell would not see an overconfident camera).
  const testing::Scene scene = testing::RandomVolumeScene(120, 0.5, 31);
  Correspondences c;
  c.image_size = scene.camera.image_size;
  c.views.push_back({"all", "", std::nullopt, scene.observations, std::nullopt});
  CalibrationOptions options;
  options.start = CalibrationOptions::Start::kDlt;
  const CalibrationResult result = Calibrate(c, options);
  ASSERT_EQ(result.exit_code, ExitCode::kOk) << result.message;
  ASSERT_TRUE(result.camera.covariance && result.refinement);
  ReportCamera rc{"refined.json", result.camera, result.refinement->sigma_px};
  const CameraReport cam = BuildReprojReport({&rc, 1}, c, "corr.json").cameras.at(0);
  ASSERT_TRUE(cam.chi2_per_dof) << cam.normalization;
  EXPECT_NEAR(*cam.chi2_per_dof, 1.0, 0.05);
  EXPECT_EQ(cam.normalized->n, 120u);
  // The projection-uncertainty map: at every cell's centre, at the points' median z (sorted here).
  std::vector<double> z;
  for (const Observation& o : scene.observations) z.push_back((*result.camera.camera_from_world * o.point).z());
  std::sort(z.begin(), z.end());
  const double median_z = (z[59] + z[60]) / 2;
  EXPECT_NEAR(cam.uncertainty_depth, median_z, 1e-9 * median_z);
  ASSERT_EQ(cam.uncertainty_px.size(), 48u);
  const ImageGrid grid{c.image_size, 8, 6};
  for (int row = 0; row < 6; ++row) {
    for (int col = 0; col < 8; ++col) {
      const Eigen::Vector2d px(-0.5 + 1280 * (col + 0.5) / 8, -0.5 + 1024 * (row + 0.5) / 6);
      EXPECT_EQ(grid.CellCentre(col, row), px);
      const auto e = ProjectionUncertaintyAtPixel(result.camera, px, cam.uncertainty_depth);
      ASSERT_TRUE(e && cam.uncertainty_px[row * 8 + col]);
      EXPECT_EQ(*cam.uncertainty_px[row * 8 + col], e->sigma_major_px);
    }
  }
  rc.sigma_px = 2 * *rc.sigma_px;
  const CameraReport doubled = BuildReprojReport({&rc, 1}, c, "corr.json").cameras.at(0);
  EXPECT_NEAR(*doubled.chi2_per_dof, 0.25, 0.03);
  // Without a covariance nothing is normalized, and the report says why.
  rc.camera.covariance.reset();
  const CameraReport none = BuildReprojReport({&rc, 1}, c, "corr.json").cameras.at(0);
  EXPECT_FALSE(none.chi2_per_dof);
  EXPECT_NE(none.normalization.find("no covariance"), std::string::npos);
  EXPECT_TRUE(none.uncertainty_px.empty());
}

}  // namespace
}  // namespace vstcal
