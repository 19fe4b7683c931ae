// The Kannala–Brandt fisheye ("kannala-brandt") against OpenCV's cv::fisheye in the same tests:
// projection, its Jacobians, unprojection; and against closed forms where OpenCV cannot go (rays
// at and beyond 90°, the edge of the valid domain, the optical axis).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include <ceres/jet.h>
#include <opencv2/calib3d.hpp>

#include "vstcal/camera/camera.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/estimators/free_intrinsics.h"

namespace vstcal {
namespace {

constexpr double kFisheyePi = 3.14159265358979323846;

// A fisheye camera with random coefficients of the size calibrated fisheye lenses have (OpenCV's
// sample fits: |k1| ≲ 0.05, |k4| ≲ 0.001), and skew α·fx (cv::fisheye's α).
Camera RandomFisheye(std::mt19937_64& rng, double alpha) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double fx = 300 + 20 * u(rng), fy = fx * (1 + 0.01 * u(rng));
  Eigen::Matrix3d K;
  K << fx, alpha * fx, 640 + 10 * u(rng), 0, fy, 480 + 10 * u(rng), 0, 0, 1;
  const double d[4] = {0.05 * u(rng), 0.01 * u(rng), 0.005 * u(rng), 0.001 * u(rng)};
  return Camera::FromK(K, ImageSize{1280, 960}, KannalaBrandtModel{}, d);
}

// Points at angles off the axis up to max_theta, any azimuth, distances 0.5 to 5.
std::vector<Eigen::Vector3d> FisheyePoints(std::mt19937_64& rng, int n, double max_theta) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < n; ++i) {
    const double theta = max_theta * std::sqrt(u(rng)), phi = 2 * kFisheyePi * u(rng), d = 0.5 + 4.5 * u(rng);
    points.emplace_back(d * std::sin(theta) * std::cos(phi), d * std::sin(theta) * std::sin(phi), d * std::cos(theta));
  }
  return points;
}

cv::Matx33d OpenCvK(const Camera& c) { return cv::Matx33d(c.params[0], 0, c.params[2], 0, c.params[1], c.params[3], 0, 0, 1); }
cv::Vec4d OpenCvD(const Camera& c) { return cv::Vec4d(c.params[5], c.params[6], c.params[7], c.params[8]); }

// Peer: cv::fisheye::projectPoints (rays in front of the camera: OpenCV divides by z), random
// cameras and points out to 80°, with skew (OpenCV's α = s/fx).
TEST(FisheyeModel, ProjectionAgreesWithOpenCvFisheye) {
  std::mt19937_64 rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    const double alpha = trial % 2 ? 0.002 : 0.0;
    const Camera c = RandomFisheye(rng, alpha);
    const auto points = FisheyePoints(rng, 200, 80 * kFisheyePi / 180);
    std::vector<cv::Point3d> object;
    for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    cv::fisheye::projectPoints(object, image, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), OpenCvK(c), OpenCvD(c), alpha);
    for (size_t i = 0; i < points.size(); ++i) {
      const auto px = c.Project(points[i]);
      ASSERT_TRUE(px.has_value()) << points[i].transpose();
      EXPECT_LT((*px - Eigen::Vector2d(image[i].x, image[i].y)).norm(), 1e-9 * px->norm()) << trial << " " << i;
    }
  }
}

// Peer: projectPoints' own Jacobian (2N × 15: f, c, k, rvec, tvec, α) against
// ProjectWithJacobians: with rvec = tvec = 0 its tvec columns are ∂px/∂p_cam.
TEST(FisheyeModel, JacobiansAgreeWithOpenCvFisheye) {
  std::mt19937_64 rng(24);
  for (int trial = 0; trial < 5; ++trial) {
    const Camera c = RandomFisheye(rng, 0.0);
    const auto points = FisheyePoints(rng, 50, 80 * kFisheyePi / 180);
    std::vector<cv::Point3d> object;
    for (const auto& p : points) object.emplace_back(p.x(), p.y(), p.z());
    std::vector<cv::Point2d> image;
    cv::Mat jacobian;
    cv::fisheye::projectPoints(object, image, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), OpenCvK(c), OpenCvD(c), 0.0,
                               jacobian);
    ASSERT_EQ(jacobian.cols, 15);
    // Our parameter index for OpenCV's columns 0..7 (fx, fy, cx, cy, k1..k4).
    const int ours[8] = {0, 1, 2, 3, 5, 6, 7, 8};
    for (size_t i = 0; i < points.size(); ++i) {
      double px[2], d_params[2 * 9], d_point[6];
      ASSERT_TRUE(KannalaBrandtModel::ProjectWithJacobians(c.params.data(), points[i].data(), px, d_params, d_point));
      for (int row = 0; row < 2; ++row) {
        const double* cv_row = jacobian.ptr<double>(static_cast<int>(2 * i) + row);
        for (int k = 0; k < 8; ++k) {
          EXPECT_NEAR(d_params[row * 9 + ours[k]], cv_row[k], 1e-9 * (1 + std::abs(cv_row[k]))) << i << " " << k;
        }
        for (int k = 0; k < 3; ++k) {
          EXPECT_NEAR(d_point[row * 3 + k], cv_row[11 + k], 1e-9 * (1 + std::abs(cv_row[11 + k]))) << i << " " << k;
        }
      }
    }
  }
}

// Central differences where OpenCV cannot go: 100° and 150° off the axis, and near the axis.
TEST(FisheyeModel, JacobiansMatchCentralDifferencesBeyondNinetyDegrees) {
  Eigen::Matrix3d K;
  K << 310, 0.7, 645, 0, 308, 478, 0, 0, 1;
  const double d[4] = {0.03, -0.004, 0.0007, -0.0001};
  const Camera c = Camera::FromK(K, ImageSize{1280, 960}, KannalaBrandtModel{}, d);
  ASSERT_GT(KannalaBrandtModel::MaxTheta(d), 152 * kFisheyePi / 180);  // 154°: the slope's first zero
  auto project = [](const std::vector<double>& q, const Eigen::Vector3d& x) {
    double out[2] = {NAN, NAN};
    EXPECT_TRUE(KannalaBrandtModel::Project(q.data(), x.data(), out));
    return Eigen::Vector2d(out[0], out[1]);
  };
  for (const double deg : {1e-3, 20.0, 89.0, 100.0, 150.0}) {
    const double t = deg * kFisheyePi / 180;
    const Eigen::Vector3d p(1.3 * std::sin(t) * std::cos(0.4), 1.3 * std::sin(t) * std::sin(0.4), 1.3 * std::cos(t));
    double px[2], d_params[18], d_point[6];
    ASSERT_TRUE(KannalaBrandtModel::ProjectWithJacobians(c.params.data(), p.data(), px, d_params, d_point)) << deg;
    for (int k = 0; k < 12; ++k) {
      std::vector<double> qp = c.params, qm = c.params;
      Eigen::Vector3d xp = p, xm = p;
      const double h = k < 9 ? 1e-6 * std::max(1.0, std::abs(c.params[k])) : 1e-7;
      (k < 9 ? qp[k] : xp(k - 9)) += h;
      (k < 9 ? qm[k] : xm(k - 9)) -= h;
      const Eigen::Vector2d numeric = (project(qp, xp) - project(qm, xm)) / (2 * h);
      for (int row = 0; row < 2; ++row) {
        const double analytic = k < 9 ? d_params[row * 9 + k] : d_point[row * 3 + k - 9];
        EXPECT_NEAR(analytic, numeric(row), 1e-5 * (1 + std::abs(numeric(row)))) << deg << "° k=" << k;
      }
    }
  }
}

// On the axis (r = 0) θd/r has the limit 1/z: values and Jets finite, the Jacobian that of a
// pinhole there (∂u/∂X = fx/z, ∂u/∂Y = s/z, ∂v/∂Y = fy/z).
TEST(FisheyeModel, OnTheAxisValuesAndJetsAreFinite) {
  Eigen::Matrix3d K;
  K << 310, 0.7, 645, 0, 308, 478, 0, 0, 1;
  const double d[4] = {0.03, -0.004, 0.0007, -0.0001};
  const Camera c = Camera::FromK(K, ImageSize{1280, 960}, KannalaBrandtModel{}, d);
  const Eigen::Vector3d p(0, 0, 2);
  double px[2], d_params[18], d_point[6];
  ASSERT_TRUE(KannalaBrandtModel::ProjectWithJacobians(c.params.data(), p.data(), px, d_params, d_point));
  EXPECT_EQ(px[0], 645);
  EXPECT_EQ(px[1], 478);
  EXPECT_DOUBLE_EQ(d_point[0], 310 / 2.0);
  EXPECT_DOUBLE_EQ(d_point[1], 0.7 / 2.0);
  EXPECT_DOUBLE_EQ(d_point[4], 308 / 2.0);
  for (const double v : d_params) EXPECT_TRUE(std::isfinite(v));
  EXPECT_EQ(*c.UnprojectRay(Eigen::Vector2d(645, 478)), Eigen::Vector3d(0, 0, 1));
  // On the axis behind the camera there is no azimuth: refused, as is the centre of projection.
  EXPECT_FALSE(c.Project(Eigen::Vector3d(0, 0, -1)).has_value());
  EXPECT_FALSE(c.Project(Eigen::Vector3d(0, 0, 0)).has_value());
}

// The slope used by the domain check is DistortAngle's derivative (Jet), and MaxTheta its first
// zero: θd = θ(1 + k1 θ²) has slope 1 + 3 k1 θ², zero at θ = 1/√(−3 k1).
TEST(FisheyeModel, ValidDomainClosedForm) {
  const double d[4] = {-0.1, 0, 0, 0};
  EXPECT_NEAR(KannalaBrandtModel::MaxTheta(d), 1 / std::sqrt(0.3), 1e-11);
  const double none[4] = {0, 0, 0, 0};
  EXPECT_EQ(KannalaBrandtModel::MaxTheta(none), kFisheyePi);  // never past π
  const double e[4] = {0.03, -0.004, 0.0007, -0.0001};
  using Jet = ceres::Jet<double, 1>;
  const Jet je[4] = {Jet(e[0]), Jet(e[1]), Jet(e[2]), Jet(e[3])};
  for (double t = 0; t < 3.1; t += 0.1) {
    EXPECT_NEAR(KannalaBrandtModel::AngleSlope(e, t), KannalaBrandtModel::DistortAngle(je, Jet(t, 0)).v[0], 1e-14);
  }
}

// Round trips out to and beyond 90° (unit rays), and Unproject's (x, y, 1) form where it exists.
TEST(FisheyeModel, UnprojectInvertsProjectBeyondNinetyDegrees) {
  std::mt19937_64 rng(25);
  for (int trial = 0; trial < 10; ++trial) {
    Camera c = RandomFisheye(rng, trial % 2 ? 0.002 : 0.0);
    // Coefficients small enough for a 200° lens: θd grows up to 100° off the axis.
    for (int k = 5; k < 9; ++k) c.params[k] *= 0.2;
    ASSERT_GT(KannalaBrandtModel::MaxTheta(c.params.data() + 5), 100 * kFisheyePi / 180);
    for (const Eigen::Vector3d& p : FisheyePoints(rng, 200, 100 * kFisheyePi / 180)) {
      const auto px = c.Project(p);
      ASSERT_TRUE(px.has_value());
      const auto ray = c.UnprojectRay(*px);
      ASSERT_TRUE(ray.has_value()) << p.transpose();
      EXPECT_NEAR(ray->norm(), 1.0, 1e-15);
      EXPECT_LT((*ray - p.normalized()).norm(), 1e-12) << p.transpose();
      const auto xy1 = c.Unproject(*px);
      EXPECT_EQ(xy1.has_value(), p.z() > 0);
      if (xy1 && p.z() > 0.1 * p.norm()) {
        EXPECT_LT((*xy1 - p / p.z()).norm(), 1e-12 * (1 + p.head<2>().norm() / p.z()));
      }
    }
  }
}

// Peer: cv::fisheye::undistortPoints (Newton on θ, stopped at 1e-8 by default: asked here for 1e-14
// and 100 iterations) gives the same (x, y) as Unproject. Out to 70°: OpenCV clamps θd to π/2.
TEST(FisheyeModel, UnprojectAgreesWithOpenCvUndistortPoints) {
  std::mt19937_64 rng(26);
  const Camera c = RandomFisheye(rng, 0.0);
  const auto points = FisheyePoints(rng, 300, 70 * kFisheyePi / 180);
  std::vector<cv::Point2d> distorted, undistorted;
  for (const auto& p : points) {
    const Eigen::Vector2d px = *c.Project(p);
    distorted.emplace_back(px.x(), px.y());
  }
  cv::fisheye::undistortPoints(distorted, undistorted, OpenCvK(c), OpenCvD(c), cv::noArray(), cv::noArray(),
                               cv::TermCriteria(cv::TermCriteria::MAX_ITER + cv::TermCriteria::EPS, 100, 1e-14));
  for (size_t i = 0; i < points.size(); ++i) {
    const auto ray = c.Unproject(Eigen::Vector2d(distorted[i].x, distorted[i].y));
    ASSERT_TRUE(ray.has_value());
    const Eigen::Vector2d theirs(undistorted[i].x, undistorted[i].y);
    EXPECT_LT((ray->head<2>() - theirs).norm(), 1e-9 * (1 + theirs.norm())) << i;
  }
}

// Past the valid domain: θd = θ(1 − 0.1 θ²) stops growing at θ = 1/√0.3 (104.6°). A point beyond
// it is refused by Project, and a pixel beyond θd's largest value by Unproject; inside, both work.
TEST(FisheyeModel, PointsPastTheValidDomainAreRefused) {
  Eigen::Matrix3d K;
  K << 300, 0, 640, 0, 300, 480, 0, 0, 1;
  const double d[4] = {-0.1, 0, 0, 0};
  const Camera c = Camera::FromK(K, ImageSize{1280, 960}, KannalaBrandtModel{}, d);
  const double edge = 1 / std::sqrt(0.3);
  auto at = [](double theta) { return Eigen::Vector3d(std::sin(theta), 0, std::cos(theta)); };
  EXPECT_TRUE(c.Project(at(edge - 1e-6)).has_value());
  EXPECT_FALSE(c.Project(at(edge + 1e-6)).has_value());
  EXPECT_FALSE(c.Project(at(3.0)).has_value());
  double px[2], d_params[18];
  EXPECT_FALSE(KannalaBrandtModel::ProjectWithJacobians(c.params.data(), at(2.0).data(), px, d_params, nullptr));
  const double peak = edge * (1 - 0.1 * edge * edge);
  EXPECT_TRUE(c.UnprojectRay(Eigen::Vector2d(640 + 300 * (peak - 1e-6), 480)).has_value());
  EXPECT_FALSE(c.UnprojectRay(Eigen::Vector2d(640 + 300 * (peak + 1e-6), 480)).has_value());
  // Below 90° the domain is a normalized radius: tan² of the edge when the edge is before 90°.
  const double early[4] = {-0.5, 0, 0, 0};
  const Camera e = Camera::FromK(K, ImageSize{1280, 960}, KannalaBrandtModel{}, early);
  EXPECT_NEAR(e.ValidRadiusSquared(), std::pow(std::tan(1 / std::sqrt(1.5)), 2), 1e-9);
  EXPECT_EQ(c.ValidRadiusSquared(), std::numeric_limits<double>::infinity());
}

// The fisheye's k1…k4 are not OpenCV's plumb-bob vector: four OpenCV coefficients stay
// "radial-tangential", and a refinement never turns a fisheye into another family.
TEST(FisheyeModel, IsNeverMistakenForABrownConradyModel) {
  EXPECT_TRUE(std::holds_alternative<RadialTangentialModel>(*LensModelForOpenCvLength(4)));
  EXPECT_TRUE(std::holds_alternative<KannalaBrandtModel>(*LensModelFromName("kannala-brandt")));
  EXPECT_FALSE(LensModelExtends(RadialTangentialModel{}, KannalaBrandtModel{}));
  EXPECT_TRUE(LensModelExtends(KannalaBrandtModel{}, PinholeModel{}));
  RefineOptions options;
  options.free_distortion = {"k1", "k2", "k3", "k4"};
  EXPECT_TRUE(std::holds_alternative<KannalaBrandtModel>(RefinedModel(KannalaBrandtModel{}, options)));
  EXPECT_TRUE(std::holds_alternative<RationalModel>(RefinedModel(PinholeModel{}, options)));
  options.free_distortion = {"k1", "p1"};
  EXPECT_THROW(RefinedModel(KannalaBrandtModel{}, options), InputError);
}

}  // namespace
}  // namespace vstcal
