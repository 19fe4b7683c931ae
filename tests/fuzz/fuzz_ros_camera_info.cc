// ROS camera_info YAML: the reader (libyaml behind the tree's limits) and the writer's fixed point
// (docs/formats.md#ros-camera-info).
#include "harness.h"
#include "vstcal/formats/camera/ros_camera_info.h"

VSTCAL_FUZZ_TARGET(ros_camera_info, text) {
  using namespace vstcal;
  RosCameraInfoFromText(text, "fuzz.yaml", LengthUnit::kMillimetre);
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    return RosCameraInfoText(RosCameraInfoFromText(s, "fuzz.yaml", LengthUnit::kMillimetre), "fuzz.yaml",
                             fuzz::kProvenance)
        .text;
  });
}
