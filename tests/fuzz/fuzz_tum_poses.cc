// TUM trajectory text (calib-handeye --poses, any other extension): the reader, then its log
// written as poses@1 and read back to a fixed point (docs/formats.md#poses).
#include "harness.h"
#include "vstcal/formats/handeye/pose_log_io.h"

VSTCAL_FUZZ_TARGET(tum_poses, text) {
  using namespace vstcal;
  const PoseLog log = PoseLogFromTum(text, "fuzz.txt", LengthUnit::kMetre);
  const std::string json = DumpJson(PoseLogToJson(log, fuzz::kProvenance));
  fuzz::RequireFixedPoint(json, [](const std::string& s) {
    return DumpJson(PoseLogToJson(PoseLogFromJson(JsonDocument::Parse(s, "fuzz.json")), fuzz::kProvenance));
  });
}
