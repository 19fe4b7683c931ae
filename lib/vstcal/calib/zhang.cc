#include "vstcal/calib/zhang.h"

#include <Eigen/LU>
#include <cmath>

#include "vstcal/estimators/homography.h"
#include "vstcal/estimators/length_range.h"
#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// Zhang's v_ij: h_iᵀ B h_j = v_ijᵀ b with b = (B11, B12, B22, B13, B23, B33).
Eigen::Matrix<double, 6, 1> V(const Eigen::Matrix3d& H, int i, int j) {
  const Eigen::Vector3d a = H.col(i), c = H.col(j);
  Eigen::Matrix<double, 6, 1> v;
  v << a(0) * c(0), a(0) * c(1) + a(1) * c(0), a(1) * c(1), a(2) * c(0) + a(0) * c(2), a(2) * c(1) + a(1) * c(2),
      a(2) * c(2);
  return v;
}

}  // namespace

std::vector<std::string> DropSparseViews(Correspondences* c, size_t min_points) {
  std::vector<std::string> warnings;
  std::vector<View> kept;
  for (View& v : c->views) {
    if (v.observations.size() >= min_points) {
      kept.push_back(std::move(v));
    } else {
      warnings.push_back("view \"" + v.name + "\" skipped: " + std::to_string(v.observations.size()) +
                         " points, fewer than " + std::to_string(min_points));
    }
  }
  c->views = std::move(kept);
  return warnings;
}

ZhangResult ZhangInitialization(const Correspondences& c) {
  ZhangResult out;
  // Board lengths of 1e200 or 1e-300 square beyond the doubles in the closed form: say that,
  // rather than call the views degenerate.
  if (const auto range = LengthsOutOfRange(c, std::nullopt)) {
    out.message = "the board's " + range->substr(std::string("the ").size()) + "; give the board in another length unit";
    return out;
  }
  std::vector<Eigen::Matrix3d> homographies;
  for (const View& view : c.views) {
    const auto H = EstimateHomography(view.observations);
    if (!H) {
      out.message = "view \"" + view.name + "\": its board points or pixels are degenerate (collinear?); remove the view";
      return out;
    }
    homographies.push_back(*H);
  }
  // Zhang's constraints only involve h₁ and h₂ up to a common factor, so each view's first two
  // columns may be rescaled freely: bringing them to the size of h₃ (board lengths vs the board's
  // distance) keeps the linear system well conditioned whatever the length unit.
  std::vector<Eigen::Matrix3d> balanced = homographies;
  for (Eigen::Matrix3d& H : balanced) {
    const double scale = H.col(2).norm() / (0.5 * (H.col(0).norm() + H.col(1).norm()));
    H.leftCols<2>() *= scale;
  }
  if (homographies.size() < 2) {
    out.message = "planar views need at least 2 views of the board at different orientations, got " +
                  std::to_string(homographies.size()) + "; add views";
    return out;
  }
  // Pixels scaled by 1/s (K = diag(s, s, 1) K̃) keep B's entries of comparable size.
  const double s = 0.5 * (c.image_size.width + c.image_size.height);
  const Eigen::Matrix3d S_inv = Eigen::Vector3d(1 / s, 1 / s, 1).asDiagonal();
  Eigen::MatrixXd A(2 * homographies.size() + 1, 6);
  for (size_t k = 0; k < balanced.size(); ++k) {
    // Each view's constraints are homogeneous in its H: at unit norm they weigh like the zero-skew
    // row below, whatever the length unit (in 1e-6 m a view's rows would otherwise be 1e-9 of it).
    Eigen::Matrix3d H = S_inv * balanced[k];
    H /= H.norm();
    A.row(2 * k) = V(H, 0, 1).transpose();
    A.row(2 * k + 1) = (V(H, 0, 0) - V(H, 1, 1)).transpose();
  }
  A.row(A.rows() - 1) << 0, 1, 0, 0, 0, 0;  // zero skew: B12 = 0
  const SingularValueDecomposition svd = DecomposeSvd(A, Eigen::ComputeFullV);
  if (!(svd.singular_values(4) > 1e-9 * svd.singular_values(0))) {
    out.message = "the views do not constrain K (boards all parallel, or all tilted about one axis); add views "
                  "with the board tilted in different directions";
    return out;
  }
  Eigen::Matrix<double, 6, 1> b = svd.V.col(5);
  if (b(0) < 0) b = -b;  // B is positive definite up to scale
  const double B11 = b(0), B12 = b(1), B22 = b(2), B13 = b(3), B23 = b(4), B33 = b(5);
  // Zhang's Appendix B closed form.
  const double denom = B11 * B22 - B12 * B12;
  const double v0 = (B12 * B13 - B11 * B23) / denom;
  const double lambda = B33 - (B13 * B13 + v0 * (B12 * B13 - B11 * B23)) / B11;
  const double alpha2 = lambda / B11, beta2 = lambda * B11 / denom;
  if (!(alpha2 > 0) || !(beta2 > 0)) {
    out.message = "the closed-form intrinsics are not real (B not positive definite): the views are degenerate or "
                  "the correspondences are wrong; check them";
    return out;
  }
  const double alpha = std::sqrt(alpha2), beta = std::sqrt(beta2);
  const double u0 = -B13 * alpha2 / lambda;
  Eigen::Matrix3d K;
  K << s * alpha, 0, s * u0, 0, s * beta, s * v0, 0, 0, 1;
  out.camera = Camera::FromK(K, c.image_size);

  const Eigen::Matrix3d K_inv = K.inverse();
  for (const Eigen::Matrix3d& H : homographies) {
    const double scale = 1.0 / (K_inv * H.col(0)).norm();
    double sign = (K_inv * H.col(2))(2) > 0 ? 1.0 : -1.0;  // the board is in front: t_z > 0
    const Eigen::Vector3d r1 = sign * scale * K_inv * H.col(0);
    const Eigen::Vector3d r2 = sign * scale * K_inv * H.col(1);
    Eigen::Matrix3d R;
    R << r1, r2, r1.cross(r2);
    Rigid3d pose;
    pose.R = NearestRotation(R);
    pose.t = sign * scale * K_inv * H.col(2);
    out.camera_from_board.push_back(pose);
  }
  out.ok = true;
  return out;
}

}  // namespace vstcal
