// vstcal/target@1 (docs/formats.md#target): the reader, the writer's fixed point, and the corners
// and marker squares of what was read.
#include "harness.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/json/json_writer.h"

namespace {

std::string TargetPass(const std::string& text) {
  using namespace vstcal;
  return DumpJson(TargetToJson(TargetFromJson(JsonDocument::Parse(text, "fuzz.json")), fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(target, text) {
  using namespace vstcal;
  const Target t = TargetFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, TargetPass);
  fuzz::Require(static_cast<int>(TargetCorners(t).size()) == NumCorners(t), "corner count");
  (void)MarkerQuads(t);
}
