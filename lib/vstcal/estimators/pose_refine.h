// Levenberg–Marquardt on one rigid pose seen by one or more cameras fixed to it, through the one
// projection (docs/math/stereo.md#pose-refinement):
//
//   minimise over body_from_world   Σ_sets Σ_i |project_k(camera_from_body_k · body_from_world · X_i) − u_i|²
//
// A step is a left perturbation body_from_world' = (Exp ω, ρ) · body_from_world; with p the point
// in the body frame and x = camera_from_body · p, the Jacobian of a pixel is
// ∂u/∂x · R_cb · [−[p]× | I] (∂u/∂x from LensModel::ProjectWithJacobians). Mono PnP is one set with
// camera_from_body = I; the joint binocular registration is two sets, the right one with
// camera_from_body = right_from_left.
#pragma once

#include <optional>
#include <span>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/estimators/pnp.h"

namespace vstcal {

// One camera's observations of world points.
struct PoseObservations {
  const Camera* camera = nullptr;
  Rigid3d camera_from_body;  // identity when the camera is the body
  std::span<const Eigen::Vector3d> points_in_world;
  std::span<const Eigen::Vector2d> pixels;  // one per point
};

struct PoseRefineOptions {
  int max_iterations = 200;
  // Converged when an accepted step moves the predicted pixels by less than this, RMS over the
  // observations (px: √(δᵀJᵀJδ / n)), or when no damping lowers the cost any more. A criterion in
  // pixels, not in the pose: a planar target's pose can slide along a nearly flat valley of the
  // cost (its tilt is poorly determined), where a step that changes no pixel is not worth taking.
  double pixel_tolerance = 1e-6;
  // Converged when an accepted step lowers the cost by less than this fraction: along such a valley
  // Gauss–Newton converges only linearly, and the rest of the way changes no pixel that matters.
  double cost_tolerance = 1e-10;
};

struct PoseRefinement {
  PoseStatus status = PoseStatus::kNotConverged;
  Rigid3d body_from_world;
  int iterations = 0;
  double cost = 0;  // Σ |r|², px²
  size_t residuals = 0;  // observations (2 numbers each)
};

// From `start`; kNoSolution when a point of the start is behind its camera.
PoseRefinement RefinePose(std::span<const PoseObservations> sets, const Rigid3d& start,
                          const PoseRefineOptions& options = {});

// Refines `start` and, where a planar layout left a second branch (`mirrored`, pnp.h), that one
// too, over `sets`; keeps the lower cost. `iterations` sums both refinements.
PoseRefinement RefineBranches(std::span<const PoseObservations> sets, const Rigid3d& start,
                              const std::optional<Rigid3d>& mirrored, const PoseRefineOptions& options = {});

// One camera's pose from ≥ 4 world points and their pixels, end to end: fewer than 4 points or
// collinear ones are refused (status), then the closed form (pnp.h) is refined; for a planar
// layout the mirrored branch is refined too and the lower cost kept. `iterations` sums both.
PoseRefinement SolvePnp(const Camera& camera, std::span<const Eigen::Vector3d> points_in_world,
                        std::span<const Eigen::Vector2d> pixels, const PoseRefineOptions& options = {});

}  // namespace vstcal
