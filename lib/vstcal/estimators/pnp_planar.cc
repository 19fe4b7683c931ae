#include <Eigen/SVD>
#include <cmath>
#include <vector>

#include "vstcal/estimators/homography.h"
#include "vstcal/estimators/pnp_starts.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal::pnp_starts {

// ---- Coplanar points: the homography of their plane, H ∝ [r1 r2 t] in the plane's frame.
ClosedFormPose PlanarPose(std::span<const Eigen::Vector3d> world, std::span<const Eigen::Vector3d> rays, const Spread& s) {
  // plane_from_world: x, y along the two main axes, z along the normal (right-handed).
  Rigid3d plane_from_world;
  plane_from_world.R.row(0) = s.axes.col(0).transpose();
  plane_from_world.R.row(1) = s.axes.col(1).transpose();
  plane_from_world.R.row(2) = s.axes.col(0).cross(s.axes.col(1)).transpose();
  plane_from_world.t = -(plane_from_world.R * s.centroid);
  std::vector<Observation> on_plane(world.size());
  for (size_t i = 0; i < world.size(); ++i) {
    on_plane[i].point << (plane_from_world * world[i]).head<2>(), 0;
    on_plane[i].pixel = rays[i].head<2>();
  }
  const auto H = EstimateHomography(on_plane);
  if (!H) return {};
  Eigen::Matrix<double, 3, 2> r12 = H->leftCols<2>();
  const double scale = 0.5 * (r12.col(0).norm() + r12.col(1).norm());
  Eigen::Vector3d t = H->col(2) / scale;
  r12 /= scale;
  if (t.z() < 0) {  // H's sign is free: the plane is in front
    t = -t;
    r12 = -r12;
  }
  // The nearest pair of orthonormal columns (polar decomposition), then r3 = r1 × r2.
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 2>> svd(r12, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix<double, 3, 2> orthonormal = svd.matrixU().leftCols<2>() * svd.matrixV().transpose();
  Rigid3d camera_from_plane;
  camera_from_plane.R << orthonormal.col(0), orthonormal.col(1), orthonormal.col(0).cross(orthonormal.col(1));
  camera_from_plane.t = t;
  ClosedFormPose pose{PoseStatus::kOk, camera_from_plane * plane_from_world, std::nullopt};
  // The mirrored branch: the normal n reflected about the line of sight ŝ to the centroid (the
  // plane frame's origin, at t), n' = 2(n·ŝ)ŝ − n, by the rotation about n × n' through the centroid.
  const Eigen::Vector3d n = camera_from_plane.R.col(2), sight = t.normalized();
  const Eigen::Vector3d mirrored = 2 * n.dot(sight) * sight - n;
  const Eigen::Vector3d axis = n.cross(mirrored);
  if (axis.norm() > 1e-9) {
    const Eigen::Vector3d rotvec = axis.normalized() * std::atan2(axis.norm(), n.dot(mirrored));
    pose.mirrored = Rigid3d{RotationFromRotvec(rotvec) * camera_from_plane.R, t} * plane_from_world;
  }
  return pose;
}

}  // namespace vstcal::pnp_starts
