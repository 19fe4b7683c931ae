// The closed-form starts of SolvePnpClosedForm (pnp.h), one translation unit each: GCC's
// instantiation of Eigen's fixed-size decompositions grows faster than linearly within a unit, and
// the three together in pnp.cc took 102 CPU-s to compile against 30 s apart
// (docs/performance.md#build). Internal to the estimators.
#pragma once

#include <span>

#include <Eigen/Core>

#include "vstcal/estimators/pnp.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::pnp_starts {

// Centroid, principal axes (columns, by decreasing spread) and the spread σ along each (the square
// roots of the scatter matrix's eigenvalues).
struct Spread {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();
  Eigen::Vector3d sigma = Eigen::Vector3d::Zero();
};

// Σ |p̂ − ray|² over the points in the camera's normalized image plane; infinite if a point is
// behind the camera.
double ReprojectionError(const Rigid3d& camera_from_world, std::span<const Eigen::Vector3d> world,
                         std::span<const Eigen::Vector3d> rays);

// EPnP (Lepetit, Moreno-Noguer & Fua 2009) for 6 or more points in space.
ClosedFormPose EpnpPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays, const Spread& s);
// Grunert's P3P on the largest triangle, for 4 or 5 points in space.
ClosedFormPose FewPointsPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays);
// The homography of the points' plane, with the mirrored branch.
ClosedFormPose PlanarPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays, const Spread& s);

}  // namespace vstcal::pnp_starts
