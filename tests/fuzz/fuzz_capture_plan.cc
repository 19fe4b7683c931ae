// vstcal/capture-plan@1 as calib-capture plan --compare reads it (docs/formats.md#capture-plan):
// the reader, then the comparison of the plan with itself in both forms (every ratio 1 or null).
#include "harness.h"
#include "vstcal/formats/capture/plan_compare.h"
#include "vstcal/json/json_writer.h"

VSTCAL_FUZZ_TARGET(capture_plan, text) {
  using namespace vstcal;
  const PlanPrediction p = PlanPredictionFromJson(JsonDocument::Parse(text, "fuzz.json"));
  (void)DumpJson(ComparePlansToJson(p, p, fuzz::kProvenance));
  (void)ComparePlansText(p, p);
}
