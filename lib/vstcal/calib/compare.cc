#include "vstcal/calib/compare.h"

#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <boost/math/distributions/chi_squared.hpp>

#include "vstcal/core/error.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/geometry/linalg.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

bool HasCovariance(const CalibratedCamera& c) { return c.covariance && !c.covariance->empty(); }

// A difference this small is the rounding of two projections through a pose and back (≈ 1e-12 px),
// not a disagreement: far below any pixel measurement.
constexpr double kRoundingPx = 1e-9;

}  // namespace

double DisagreementSigma(const Eigen::Vector2d& d, const Eigen::Matrix2d& covariance_a, const Eigen::Matrix2d& covariance_b) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(covariance_a + covariance_b);
  const double largest = std::max(eig.eigenvalues()(1), 0.0);
  double m2 = 0;
  for (int i = 0; i < 2; ++i) {
    const double along = eig.eigenvectors().col(i).dot(d);
    const double variance = eig.eigenvalues()(i);
    if (variance > 1e-12 * largest && variance > 0) {
      m2 += along * along / variance;
    } else if (std::abs(along) > kRoundingPx) {
      return std::numeric_limits<double>::infinity();
    }
  }
  return std::sqrt(m2);
}

CameraComparison CompareCameras(const CalibratedCamera& a, const CalibratedCamera& b, std::optional<double> depth) {
  if (!(a.camera.image_size == b.camera.image_size)) {
    throw InputError("image_size: " + std::to_string(a.camera.image_size.width) + "x" +
                     std::to_string(a.camera.image_size.height) + " vs " + std::to_string(b.camera.image_size.width) +
                     "x" + std::to_string(b.camera.image_size.height) + "; compare cameras of the same sensor");
  }
  if (a.length_unit != b.length_unit) {
    throw InputError("length_unit: \"" + std::string(LengthUnitName(a.length_unit)) + "\" vs \"" +
                     std::string(LengthUnitName(b.length_unit)) + "\"; convert one of them first");
  }
  CameraComparison out;
  out.K_difference = b.camera.K() - a.camera.K();
  out.fx_relative = out.K_difference(0, 0) / a.camera.K()(0, 0);
  const bool posed = a.camera_from_world && b.camera_from_world;
  if (posed) {
    out.rotation_deg = RadToDeg(AngleBetween(a.camera_from_world->R, b.camera_from_world->R));
    out.centre_distance = (a.camera_from_world->inverse().t - b.camera_from_world->inverse().t).norm();
  }
  out.depth = depth.value_or(posed ? a.camera_from_world->t.z() : 1000.0);
  if (!(out.depth > 0)) throw InputError(VSTCAL_OPT("depth") ": must be positive (a point in front of the camera)");

  // Without poses both cameras sit at the same place: compare the intrinsics alone.
  const Rigid3d world_from_a = posed ? a.camera_from_world->inverse() : Rigid3d::Identity();
  const Rigid3d b_from_world = posed ? *b.camera_from_world : Rigid3d::Identity();
  const bool sigma = HasCovariance(a) && HasCovariance(b);
  const auto kind = posed ? ProjectionUncertaintyKind::kWithPoses : ProjectionUncertaintyKind::kIntrinsicsOnly;
  const ImageSize& size = a.camera.image_size;
  for (int i = 0; i < 9; ++i) {
    for (int j = 0; j < 9; ++j) {
      const Eigen::Vector2d px(-0.5 + size.width * (i + 0.5) / 9.0, -0.5 + size.height * (j + 0.5) / 9.0);
      const auto ray = a.camera.Unproject(px);
      if (!ray) continue;
      const Eigen::Vector3d point_in_world = world_from_a * (*ray * out.depth);
      const auto q = b.camera.Project(b_from_world * point_in_world);
      if (!q) continue;
      const double d = (*q - px).norm();
      out.rms_px += d * d;
      out.max_px = std::max(out.max_px, d);
      ++out.n_points;
      if (!sigma) continue;
      // Unposed, b's point is a's camera-frame point, which b sees at q with the same depth.
      const auto ea = posed ? ProjectionUncertaintyAtWorldPoint(a, point_in_world, kind)
                            : ProjectionUncertaintyAtPixel(a, px, out.depth, kind);
      const auto eb = posed ? ProjectionUncertaintyAtWorldPoint(b, point_in_world, kind)
                            : ProjectionUncertaintyAtPixel(b, *q, out.depth, kind);
      if (!ea || !eb) continue;
      const double m = DisagreementSigma(*q - px, ea->covariance, eb->covariance);
      if (!out.max_sigma || m > *out.max_sigma) {
        out.max_sigma = m;
        out.max_sigma_pixel = px;
      }
    }
  }
  out.rms_px = out.n_points ? std::sqrt(out.rms_px / static_cast<double>(out.n_points)) : 0.0;
  return out;
}

std::vector<PointDisagreement> CompareAtTestPoints(const CalibratedCamera& a, const CalibratedCamera& b,
                                                   const Correspondences& corners) {
  if (!a.camera_from_world || !b.camera_from_world) {
    throw InputError("camera_from_world: comparing at world points needs both cameras posed in the world (volume rigs)");
  }
  const Correspondences* files[] = {&corners};
  const MeasuredVolume volume = MeasuredVolumeOf(files);
  std::vector<PointDisagreement> out;
  for (const TestPoint& t : corners.test_points) {
    PointDisagreement d{t.name, t.point_in_world, std::nullopt, volume.Contains(t.point_in_world), std::nullopt};
    const auto qa = a.camera.Project(*a.camera_from_world * t.point_in_world);
    const auto qb = b.camera.Project(*b.camera_from_world * t.point_in_world);
    if (qa && qb) {
      d.pixel_distance = (*qa - *qb).norm();
      const auto ea = ProjectionUncertaintyAtWorldPoint(a, t.point_in_world);
      const auto eb = ProjectionUncertaintyAtWorldPoint(b, t.point_in_world);
      if (ea && eb) d.sigma = DisagreementSigma(*qb - *qa, ea->covariance, eb->covariance);
    }
    out.push_back(std::move(d));
  }
  return out;
}

CrossValidation CrossValidate(const CalibratedCamera& a, const CalibratedCamera& b, int cols, int rows, double alpha) {
  if (a.camera.image_size.width != b.camera.image_size.width || a.camera.image_size.height != b.camera.image_size.height) {
    throw InputError("image_size: the two calibrations are of different sensors; cross-validate two calibrations of one camera");
  }
  if (!HasCovariance(a) || !HasCovariance(b)) {
    throw InputError("covariance: cross-validation weighs the difference by both calibrations' uncertainty; give two refined cameras");
  }
  CrossValidation out;
  out.cols = cols;
  out.rows = rows;
  out.alpha = alpha;
  // Intrinsics only, a camera-frame direction: any depth gives the same projections and ellipses.
  constexpr double kDepth = 1000.0;
  const ImageSize& size = a.camera.image_size;
  std::vector<Eigen::Vector2d> differences;
  std::vector<Eigen::MatrixXd> jacobians_a, jacobians_b;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      RegionAgreement region;
      region.col = c;
      region.row = r;
      region.pixel = Eigen::Vector2d(-0.5 + size.width * (c + 0.5) / cols, -0.5 + size.height * (r + 0.5) / rows);
      const auto ray = a.camera.Unproject(region.pixel);
      const auto q = ray ? b.camera.Project(*ray * kDepth) : std::nullopt;
      if (q) {
        region.distance_px = (*q - region.pixel).norm();
        const auto ja = IntrinsicsJacobianAt(a, *ray * kDepth), jb = IntrinsicsJacobianAt(b, *ray * kDepth);
        if (ja && jb) {
          differences.push_back(*q - region.pixel);
          jacobians_a.push_back(*ja);
          jacobians_b.push_back(*jb);
        }
        const auto ea = ProjectionUncertaintyAtPixel(a, region.pixel, kDepth, ProjectionUncertaintyKind::kIntrinsicsOnly);
        const auto eb = ProjectionUncertaintyAtPixel(b, *q, kDepth, ProjectionUncertaintyKind::kIntrinsicsOnly);
        if (ea && eb) {
          region.sigma = DisagreementSigma(*q - region.pixel, ea->covariance, eb->covariance);
          region.p_value = std::exp(-0.5 * *region.sigma * *region.sigma);
          out.min_p = out.min_p ? std::min(*out.min_p, *region.p_value) : *region.p_value;
          ++out.tested;
        }
      }
      out.regions.push_back(region);
    }
  }
  if (!differences.empty()) {
    const auto n = static_cast<Eigen::Index>(differences.size());
    Eigen::VectorXd d(2 * n);
    Eigen::MatrixXd Ja(2 * n, jacobians_a.front().cols()), Jb(2 * n, jacobians_b.front().cols());
    for (Eigen::Index k = 0; k < n; ++k) {
      d.segment<2>(2 * k) = differences[static_cast<size_t>(k)];
      Ja.middleRows(2 * k, 2) = jacobians_a[static_cast<size_t>(k)];
      Jb.middleRows(2 * k, 2) = jacobians_b[static_cast<size_t>(k)];
    }
    // One Jacobian for both when they name the same parameters: to first order the two are equal,
    // and their O(δθ) difference would otherwise add directions of near-zero variance that
    // amplify the noise (rank(C) is then at most the number of parameters, as it should be).
    if (a.covariance->parameters == b.covariance->parameters) Ja = Jb = 0.5 * (Ja + Jb);
    const Eigen::MatrixXd C = PropagateCovariance(*a.covariance, Ja) + PropagateCovariance(*b.covariance, Jb);
    const SymmetricEigen eig = DecomposeSymmetric(C);
    const double largest = eig.values.maxCoeff();
    const Eigen::VectorXd along = eig.vectors.transpose() * d;
    bool beyond = false;  // a difference where neither calibration has any uncertainty
    for (Eigen::Index i = 0; i < along.size(); ++i) {
      if (eig.values(i) > 1e-12 * largest) {
        out.chi2 += along(i) * along(i) / eig.values(i);
        ++out.dof;
      } else if (std::abs(along(i)) > 1e-9) {
        beyond = true;
      }
    }
    if (beyond) out.chi2 = std::numeric_limits<double>::infinity();
    out.p_value = out.dof == 0 ? 1.0 : std::isinf(out.chi2) ? 0.0
                                     : boost::math::cdf(boost::math::complement(boost::math::chi_squared(out.dof), out.chi2));
    out.agree = *out.p_value >= alpha;
  }
  return out;
}

}  // namespace vstcal
