// vstcal/handeye@1 (calib-handeye solve's output, read by err-sim's chain): the reader, then what it
// read written again and read back to a fixed point (docs/formats.md#handeye).
#include "harness.h"
#include "vstcal/formats/handeye/handeye_io.h"

VSTCAL_FUZZ_TARGET(handeye, text) {
  using namespace vstcal;
  const auto write = [](const HandEyeMeasurement& m) { return DumpJson(HandEyeToJson(m.solution, m.length_unit, fuzz::kProvenance)); };
  const std::string json = write(HandEyeFromJson(JsonDocument::Parse(text, "fuzz.json")));
  fuzz::RequireFixedPoint(json, [&](const std::string& s) { return write(HandEyeFromJson(JsonDocument::Parse(s, "fuzz.json"))); });
}
