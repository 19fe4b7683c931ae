// The solver blocks calib-dlt and calib-tsai add to their vstcal/camera@1 output ("dlt", "tsai",
// "refinement", "projection_uncertainty"): docs/formats.md#camera.
#pragma once

#include <optional>
#include <string_view>
#include <vector>

#include "vstcal/calib/pipeline.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {

// "dlt" (when DLT ran), "tsai" (when Tsai ran), "refinement" (when refined).
OrderedJson CalibrationBlocksToJson(const CalibrationResult& result, const CalibrationOptions& options);

// Where the user wants the projection's 1-σ ellipse, besides the test points.
struct UncertaintyRequest {
  std::vector<Eigen::Vector3d> world_points;  // volume rigs
  std::vector<Eigen::Vector3d> pixel_depths;  // (u, v, depth)
  std::optional<double> grid_depth;
  int grid_cols = 16;
  int grid_rows = 9;
};

// What the two kinds of projection uncertainty mean (ProjectionUncertaintyKind), as the camera
// file and the tools' summaries label them.
inline constexpr std::string_view kWithPosesMeaning =
    "the point tied to the calibration object (through camera_from_world, or averaged over every board's pose): "
    "intrinsics and poses vary";
inline constexpr std::string_view kIntrinsicsOnlyMeaning =
    "the point fixed in the camera frame, only the intrinsics vary: what using this camera elsewhere, posed anew, "
    "inherits";

// "projection_uncertainty": both kinds of ellipse at the test points (volume rigs), the requested
// points and pixels, and the grid; null when the camera has no covariance.
OrderedJson UncertaintyToJson(const CalibratedCamera& camera, const UncertaintyRequest& request);

}  // namespace vstcal
