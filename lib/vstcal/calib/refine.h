// Maximum-likelihood refinement shared by every solver (DLT, Tsai, Zhang's planar views): Ceres
// trust-region least squares with Powell's dogleg (refine.cc says why) over the free intrinsics
// (estimators/free_intrinsics.h: free, held or tied lens parameters) and one pose per rig (volume) or per
// view (planar views), the poses eliminated by the Schur complement (Ceres's DENSE_SCHUR, the
// intrinsics the last elimination group), with per-point weights, an optional robust loss,
// outliers listed (never dropped), and the parameter covariance at the optimum
// (estimators/information.h). Cost and memory are linear in the number of views. Objective and
// parameter blocks: estimators/reprojection_cost.h; covariance, its degrees of freedom and the
// observability test: docs/math/uncertainty.md.
#pragma once

#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/estimators/refine_options.h"

namespace vstcal {

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
  double normalized = 0;  // √w |r| / σ̂
};

struct Refinement {
  RefineStatus status = RefineStatus::kFailed;
  std::string message;

  Camera camera;               // refined (model possibly promoted, see RefineOptions)
  std::vector<Rigid3d> poses;  // camera_from_world (volume: one) or camera_from_board (one per view)
  Fit fit;

  FreeIntrinsics free;              // what was estimated
  std::vector<HeldIntrinsic> held;  // what was not, its value and why

  // Covariance of the estimate, σ̂² (JᵀWJ)⁻¹ at the optimum (estimators/information.h): over the lens
  // parameters that moved and the poses, named as ParameterCovariance documents. Empty when a
  // parameter is unobservable (the message names it).
  ParameterCovariance covariance;
  double smallest_scaled_eigenvalue = 0;  // of the scaled information's Schur complement
  double sigma_px = 0;  // σ̂ = √(Σ w r² / dof): the pixel noise per coordinate of a weight-1 point
  int dof = 0;          // 2N − number of free parameters, N the points σ̂ sums over
  // Under a robust loss σ̂ sums over the points not listed as outliers (they barely weigh in the fit
  // or in JᵀWJ); under least squares over all points.
  bool sigma_inliers_only = false;
  double robust_sigma_px = 0;
  std::vector<Outlier> outliers;

  int iterations = 0;          // over every round when there are priors (refine.cc)
  double initial_rms_px = 0;  // RMS of the weighted residuals √w r at the start

  // The priors the estimate and its covariance include (RefineOptions::priors): the covariance is
  // the posterior's, conditional only on `held`.
  std::vector<IntrinsicPrior> priors;
};

// `initial_poses` holds camera_from_world (volume rig: one) or camera_from_board (planar views:
// one per view), e.g. from SolveDlt, Tsai or Zhang's method. Throws InputError for options that
// name unknown distortion terms; geometric failures come back in the status.
Refinement Refine(const Correspondences& c, const Camera& initial, const std::vector<Rigid3d>& initial_poses,
                  const RefineOptions& options);

}  // namespace vstcal
