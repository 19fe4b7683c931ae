// A solved camera: the content of a vstcal/camera@1 file (docs/formats.md#camera).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/scene/fit.h"
#include "vstcal/scene/parameter_covariance.h"
#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

using Matrix34d = Eigen::Matrix<double, 3, 4>;

// One view of a planar-views calibration: the board's pose and how well it fits.
struct ViewPose {
  std::string name;
  Rigid3d camera_from_board;
  double rms_px = 0;
};

struct CalibratedCamera {
  std::string name;  // which camera of a rig ("left"), may be empty
  Camera camera;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  std::string method;                        // "dlt", "tsai", "synthetic", ...
  std::optional<Rigid3d> camera_from_world;  // volume rigs
  std::optional<Matrix34d> P;                // as solved (DLT); else K[R|t] is written
  std::optional<Fit> fit;
  std::vector<ViewPose> views;                   // planar-views rigs
  std::optional<ParameterCovariance> covariance;  // when a solver estimated uncertainty
};

// P = K [R | t], scaled as docs/conventions.md#projection-matrix states.
Matrix34d ProjectionMatrix(const Eigen::Matrix3d& K, const Rigid3d& camera_from_world);

// Scales P so that ‖P(2, 0:3)‖ = 1 and its depth row is positive for points in front of the
// camera. `sign` is +1 or −1 and says on which side the scene lies (from NormalizeDepthSign).
Matrix34d NormalizeProjectionScale(const Matrix34d& P, double sign = 1.0);

}  // namespace vstcal
