// The one projection against closed forms and two peer libraries (OpenCV, mrcal), its inverse,
// and its ceres::Jet instantiation.
#include <gtest/gtest.h>

#include <ceres/jet.h>
#include <opencv2/calib3d.hpp>

#include "support/mrcal.h"
#include "support/scenes.h"
#include "vstcal/camera/camera.h"
#include "vstcal/camera/intrinsics.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

// A radial-tangential camera with distortion like a wide consumer lens.
Camera WideCamera(double skew = 0.0) {
  Eigen::Matrix3d K;
  K << 700.5, skew, 641.3, 0, 698.2, 362.9, 0, 0, 1;
  const double d[5] = {-0.171, 0.028, 0.0007, -0.0004, -0.0021};
  return Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, d);
}

// A rational camera with a strongly barrel-distorting wide lens: the denominator keeps the radial
// scaling near 1/(1 + k4 r²) at the edge, as OpenCV's CALIB_RATIONAL_MODEL fits produce.
Camera RationalCamera(double skew = 0.0) {
  Eigen::Matrix3d K;
  K << 702.5, skew, 639.1, 0, 701.2, 361.4, 0, 0, 1;
  const double d[8] = {0.412, -0.083, 0.0006, -0.0003, 0.0042, 0.645, -0.041, 0.0093};
  return Camera::FromK(K, ImageSize{1280, 720}, RationalModel{}, d);
}

TEST(CameraModel, PinholeWithSkewClosedForm) {
  Eigen::Matrix3d K;
  K << 1000, 3.5, 500, 0, 990, 400, 0, 0, 1;
  const Camera c = Camera::FromK(K, ImageSize{1000, 800});
  const Eigen::Vector3d p(0.3, -0.2, 2.0);
  const Eigen::Vector2d px = *c.Project(p);
  EXPECT_DOUBLE_EQ(px.x(), 1000 * 0.15 + 3.5 * -0.1 + 500);
  EXPECT_DOUBLE_EQ(px.y(), 990 * -0.1 + 400);
  EXPECT_EQ(c.K(), K);
}

TEST(CameraModel, BehindTheCameraIsInvalidNotZero) {
  const Camera c = WideCamera();
  EXPECT_FALSE(c.Project(Eigen::Vector3d(0.1, 0.1, -1.0)).has_value());
  EXPECT_FALSE(c.Project(Eigen::Vector3d(0.1, 0.1, 0.0)).has_value());
  double px[2] = {-7, -7};
  const double p[3] = {1, 1, -2};
  EXPECT_FALSE(RadialTangentialModel::Project(c.params.data(), p, px));
  EXPECT_EQ(px[0], -7);  // untouched
}

// Largest pixel distance between our projection and OpenCV's projectPoints with the camera's
// coefficients, in OpenCV's order (OpenCV ignores skew: callers pass skew-free cameras).
double WorstVsOpenCv(const Camera& c, const std::vector<Eigen::Vector3d>& points) {
  std::vector<cv::Point3d> object;
  for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
  const Eigen::Matrix3d K = c.K();
  const cv::Matx33d camera_matrix(K(0, 0), 0, K(0, 2), 0, K(1, 1), K(1, 2), 0, 0, 1);
  const std::vector<double> dist(c.distortion().begin(), c.distortion().end());
  std::vector<cv::Point2d> image;
  cv::projectPoints(object, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera_matrix, dist, image);
  double worst = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2d ours = *c.Project(points[i]);
    worst = std::max(worst, (ours - Eigen::Vector2d(image[i].x, image[i].y)).norm());
  }
  return worst;
}

// The same against mrcal_project: mrcal's intrinsics are fx, fy, cx, cy, then the distortion in
// OpenCV's order (no skew).
double WorstVsMrcal(const Camera& c, mrcal_lensmodel_type_t type, const std::vector<Eigen::Vector3d>& points) {
  std::vector<double> intrinsics = {c.params[0], c.params[1], c.params[2], c.params[3]};
  intrinsics.insert(intrinsics.end(), c.distortion().begin(), c.distortion().end());
  mrcal_lensmodel_t model;
  model.type = type;
  EXPECT_EQ(mrcal_lensmodel_num_params(&model), static_cast<int>(intrinsics.size()));
  std::vector<mrcal_point3_t> p(points.size());
  std::vector<mrcal_point2_t> q(points.size());
  for (size_t i = 0; i < points.size(); ++i) p[i] = {{points[i].x(), points[i].y(), points[i].z()}};
  EXPECT_TRUE(
      mrcal_project(q.data(), nullptr, nullptr, p.data(), static_cast<int>(p.size()), &model, intrinsics.data()));
  double worst = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    worst = std::max(worst, (*c.Project(points[i]) - Eigen::Vector2d(q[i].x, q[i].y)).norm());
  }
  return worst;
}

// Peer 1: OpenCV's projectPoints with the same five coefficients.
TEST(CameraModel, AgreesWithOpenCvProjectPoints) { EXPECT_LT(WorstVsOpenCv(WideCamera(), testing::PointsInFront(1000, 11)), 1e-9); }

// ... and with eight: OpenCV selects its rational model by the vector's length.
TEST(CameraModel, RationalAgreesWithOpenCvProjectPoints) {
  EXPECT_LT(WorstVsOpenCv(RationalCamera(), testing::PointsInFront(1000, 14)), 1e-9);
}

// Peer 2: mrcal_project with LENSMODEL_OPENCV5 (fx, fy, cx, cy, k1, k2, p1, p2, k3).
TEST(CameraModel, AgreesWithMrcalOpenCv5) {
  EXPECT_LT(WorstVsMrcal(WideCamera(), MRCAL_LENSMODEL_OPENCV5, testing::PointsInFront(1000, 12)), 1e-9);
}

// LENSMODEL_OPENCV8: fx, fy, cx, cy, k1, k2, p1, p2, k3, k4, k5, k6.
TEST(CameraModel, RationalAgreesWithMrcalOpenCv8) {
  EXPECT_LT(WorstVsMrcal(RationalCamera(), MRCAL_LENSMODEL_OPENCV8, testing::PointsInFront(1000, 15)), 1e-9);
}

// With k4 = k5 = k6 = 0 the denominator is exactly 1: the rational model is the radial-tangential
// one, bit for bit.
TEST(CameraModel, RationalWithUnitDenominatorIsRadialTangential) {
  const Camera rt = WideCamera();
  std::vector<double> d(rt.distortion().begin(), rt.distortion().end());
  d.insert(d.end(), {0.0, 0.0, 0.0});
  const Camera rational = Camera::FromK(rt.K(), rt.image_size, RationalModel{}, d);
  for (const Eigen::Vector3d& p : testing::PointsInFront(500, 17)) EXPECT_EQ(*rational.Project(p), *rt.Project(p));
}

TEST(CameraModel, UnprojectInvertsProject) {
  for (const Camera& c : {WideCamera(0.0), WideCamera(2.5), Camera::FromK(WideCamera(1.0).K(), ImageSize{1280, 720}),
                          RationalCamera(0.0), RationalCamera(-1.5)}) {
    for (const Eigen::Vector3d& p : testing::PointsInFront(500, 13)) {
      const Eigen::Vector2d px = *c.Project(p);
      const auto ray = c.Unproject(px);
      ASSERT_TRUE(ray.has_value()) << LensModelName(c.model) << " at " << px.transpose();
      EXPECT_NEAR(ray->z(), 1.0, 0);
      EXPECT_LT((*ray - p / p.z()).norm(), 1e-12) << px.transpose();
    }
  }
}

// Beyond the radius where radial distortion folds back, there is no unique ray.
TEST(CameraModel, UnprojectRefusesTheFoldOverRegion) {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  const double strong_barrel[5] = {-0.5, 0, 0, 0, 0};  // r_d = r(1 − 0.5 r²) peaks at r = √(2/3)
  const Camera c = Camera::FromK(K, ImageSize{640, 480}, RadialTangentialModel{}, strong_barrel);
  EXPECT_TRUE(c.Unproject(Eigen::Vector2d(320 + 500 * 0.3, 240)).has_value());
  const double peak = std::sqrt(2.0 / 3) * (1 - 0.5 * 2.0 / 3);  // largest reachable distorted radius
  EXPECT_FALSE(c.Unproject(Eigen::Vector2d(320 + 500 * (peak + 0.01), 240)).has_value());
}

// Jet instantiation: derivatives w.r.t. every parameter and the 3 point coordinates agree with
// central differences.
template <typename Model>
void ExpectJetDerivativesMatchCentralDifferences(const Camera& c) {
  constexpr int kParams = Model::kNumParams;
  using Jet = ceres::Jet<double, kParams + 3>;
  ASSERT_EQ(static_cast<int>(c.params.size()), kParams);
  const Eigen::Vector3d p(0.4, -0.25, 1.7);
  Jet params[kParams], point[3], px[2];
  for (int i = 0; i < kParams; ++i) params[i] = Jet(c.params[i], i);
  for (int i = 0; i < 3; ++i) point[i] = Jet(p(i), kParams + i);
  ASSERT_TRUE(Model::Project(params, point, px));
  auto project = [&](std::vector<double> q, Eigen::Vector3d x) {
    double out[2] = {NAN, NAN};
    EXPECT_TRUE(Model::Project(q.data(), x.data(), out));
    return Eigen::Vector2d(out[0], out[1]);
  };
  for (int k = 0; k < kParams + 3; ++k) {
    std::vector<double> qp = c.params, qm = c.params;
    Eigen::Vector3d xp = p, xm = p;
    const double h = k < kParams ? 1e-6 * std::max(1.0, std::abs(c.params[k])) : 1e-6;
    if (k < kParams) {
      qp[k] += h;
      qm[k] -= h;
    } else {
      xp(k - kParams) += h;
      xm(k - kParams) -= h;
    }
    const Eigen::Vector2d numeric = (project(qp, xp) - project(qm, xm)) / (2 * h);
    for (int i = 0; i < 2; ++i) EXPECT_NEAR(px[i].v(k), numeric(i), 1e-5 * (1 + std::abs(numeric(i)))) << k;
  }
  EXPECT_NEAR(px[0].a, c.Project(p)->x(), 1e-12);
}

TEST(CameraModel, JetDerivativesMatchCentralDifferences) {
  ExpectJetDerivativesMatchCentralDifferences<RadialTangentialModel>(WideCamera(1.5));
}

TEST(CameraModel, RationalJetDerivativesMatchCentralDifferences) {
  ExpectJetDerivativesMatchCentralDifferences<RationalModel>(RationalCamera(1.5));
}

TEST(CameraModel, NamesAndParameterLayout) {
  EXPECT_TRUE(std::holds_alternative<PinholeModel>(*LensModelFromName("none")));
  EXPECT_TRUE(std::holds_alternative<RadialTangentialModel>(*LensModelFromName("radial-tangential")));
  EXPECT_TRUE(std::holds_alternative<RationalModel>(*LensModelFromName("rational")));
  EXPECT_FALSE(LensModelFromName("opencv5").has_value());
  EXPECT_EQ(KnownLensModelNames(), "\"none\", \"radial-tangential\", \"rational\", \"kannala-brandt\"");
  EXPECT_EQ(LensModelNumParams(RadialTangentialModel{}), 10);
  const auto names = LensModelParamNames(RadialTangentialModel{});
  EXPECT_EQ(names[5], "k1");
  EXPECT_EQ(names[7], "p1");
  EXPECT_EQ(names[9], "k3");
  EXPECT_EQ(LensModelNumParams(RationalModel{}), 13);
  const auto rational = LensModelParamNames(RationalModel{});
  EXPECT_EQ(rational[9], "k3");
  EXPECT_EQ(rational[10], "k4");
  EXPECT_EQ(rational[12], "k6");
  const Camera c = WideCamera();
  EXPECT_DOUBLE_EQ(c.distortion()[4], -0.0021);
  EXPECT_TRUE(c.InImage(Eigen::Vector2d(-0.5, 719.5)));
  EXPECT_FALSE(c.InImage(Eigen::Vector2d(-0.51, 300)));
}

// Seed 001 Eq. 5: K = [[fu, −fu cot θ, u0], [0, fv / sin θ, v0], [0, 0, 1]].
TEST(Intrinsics, SkewFormClosedFormAndRoundTrip) {
  SkewForm f{1000, 900, 640, 360, DegToRad(80)};
  const Eigen::Matrix3d K = KFromSkewForm(f);
  EXPECT_NEAR(K(0, 1), -1000 / std::tan(DegToRad(80)), 1e-12);
  EXPECT_NEAR(K(1, 1), 900 / std::sin(DegToRad(80)), 1e-12);
  const SkewForm g = SkewFormFromK(K);
  EXPECT_NEAR(g.fu, 1000, 1e-12);
  EXPECT_NEAR(g.fv, 900, 1e-12);
  EXPECT_NEAR(g.theta_rad, DegToRad(80), 1e-15);
  SkewForm square{1000, 900, 640, 360, kPi / 2};
  EXPECT_EQ(KFromSkewForm(square)(0, 1), 0.0);  // exactly: no rounding residue at 90°
  EXPECT_EQ(SkewFormFromK(KFromSkewForm(square)).theta_rad, kPi / 2);
  EXPECT_NEAR(FocalFromHorizontalFov(1280, DegToRad(90)), 640, 1e-12);
}

}  // namespace
}  // namespace vstcal
