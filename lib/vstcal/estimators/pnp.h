// A camera's pose from world points and their pixels (perspective-n-point), in two steps
// (docs/math/stereo.md#pnp): a closed-form start — EPnP (Lepetit, Moreno-Noguer & Fua, IJCV 2009)
// for points spread in space (Grunert's P3P for 4 or 5 of them), the plane's homography for coplanar
// ones — then Levenberg–Marquardt
// on the 6-DoF pose through the one projection (pose_refine.h). Seed 000 §4.1 tracks four
// embedded points this way; OpenCV's solvePnP is the peer (tests/bench/bench_stereo.cc).
#pragma once

#include <optional>
#include <span>
#include <string_view>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

inline constexpr size_t kMinPnpPoints = 4;

enum class PoseStatus {
  kOk,
  kTooFewPoints,  // fewer than kMinPnpPoints
  kCollinear,     // the points lie on one line: the rotation about it is free
  kNoRay,         // a pixel has no ray (outside the lens model's domain)
  kNoSolution,    // no pose puts the points in front of the camera, or the start failed
  kNotConverged,  // the refinement ran out of iterations
};
// "fewer than 4 points", "the points lie on one line", ... for messages.
std::string_view PoseStatusText(PoseStatus status);

// How points spread, from the singular values σ1 ≥ σ2 ≥ σ3 of their centred coordinates:
// collinear when σ2 ≤ 1e-6 σ1, planar when σ3 ≤ 1e-3 σ1 (the homography start is then better
// conditioned than EPnP's fourth control point), spatial otherwise.
enum class PointLayout { kCollinear, kPlanar, kSpatial };
PointLayout ClassifyLayout(std::span<const Eigen::Vector3d> points);

struct ClosedFormPose {
  PoseStatus status = PoseStatus::kNoSolution;
  Rigid3d camera_from_world;
  // Planar layouts: the other branch of a plane's pose ambiguity — the plane turned about its
  // centroid so that its normal is mirrored about the line of sight, which projects the points to
  // the same pixels to first order (docs/math/stereo.md#pnp). Refine both; keep the lower cost.
  std::optional<Rigid3d> mirrored;
};

// The closed-form start from ≥ 4 points: pixels are unprojected through the camera (distortion
// removed), then EPnP for 6 or more points in space (the best of its N = 1, 2, 3 kernel solutions
// after Gauss–Newton on the betas, by reprojection error), Grunert's P3P on the largest triangle
// for 4 or 5 points in space (the others choose among its solutions), or the homography of the
// points' plane decomposed into [r1 r2 t] (planar layouts). Not a maximum-likelihood estimate:
// refine it.
ClosedFormPose SolvePnpClosedForm(const Camera& camera, std::span<const Eigen::Vector3d> points_in_world,
                                  std::span<const Eigen::Vector2d> pixels);

}  // namespace vstcal
