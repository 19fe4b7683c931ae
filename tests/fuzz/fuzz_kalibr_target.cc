// Kalibr's target YAML (docs/formats.md#kalibr-target): the reader, and the target it gives written
// as vstcal/target@1 and read back, a fixed point with the same corners.
#include "harness.h"
#include "vstcal/formats/capture/kalibr_target.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/json/json_writer.h"

namespace {

std::string KalibrTargetPass(const std::string& text) {
  using namespace vstcal;
  return DumpJson(TargetToJson(TargetFromJson(JsonDocument::Parse(text, "fuzz.json")), fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(kalibr_target, text) {
  using namespace vstcal;
  const Target t = KalibrTargetFromText(text, "fuzz.yaml");
  fuzz::Require(!CheckTarget(t), "a target read is a checked target");
  const std::string json = DumpJson(TargetToJson(t, fuzz::kProvenance));
  fuzz::RequireFixedPoint(json, KalibrTargetPass);
  const Target back = TargetFromJson(JsonDocument::Parse(json, "fuzz.json"));
  for (int id = 0; id < NumCorners(t); ++id) fuzz::Require(CornerPosition(back, id) == CornerPosition(t, id), "corners kept");
}
