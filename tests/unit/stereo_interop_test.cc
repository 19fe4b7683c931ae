// A rig exported to OpenCV and mrcal, checked by the peers themselves: cv::FileStorage reads our
// stereo YAML, OpenCV's own projection, undistortion, epipolar lines and reprojection agree with
// the rig; libmrcal reads the two .cameramodel files and projects points of the shared reference
// frame (the left camera) as our cameras do; and the files read back into the same rig.
#include <gtest/gtest.h>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/error_of.h"
#include "support/mrcal.h"
#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/stereo/stereo_peer_formats.h"
#include "vstcal/scene/epipolar.h"
#include "vstcal/stereo/rectify.h"

namespace vstcal {
namespace {

using testing::ErrorOf;
using testing::PointsInFront;
using testing::ZedLikeRig;

const Provenance kProvenance{"stereo_interop_test", {}, std::nullopt};

// Points 0.3 to 4.3 m in front of the left camera (mm) that both cameras see.
std::vector<Eigen::Vector3d> SharedPoints(const StereoRig& rig) {
  std::vector<Eigen::Vector3d> out;
  for (const Eigen::Vector3d& p : PointsInFront(400, 5, 0.6, 0.4)) {
    const Eigen::Vector3d x = 1000 * p;
    const auto l = rig.left.camera.Project(x), r = rig.right.camera.Project(rig.right_from_left * x);
    if (l && r && rig.left.camera.InImage(*l) && rig.right.camera.InImage(*r)) out.push_back(x);
  }
  return out;
}

cv::Mat Read(const cv::FileStorage& fs, const char* key) {
  cv::Mat m;
  fs[key] >> m;
  return m;
}

template <int R, int C>
Eigen::Matrix<double, R, C> ToEigen(const cv::Mat& m) {
  Eigen::Matrix<double, R, C> e;
  cv::cv2eigen(m, e);
  return e;
}

TEST(StereoInterop, OpenCvReadsTheYamlAndAgreesWithTheRig) {
  StereoRig rig = ZedLikeRig();
  rig.rectification = Rectify(rig, {0.0, true}, "rig");
  const ExportedCamera yaml = OpenCvStereoYamlText(rig, "rig.json", kProvenance);
  const cv::FileStorage fs(yaml.text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 1280);
  EXPECT_EQ(static_cast<int>(fs["image_height"]), 720);
  const cv::Mat M1 = Read(fs, "M1"), D1 = Read(fs, "D1"), M2 = Read(fs, "M2"), D2 = Read(fs, "D2"), R = Read(fs, "R"),
                T = Read(fs, "T"), E = Read(fs, "E"), F = Read(fs, "F");
  // Bit for bit: cv::FileStorage prints 17 significant digits.
  EXPECT_EQ((ToEigen<3, 3>(M1)), rig.left.camera.K());
  EXPECT_EQ((ToEigen<3, 3>(R)), rig.right_from_left.R);
  EXPECT_EQ((ToEigen<3, 1>(T)), rig.right_from_left.t);
  EXPECT_EQ((ToEigen<3, 3>(F)), FundamentalMatrix(rig));

  const std::vector<Eigen::Vector3d> points = SharedPoints(rig);
  ASSERT_GT(points.size(), 100u);
  std::vector<cv::Point3d> object;
  for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
  // OpenCV projects into the right camera through R, T: the pixels are ours.
  std::vector<cv::Point2d> left_px, right_px;
  cv::Mat rvec;
  cv::Rodrigues(R, rvec);
  cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), M1, D1, left_px);
  cv::projectPoints(object, rvec, T, M2, D2, right_px);
  double worst = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d l = *rig.left.camera.Project(points[i]);
    const Eigen::Vector2d r = *rig.right.camera.Project(rig.right_from_left * points[i]);
    worst = std::max({worst, (l - Eigen::Vector2d(left_px[i].x, left_px[i].y)).norm(),
                      (r - Eigen::Vector2d(right_px[i].x, right_px[i].y)).norm()});
  }
  EXPECT_LT(worst, 1e-8);

  // Epipolar geometry through OpenCV: pixels undistorted by cv::undistortPoints satisfy
  // x_rᵀ E x_l = 0 (normalized) and lie on cv::computeCorrespondEpilines' lines of F (pixels).
  // (OpenCV's default is 5 fixed-point iterations; 100 reach its convergence.)
  const cv::TermCriteria precise(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-15);
  std::vector<cv::Point2d> left_n, right_n, left_u, right_u;
  cv::undistortPoints(left_px, left_n, M1, D1, cv::noArray(), cv::noArray(), precise);
  cv::undistortPoints(right_px, right_n, M2, D2, cv::noArray(), cv::noArray(), precise);
  cv::undistortPoints(left_px, left_u, M1, D1, cv::noArray(), M1, precise);
  cv::undistortPoints(right_px, right_u, M2, D2, cv::noArray(), M2, precise);
  std::vector<cv::Vec3d> lines;
  cv::computeCorrespondEpilines(left_u, 1, F, lines);
  const Eigen::Matrix3d Ee = ToEigen<3, 3>(E);
  double worst_e = 0, worst_line = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d xl(left_n[i].x, left_n[i].y, 1), xr(right_n[i].x, right_n[i].y, 1);
    worst_e = std::max(worst_e, std::abs(xr.dot(Ee * xl)) / rig.baseline());
    worst_line = std::max(worst_line, std::abs(lines[i][0] * right_u[i].x + lines[i][1] * right_u[i].y + lines[i][2]));
  }
  EXPECT_LT(worst_e, 1e-9);      // OpenCV's undistortion iterates to about 1e-10
  EXPECT_LT(worst_line, 1e-6);   // px from the epipolar line

  // Rectification through OpenCV: undistorted and rectified with R1, P1 and R2, P2, a point's two
  // pixels share a row, and Q reprojects them to the point in the rectified left frame.
  const cv::Mat R1 = Read(fs, "R1"), R2 = Read(fs, "R2"), P1 = Read(fs, "P1"), P2 = Read(fs, "P2"), Q = Read(fs, "Q");
  std::vector<cv::Point2d> left_r, right_r;
  cv::undistortPoints(left_px, left_r, M1, D1, R1, P1, precise);
  cv::undistortPoints(right_px, right_r, M2, D2, R2, P2, precise);
  std::vector<cv::Point3d> disparity;
  for (size_t i = 0; i < points.size(); ++i) disparity.emplace_back(left_r[i].x, left_r[i].y, left_r[i].x - right_r[i].x);
  std::vector<cv::Point3d> reprojected;
  cv::perspectiveTransform(disparity, reprojected, Q);
  const Eigen::Matrix3d R1e = ToEigen<3, 3>(R1);
  double worst_row = 0, worst_point = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    worst_row = std::max(worst_row, std::abs(left_r[i].y - right_r[i].y));
    const Eigen::Vector3d truth = R1e * points[i];
    worst_point = std::max(worst_point, (Eigen::Vector3d(reprojected[i].x, reprojected[i].y, reprojected[i].z) - truth).norm() / truth.norm());
  }
  EXPECT_LT(worst_row, 1e-6);
  EXPECT_LT(worst_point, 1e-8);
  const cv::Mat roi = Read(fs, "validRoi2");
  for (int i = 0; i < 4; ++i) EXPECT_EQ(roi.at<int>(0, i), rig.rectification->valid_roi_right[i]);
}

TEST(StereoInterop, YamlRefusesWhatOpenCvCannotHold) {
  StereoRig rig = ZedLikeRig();
  rig.right.camera.image_size = {1920, 1080};
  EXPECT_NE(ErrorOf([&] { OpenCvStereoYamlText(rig, "rig.json", kProvenance); })
                .find("rig.json: right.image_size: differs from the left camera's (1280×720)"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { Rectify(rig, {}, "rig.json"); }).find("rig.json: right.image_size: 1920×1080"), std::string::npos);
  rig = ZedLikeRig();
  rig.left.camera.params[4] = 0.5;
  EXPECT_NE(ErrorOf([&] { OpenCvStereoYamlText(rig, "rig.json", kProvenance); })
                .find("rig.json: left: K[0][1]: the camera has skew 0.5 px"),
            std::string::npos);
}

struct MrcalModelDeleter {
  void operator()(mrcal_cameramodel_t* m) const { mrcal_free_cameramodel(&m); }
};
using MrcalModel = std::unique_ptr<mrcal_cameramodel_t, MrcalModelDeleter>;

TEST(StereoInterop, LibmrcalReadsThePairAndProjectsFromTheLeftFrame) {
  for (const bool distorted : {false, true}) {
    const StereoRig rig = ZedLikeRig(distorted);
    const auto [left, right] = MrcalStereoTexts(rig, "rig.json", {}, kProvenance);
    const MrcalModel ml(mrcal_read_cameramodel_string(left.text.c_str(), static_cast<int>(left.text.size())));
    const MrcalModel mr(mrcal_read_cameramodel_string(right.text.c_str(), static_cast<int>(right.text.size())));
    ASSERT_NE(ml, nullptr);
    ASSERT_NE(mr, nullptr);
    for (int i = 0; i < 6; ++i) EXPECT_EQ(ml->rt_cam_ref[i], 0.0);  // the reference frame is the left camera
    const std::vector<Eigen::Vector3d> points = SharedPoints(rig);
    double worst = 0;
    for (const auto& [model, camera, pose] :
         {std::tuple{ml.get(), &rig.left.camera, Rigid3d::Identity()}, std::tuple{mr.get(), &rig.right.camera, rig.right_from_left}}) {
      std::vector<mrcal_point3_t> p(points.size());
      for (size_t i = 0; i < points.size(); ++i) mrcal_transform_point_rt(p[i].xyz, nullptr, nullptr, model->rt_cam_ref, points[i].data());
      std::vector<mrcal_point2_t> q(points.size());
      ASSERT_TRUE(mrcal_project(q.data(), nullptr, nullptr, p.data(), static_cast<int>(p.size()), &model->lensmodel, model->intrinsics));
      for (size_t i = 0; i < points.size(); ++i) {
        worst = std::max(worst, (*camera->Project(pose * points[i]) - Eigen::Vector2d(q[i].x, q[i].y)).norm());
      }
    }
    EXPECT_LT(worst, 1e-9);
    // Our reader takes them back: the right camera's extrinsics are right_from_left.
    const ImportedCamera back = MrcalCameramodelFromText(right.text, "right.cameramodel", std::nullopt);
    EXPECT_EQ(back.camera.camera.params, rig.right.camera.params);
    EXPECT_LT((back.camera.camera_from_world->R - rig.right_from_left.R).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(back.camera.camera_from_world->t, rig.right_from_left.t);
    EXPECT_EQ(back.camera.length_unit, LengthUnit::kMillimetre);
  }
}

}  // namespace
}  // namespace vstcal
