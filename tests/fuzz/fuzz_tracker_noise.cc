// vstcal/tracker-noise@1 (calib-handeye noise's output, read by err-sim's chain): the reader, then
// what it read written again and read back to a fixed point (docs/formats.md#tracker-noise).
#include "harness.h"
#include "vstcal/formats/handeye/handeye_io.h"

VSTCAL_FUZZ_TARGET(tracker_noise, text) {
  using namespace vstcal;
  const auto write = [](const TrackerNoiseMeasurement& m) { return DumpJson(TrackerNoiseToJson(m.noise, m.length_unit, fuzz::kProvenance)); };
  const std::string json = write(TrackerNoiseFromJson(JsonDocument::Parse(text, "fuzz.json")));
  fuzz::RequireFixedPoint(json, [&](const std::string& s) { return write(TrackerNoiseFromJson(JsonDocument::Parse(s, "fuzz.json"))); });
}
