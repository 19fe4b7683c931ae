// Calibration end to end: a closed-form start (DLT or Tsai for a volume, Zhang for planar views),
// then, unless switched off, the shared maximum-likelihood refinement with its covariance.
// calib-dlt and calib-tsai are thin mains over Calibrate().
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/calib/fisheye_start.h"
#include "vstcal/calib/refine.h"
#include "vstcal/calib/tsai.h"
#include "vstcal/estimators/principal_point_prior.h"
#include "vstcal/estimators/view_rejection.h"
#include "vstcal/calib/zhang.h"
#include "vstcal/core/error.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

struct CalibrationOptions {
  enum class Start { kDlt, kTsai };
  Start start = Start::kTsai;  // for volume rigs; planar views always start from Zhang's method
  DltOptions dlt;
  TsaiOptions tsai;
  bool refine = true;
  RefineOptions refinement;

  // One plane (Tsai's coplanar variant) refined: fx/fy stays at Tsai's sx, and the principal point
  // is estimated under a Gaussian prior centred where Tsai's stages assumed it (the image centre or
  // TsaiOptions::principal_point), σ = plane_principal_point_prior_sigma × the image diagonal per
  // coordinate (kPrior: weak data leave it near the prior, strong data move it, and its σ reaches
  // every reported σ); or held there exactly (kHold: σ's conditional on it); or estimated without
  // a prior (kFree). docs/math/uncertainty.md#one-plane.
  enum class PlanePrincipalPoint { kHold, kFree, kPrior };
  static constexpr EnumNames<PlanePrincipalPoint, 3> kPlanePrincipalPointNames = {{{PlanePrincipalPoint::kHold, "no"}, {PlanePrincipalPoint::kFree, "yes"}, {PlanePrincipalPoint::kPrior, "prior"}}};
  PlanePrincipalPoint plane_principal_point = PlanePrincipalPoint::kPrior;
  double plane_principal_point_prior_sigma = kPlanePrincipalPointPriorSigma;

  // Reject views (then corners) inconsistent with the others and re-solve, until none is
  // (docs/math/uncertainty.md#view-rejection). Off by default for every rig.
  ViewRejectionOptions reject_views;
};

// How a refined one-plane calibration treated the principal point (CalibrationOptions).
struct PlanePrincipalPointDecision {
  CalibrationOptions::PlanePrincipalPoint mode = CalibrationOptions::PlanePrincipalPoint::kPrior;
  // kPrior: the prior's centre and σ per coordinate (px), and the posterior σ of (cx, cy) from the
  // covariance (its ratio to the prior's says who decided: near 1 the prior, near 0 the data).
  Eigen::Vector2d prior_px = Eigen::Vector2d::Zero();
  double prior_sigma_px = 0;
  std::optional<Eigen::Vector2d> posterior_sigma_px;
  std::string because;
};

struct CalibrationResult {
  ExitCode exit_code = ExitCode::kOk;
  std::string message;                // why, when exit_code != kOk
  std::vector<std::string> warnings;  // skipped views, thin volumes, outliers, …

  CalibratedCamera camera;  // method "dlt", "tsai", "zhang", with "+refine" when refined
  Correspondences used;     // the correspondences the result refers to (sparse views dropped)

  std::optional<DltResult> dlt;
  // The DLT camera's first-order uncertainty (docs/math/dlt.md#covariance), kept beside a
  // refinement's so that the two can be compared; `camera.covariance` is this one unrefined.
  std::optional<DltUncertainty> dlt_uncertainty;
  std::optional<ParameterCovariance> dlt_covariance;
  std::optional<Eq13Decomposition> eq13;
  std::optional<TsaiResult> tsai;
  std::optional<Refinement> refinement;
  std::optional<PlanePrincipalPointDecision> plane_principal_point;  // one plane, refined
  // Planar views solved with a ray lens model (a fisheye): which candidate start was taken and how
  // each fared (fisheye_start.h).
  std::optional<FisheyeStartDecision> fisheye_start;

  // With reject_views: what was rejected, in order, and the last test's robust σ̂ (every view and
  // corner of `used` passed it). `used` then holds only what was kept.
  std::vector<Rejection> rejections;
  std::optional<double> rejection_sigma_px;
  int rejection_rounds = 0;
};

// Never throws on bad geometry: exit_code and message say what went wrong; with reject_views, a
// rejection that would leave fewer views than the rig needs (kMinPlanarViewsKept,
// kMinVolumeViewsKept) or a set the solver refuses is kBadInput, naming the view. Throws InputError for
// options that cannot apply (an unknown distortion term, a prior on a parameter not estimated).
CalibrationResult Calibrate(Correspondences correspondences, const CalibrationOptions& options);

}  // namespace vstcal
