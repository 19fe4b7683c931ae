// How far apart two cameras are: intrinsic differences, pose differences and what they mean in
// pixels (used to compare an estimate with ground truth or two solvers with each other).
#pragma once

#include <optional>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

struct CameraComparison {
  Eigen::Matrix3d K_difference;       // b.K − a.K, px
  double fx_relative = 0;             // (b.fx − a.fx) / a.fx
  std::optional<double> rotation_deg;  // angle of b.R · a.Rᵀ (both posed)
  std::optional<double> centre_distance;  // distance between camera centres, length unit
  // Pixel disagreement over a 9×9 grid of a's image at `depth` in front of a: each grid pixel is
  // unprojected by a to a world point at that depth, then projected by b.
  double depth = 0;
  double rms_px = 0;
  double max_px = 0;
  size_t n_points = 0;
  // When both cameras carry a covariance: the largest disagreement over the grid in units of its
  // own uncertainty, DisagreementSigma, and the grid pixel where it is (docs/math/uncertainty.md#compare).
  // Posed cameras project the same world point, each with its intrinsics and pose varying
  // (ProjectionUncertaintyKind::kWithPoses); unposed ones the same camera-frame point, only the
  // intrinsics varying (kIntrinsicsOnly). Grid points where either uncertainty is undefined are left out.
  std::optional<double> max_sigma;
  Eigen::Vector2d max_sigma_pixel = Eigen::Vector2d::Zero();
};

// The Mahalanobis distance of the difference d = q_b − q_a of two independent projections with
// covariances Σ_a and Σ_b: √(dᵀ (Σ_a + Σ_b)⁻¹ d), "how many σ apart". +∞ when d has a component
// of more than 1e-9 px (rounding) along a direction in which Σ_a + Σ_b is zero (to 1e-12 of its
// largest eigenvalue).
double DisagreementSigma(const Eigen::Vector2d& d, const Eigen::Matrix2d& covariance_a,
                         const Eigen::Matrix2d& covariance_b);

// Registration disagreement at the test points of `corners` (a volume's correspondences): each
// point projected by both posed cameras; nullopt where either sees it behind. Each point is inside
// or outside the convex hull of the file's calibration points (MeasuredVolume; nullopt when they
// span no volume). Both cameras need camera_from_world (InputError otherwise).
struct PointDisagreement {
  std::string name;
  Eigen::Vector3d point_in_world;
  std::optional<double> pixel_distance;
  std::optional<bool> inside_volume;
  // DisagreementSigma of the two projections, each with its intrinsics and pose varying; nullopt
  // unless both cameras carry a covariance and the point is in front of both.
  std::optional<double> sigma = std::nullopt;
};
std::vector<PointDisagreement> CompareAtTestPoints(const CalibratedCamera& a, const CalibratedCamera& b,
                                                   const Correspondences& corners);

// Cross-validation (docs/math/uncertainty.md#cross-validation): are two calibrations of one camera
// from disjoint data — two halves of the views — one camera within their uncertainty? At the centre
// of each of cols × rows image cells, a's ray is projected by both cameras (the same camera-frame
// direction: poses play no part, the two halves' boards are not the same) and the difference is
// measured in σ of the two intrinsics-only projection uncertainties, which are independent: m² is
// χ²₂ when both are right, so P(m² ≥ observed) = exp(−m²/2), which says where they disagree. The
// verdict is one joint test over all cells, since the cells share the parameters: the stacked
// differences d weighed by their joint covariance C = J (Σ_a + Σ_b) Jᵀ, dᵀ C⁺ d, is χ² with rank(C)
// degrees of freedom when both are right; they disagree when its p is below alpha. Both cameras
// need a covariance (InputError otherwise).
struct RegionAgreement {
  int col = 0, row = 0;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();  // the cell's centre, a's pixel
  std::optional<double> distance_px, sigma, p_value;  // nullopt where a projection or its uncertainty is undefined
};
struct CrossValidation {
  int cols = 0, rows = 0;
  double alpha = 0.01;
  std::vector<RegionAgreement> regions;  // row by row
  size_t tested = 0;                     // cells with a p-value
  std::optional<double> min_p;           // of the cells
  double chi2 = 0;                       // the joint statistic dᵀ C⁺ d
  int dof = 0;                           // rank(C)
  std::optional<double> p_value;         // P(χ²_dof ≥ chi2); nullopt when no cell was tested
  bool agree = true;
};
CrossValidation CrossValidate(const CalibratedCamera& a, const CalibratedCamera& b, int cols = 4, int rows = 3, double alpha = 0.01);

// `depth` defaults to the depth of the world origin in a's camera frame when both cameras are
// posed (a volume calibration), else 1000 length units. Throws InputError when the cameras
// differ in image size or length unit.
CameraComparison CompareCameras(const CalibratedCamera& a, const CalibratedCamera& b,
                                std::optional<double> depth = std::nullopt);

}  // namespace vstcal
