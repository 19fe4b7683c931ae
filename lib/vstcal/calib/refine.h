// Maximum-likelihood refinement shared by every solver (DLT, Tsai, Zhang's planar views): Ceres
// trust-region least squares with Powell's dogleg (refine.cc says why) over the lens model's free
// parameters and one pose per rig (volume) or per view (planar views), with optional robust loss,
// outliers listed (never dropped), and the parameter covariance at the optimum. Objective and
// parameter blocks: calib/reprojection_cost.h; covariance and its degrees of freedom:
// docs/math/uncertainty.md.
#pragma once

#include <string>
#include <vector>

#include "vstcal/calib/calibrated_camera.h"
#include "vstcal/calib/correspondences.h"

namespace vstcal {

struct RefineOptions {
  // Distortion terms to estimate, by name ("k1", "p2", …). The camera's model is promoted from
  // "none" to "radial-tangential" when any is asked for; terms not named keep their initial values.
  std::vector<std::string> free_distortion = {"k1", "k2", "p1", "p2"};
  bool free_focal = true;            // fx, fy
  bool free_principal_point = true;  // cx, cy
  bool free_skew = false;            // s: opt-in (most sensors have none; it trades off with cx)

  enum class Loss { kNone, kHuber, kCauchy };
  Loss loss = Loss::kNone;
  double loss_scale_px = 1.0;  // where the robust loss departs from the square, px

  // An observation is listed as an outlier when Gaussian noise of the robust scale σ̂ (median |r| /
  // √(2 ln 2)) would put any of the N residuals that far out with probability below
  // outlier_false_alarm: |r|²/σ̂² > −2 ln(outlier_false_alarm / N) (χ²₂ tail, Bonferroni over N).
  double outlier_false_alarm = 0.01;

  int max_iterations = 100;
};

enum class RefineStatus {
  kConverged,
  kNotConverged,  // iteration limit reached: the result is the last iterate (not written by tools)
  kFailed,        // Ceres could not start or every step failed (e.g. points behind the camera)
  kTooFewPoints,  // no more residuals than free parameters: nothing was solved
};

struct Outlier {
  size_t view = 0;   // index in Correspondences::views
  size_t point = 0;  // index in the view's observations
  Eigen::Vector2d residual_px;
  double normalized = 0;  // |r| / σ̂
};

struct Refinement {
  RefineStatus status = RefineStatus::kFailed;
  std::string message;

  Camera camera;               // refined (model possibly promoted, see RefineOptions)
  std::vector<Rigid3d> poses;  // camera_from_world (volume: one) or camera_from_board (one per view)
  Fit fit;

  // Covariance of the free parameters: σ̂² (JᵀJ)⁻¹ at the optimum, intrinsics then poses, named as
  // ParameterCovariance documents. Empty when JᵀJ is singular (a parameter is unobservable; the
  // message says so).
  ParameterCovariance covariance;
  double sigma_px = 0;  // σ̂ = √(Σ r² / dof): the estimated pixel noise per coordinate
  int dof = 0;          // 2N − number of free parameters, N the points σ̂ sums over
  // Under a robust loss σ̂ sums over the points not listed as outliers (they barely weigh in the fit
  // or in JᵀWJ); under least squares over all points.
  bool sigma_inliers_only = false;
  double robust_sigma_px = 0;
  std::vector<Outlier> outliers;

  int iterations = 0;
  double initial_rms_px = 0;
};

// `initial_poses` holds camera_from_world (volume rig: one) or camera_from_board (planar views:
// one per view), e.g. from SolveDlt, Tsai or Zhang's method. Throws InputError for options that
// name unknown distortion terms; geometric failures come back in the status.
Refinement Refine(const Correspondences& c, const Camera& initial, const std::vector<Rigid3d>& initial_poses,
                  const RefineOptions& options);

// Names of the free intrinsic parameters for a model and options, in layout order.
std::vector<std::string> FreeIntrinsicNames(const AnyLensModel& model, const RefineOptions& options);

}  // namespace vstcal
