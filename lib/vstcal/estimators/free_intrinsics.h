// Which lens parameters a refinement moves, as a linear map from its free coordinates β to the
// lens model's parameters (layout [fx, fy, cx, cy, s, distortion…], lens_models.h):
//
//   θ = θ_ref + B β,      B: kNumParams × m
//
// A free parameter is a column of B with a single 1; a held parameter has no column and keeps
// θ_ref; a tie is one column over several parameters: Tsai's coplanar aspect fx = sx·fy is the
// column (sx, 1) over (fx, fy), its coordinate named "f" (= fy). The refinement's Ceres manifold,
// its information matrix and its covariance are all in β; the covariance is written over the
// lens parameters as B Σ_β Bᵀ (docs/math/uncertainty.md#parameters).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/estimators/refine_options.h"
#include "vstcal/camera/camera.h"

namespace vstcal {

// The model a refinement solves: `initial` promoted to the smallest model of AnyLensModel that
// extends it (LensModelExtends: never a smaller one, never another family) and has every term of
// options.free_distortion. Throws InputError naming an unknown term, with the closest known one,
// or when no model extends `initial` by the terms (a fisheye with a Brown–Conrady term).
// options.lens_model, when set, replaces `initial` (which it must extend) before the promotion.
AnyLensModel RefinedModel(const AnyLensModel& initial, const RefineOptions& options);

// `initial`'s parameters in `model`'s layout (a larger model's extra terms 0).
std::vector<double> PromotedParams(const Camera& initial, const AnyLensModel& model);

struct FreeIntrinsics {
  std::vector<std::string> names;  // of β, in order: lens parameter names, "f" for fx = sx·fy
  Eigen::MatrixXd basis;           // B, kNumParams × names.size()

  int size() const { return static_cast<int>(names.size()); }
  // The lens parameters β moves (rows of B not all zero), in layout order.
  std::vector<std::string> MovedParams(const AnyLensModel& model) const;
  // B's rows that are not zero (those of MovedParams, in order): the lens parameters' covariance
  // from β's is B_m Σ_β B_mᵀ.
  Eigen::MatrixXd MovedBasis() const;
};

// β for `model` (already promoted, RefinedModel) and `options`: fx, fy (or f when tied), cx, cy,
// s, then the named distortion terms in the model's order.
FreeIntrinsics MakeFreeIntrinsics(const AnyLensModel& model, const RefineOptions& options);

// options.priors checked against `model` and `free`, each with its index in the model's layout:
// the prior's residual is (θ[index] − value)/sigma, its row over β is B.row(index)/sigma. Throws
// InputError for an unknown parameter (with the closest name), a parameter the refinement does not
// estimate, a second prior on one parameter, or a value or sigma that is not finite (sigma ≤ 0).
struct ResolvedPrior {
  int index = 0;
  double value = 0;
  double sigma = 0;
};
std::vector<ResolvedPrior> ResolvePriors(const AnyLensModel& model, const FreeIntrinsics& free,
                                         const RefineOptions& options);

// A lens parameter (or a ratio) the refinement does not move, with its value and the reason.
struct HeldIntrinsic {
  std::string parameter;  // "cx", "s", "k3", or "fx/fy" for a held aspect
  double value = 0;
  std::string because;
};

// The distortion terms named by a comma-separated list ("k1,k2,p1,p2"; "none": no term), as the
// option "distortion" gives them. Throws InputError for an empty or repeated term; whether the
// model has each term is checked where the model is known (FreeIntrinsics).
std::vector<std::string> DistortionTermsFromList(const std::string& list);

// A prior the user stated (the option "prior"), its reason saying so for the camera file.
IntrinsicPrior StatedPrior(std::string parameter, double value, double sigma);

// Holds lens parameters by name at the start's values (the option "hold"): fx and fy together, cx
// and cy together, s, or distortion terms (which leave options.free_distortion). Throws InputError
// for half a pair, a name that is not estimated, s with free_skew, or a name that also has a prior.
void HoldIntrinsics(const std::vector<std::string>& names, RefineOptions* options);

// What `options` holds for a camera in `model`'s layout (`params`), in layout order.
std::vector<HeldIntrinsic> HeldIntrinsics(const AnyLensModel& model, const std::vector<double>& params,
                                          const RefineOptions& options);

}  // namespace vstcal
