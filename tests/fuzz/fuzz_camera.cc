// vstcal/camera@1 with views and covariance: the reader, the writer's fixed point, and the
// projection uncertainty computed from what was read (docs/formats.md#camera).
#include "harness.h"
#include "vstcal/formats/calib/calibration_io.h"
#include "vstcal/formats/camera/camera_io.h"

namespace {

std::string CameraPass(const std::string& text) {
  using namespace vstcal;
  return DumpJson(CameraToJson(CameraFromJson(JsonDocument::Parse(text, "fuzz.json")), fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(camera, text) {
  using namespace vstcal;
  const CalibratedCamera c = CameraFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, CameraPass);
  if (c.covariance) {
    UncertaintyRequest request;
    if (c.camera_from_world) request.world_points.emplace_back(0.0, 0.0, 0.0);
    request.pixel_depths.emplace_back(0.5 * c.camera.image_size.width, 0.5 * c.camera.image_size.height, 1000.0);
    request.grid_depth = 1000.0;
    request.grid_cols = 3;
    request.grid_rows = 2;
    DumpJson(UncertaintyToJson(c, request));  // refuses NaN and infinity
  }
}
