// vstcal/correspondences@1: the reader, the writer's fixed point, and the DLT on what was read
// (docs/formats.md#correspondences).
#include "harness.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace {

std::string CorrespondencesPass(const std::string& text) {
  using namespace vstcal;
  const Correspondences c = CorrespondencesFromJson(JsonDocument::Parse(text, "fuzz.json"));
  return DumpJson(CorrespondencesToJson(c, fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(correspondences, text) {
  using namespace vstcal;
  const Correspondences c = CorrespondencesFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, CorrespondencesPass);
  if (c.rig == Rig::kVolume) {
    DltOptions options;
    options.exact_diagnostics = true;
    const DltResult dlt = SolveDlt(AllObservations(c), options);
    fuzz::Require(dlt.status != DltStatus::kOk || dlt.P.allFinite(), "DLT returned a non-finite P with status ok");
  }
}
