// Residuals of a calibrated camera against correspondences: per point, per view, overall, and at
// the test points (registration error, seed 000 §4.2). Residual = predicted − measured, px.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/camera/camera.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

struct ResidualStats {
  double rms_px = 0;  // sqrt(mean(|r|²)) over points
  double max_px = 0;  // max |r|
  size_t n_points = 0;
};

struct ViewFit {
  std::string name;
  ResidualStats stats;
  std::vector<Eigen::Vector2d> residuals_px;  // one per observation, in file order
};

struct TestPointFit {
  std::string name;
  Eigen::Vector3d point_in_world;
  std::optional<Eigen::Vector2d> predicted;  // nullopt when the point is behind the camera
  std::optional<Eigen::Vector2d> measured;
  // Inside (or on) the convex hull of the calibration points (`Fit::volume`); nullopt when they
  // span no volume: the point is then neither inside nor outside.
  std::optional<bool> inside_volume;

  std::optional<double> error_px() const {
    if (!predicted || !measured) return std::nullopt;
    return (*predicted - *measured).norm();
  }
};

struct Fit {
  ResidualStats overall;
  std::vector<ViewFit> views;
  std::vector<TestPointFit> test_points;
  std::optional<MeasuredVolume> volume;  // volume rigs: the calibration points' convex hull
  size_t n_behind_camera = 0;  // observations that project behind the camera (not in stats)
};

// Residuals of `camera` posed by `camera_from_world` for a volume rig (one pose for all views),
// with the test points.
Fit ComputeVolumeFit(const Camera& camera, const Rigid3d& camera_from_world, const Correspondences& c);

// Residuals with one pose per view: camera_from_view[i] maps view i's frame (its board for
// planar views) to the camera. No test points: they need a world frame.
Fit ComputeViewsFit(const Camera& camera, std::span<const Rigid3d> camera_from_view, const Correspondences& c);

ResidualStats Summarize(const std::vector<Eigen::Vector2d>& residuals_px);

}  // namespace vstcal
