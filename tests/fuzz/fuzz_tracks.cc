// vstcal/tracks@1 (calib-stereo register's input): the reader and the writer's fixed point
// (docs/formats.md#tracks).
#include "harness.h"
#include "vstcal/formats/stereo/registration_io.h"

VSTCAL_FUZZ_TARGET(tracks, text) {
  using namespace vstcal;
  TracksFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    return DumpJson(TracksToJson(TracksFromJson(JsonDocument::Parse(s, "fuzz.json")), fuzz::kProvenance));
  });
}
