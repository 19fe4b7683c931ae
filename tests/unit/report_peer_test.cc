// reproj-report's per-point numbers beside OpenCV run in the same test: residuals against
// cv::projectPoints through a distorted lens, and the angular and lateral errors against the
// measured pixel's ray from cv::undistortPoints (not vstcal's Unproject).
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/calib3d.hpp>

#include "support/scenes.h"
#include "vstcal/report/reprojection_report.h"

namespace vstcal {
namespace {

TEST(ReprojReportPeer, ResidualsAndRaysAgreeWithOpenCv) {
  const Camera camera = testing::DistortedWideCamera();  // k1 −0.171, k2 0.028, p1, p2: OpenCV's model
  std::vector<cv::Point3d> points;
  for (const Eigen::Vector3d& p : testing::PointsInFront(200, 5, 0.6, 0.35)) points.emplace_back(1000 * p.x(), 1000 * p.y(), 1000 * p.z());
  const Eigen::Matrix3d K = camera.K();
  const cv::Matx33d cv_K(K(0, 0), 0, K(0, 2), 0, K(1, 1), K(1, 2), 0, 0, 1);
  const std::span<const double> d = camera.distortion();
  const std::vector<double> cv_d(d.begin(), d.end());
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv_K, cv_d, projected);

  // Measured pixels: OpenCV's projections moved by up to 0.4 px in a fixed pattern.
  Correspondences c;
  c.image_size = camera.image_size;
  View view;
  view.name = "all";
  std::vector<cv::Point2d> measured;
  for (size_t i = 0; i < points.size(); ++i) {
    measured.emplace_back(projected[i].x + 0.4 * std::sin(0.7 * i), projected[i].y + 0.3 * std::cos(1.3 * i));
    view.observations.push_back({{points[i].x, points[i].y, points[i].z}, {measured[i].x, measured[i].y}, 1.0});
  }
  c.views.push_back(view);
  ReportCamera rc;
  rc.file = "wide.json";
  rc.camera.camera = camera;
  rc.camera.camera_from_world = Rigid3d();
  const CameraReport report = BuildReprojReport({&rc, 1}, c, "corr.json").cameras.at(0);

  const cv::TermCriteria precise(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-15);
  std::vector<cv::Point2d> normalized;
  cv::undistortPoints(measured, normalized, cv_K, cv_d, cv::noArray(), cv::noArray(), precise);
  for (size_t i = 0; i < points.size(); ++i) {
    const PointError& e = report.views[0].points[i];
    ASSERT_EQ(e.excluded, Exclusion::kNone) << i;
    EXPECT_NEAR(e.predicted->x(), projected[i].x, 1e-9) << i;
    EXPECT_NEAR(e.predicted->y(), projected[i].y, 1e-9) << i;
    const Eigen::Vector3d ray(normalized[i].x, normalized[i].y, 1), x(points[i].x, points[i].y, points[i].z);
    const double theta = std::atan2(ray.cross(x).norm(), ray.dot(x));
    EXPECT_NEAR(e.angular_rad, theta, 1e-10) << i;
    EXPECT_NEAR(e.lateral, x.norm() * std::tan(theta), 1e-9 * x.norm()) << i;
  }
}

}  // namespace
}  // namespace vstcal
