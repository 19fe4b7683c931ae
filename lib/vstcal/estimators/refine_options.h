// What the maximum-likelihood refinement estimates and how (calib/refine.h): which lens parameters
// are free, held or tied, the robust loss and the outlier rule. A header of its own so that the
// information code (estimators/information.h), the pipeline and the tools' flags share it without
// Ceres.
#pragma once

#include <optional>
#include <string>
#include <vector>
#include "vstcal/core/enum_names.h"

namespace vstcal {

// A Gaussian prior on one lens parameter (docs/math/uncertainty.md#priors): θ_i ~ N(value, sigma²),
// in the parameter's own unit (px for fx … s). The parameter stays estimated; the prior adds the
// whitened residual (θ_i − value)/sigma to the problem, so the estimate is the posterior mode and
// the covariance the posterior's: the prior's information reaches every σ, unlike a hold.
struct IntrinsicPrior {
  std::string parameter;  // a lens parameter name: "cx", "s", "k3", …
  double value = 0;
  double sigma = 0;       // > 0
  std::string because;    // written beside it in the camera file
};

struct RefineOptions {
  // Distortion terms to estimate, by name ("k1", "p2", "k5", …). The camera's model is promoted to
  // the smallest model that has every named term: "radial-tangential" for k1, k2, p1, p2, k3,
  // "rational" when k4, k5 or k6 is named. Terms not named keep their initial values.
  std::vector<std::string> free_distortion = {"k1", "k2", "p1", "p2"};
  bool free_focal = true;            // fx, fy
  bool free_principal_point = true;  // cx, cy
  bool free_skew = false;            // s: opt-in (most sensors have none; it trades off with cx)

  // Tie fx = focal_aspect · fy (Tsai's sx, held): fx and fy move together as one focal length,
  // estimated as "f" = fy. Needs free_focal. One plane cannot determine the aspect besides the
  // focal length and the principal point (docs/math/uncertainty.md#one-plane).
  std::optional<double> focal_aspect;

  // Why the principal point or the aspect is held, when it is: written in the camera file's
  // refinement.held (the pipeline says "one plane …"; a library user may say anything).
  std::string principal_point_held_because = "held by the caller (RefineOptions::free_principal_point)";
  std::string focal_aspect_held_because = "held by the caller (RefineOptions::focal_aspect)";

  enum class Loss { kNone, kHuber, kCauchy };
  static constexpr EnumNames<Loss, 3> kLossNames = {{{Loss::kNone, "none"}, {Loss::kHuber, "huber"}, {Loss::kCauchy, "cauchy"}}};
  Loss loss = Loss::kNone;
  double loss_scale_px = 1.0;  // where the robust loss departs from the square, px (of a weight-1 point)

  // An observation is listed as an outlier when Gaussian noise of the robust scale σ̂ (median
  // √w|r| / √(2 ln 2)) would put any of the N residuals that far out with probability below
  // outlier_false_alarm: w|r|²/σ̂² > −2 ln(outlier_false_alarm / N) (χ²₂ tail, Bonferroni over N).
  double outlier_false_alarm = 0.01;

  int max_iterations = 100;

  // Priors on free lens parameters (IntrinsicPrior). Each must name a parameter the refinement
  // estimates, once, with a finite value and sigma > 0 (ResolvePriors, free_intrinsics.h).
  std::vector<IntrinsicPrior> priors;

  // Why fx and fy are held when free_focal is false (refinement.held in the camera file).
  std::string focal_held_because = "held by the caller (RefineOptions::free_focal)";

  // A lens model to solve by its file name ("kannala-brandt" for a fisheye), or empty for the
  // Brown–Conrady model free_distortion calls for. The start camera is promoted to it (its layout
  // must extend the start's: a pinhole start always does), then as above. RefinedModel refuses an
  // unknown name.
  std::string lens_model;
};

}  // namespace vstcal
