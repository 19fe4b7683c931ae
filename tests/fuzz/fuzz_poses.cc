// vstcal/poses@1 (calib-handeye --poses, .json): the reader and the writer's fixed point
// (docs/formats.md#poses).
#include "harness.h"
#include "vstcal/formats/handeye/pose_log_io.h"

VSTCAL_FUZZ_TARGET(poses, text) {
  using namespace vstcal;
  PoseLogFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    return DumpJson(PoseLogToJson(PoseLogFromJson(JsonDocument::Parse(s, "fuzz.json")), fuzz::kProvenance));
  });
}
