// vstcal/stereo@1: the reader (both cameras, right_from_left, covariance, rectification checked
// against the rig), the writer's fixed point, and the baseline σ from what was read
// (docs/formats.md#stereo).
#include <cmath>

#include "harness.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/scene/stereo_rig.h"

namespace {

std::string StereoPass(const std::string& text) {
  using namespace vstcal;
  return DumpJson(StereoRigToJson(StereoRigFromJson(JsonDocument::Parse(text, "fuzz.json")), fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(stereo, text) {
  using namespace vstcal;
  const StereoRig rig = StereoRigFromJson(JsonDocument::Parse(text, "fuzz.json"));
  fuzz::RequireFixedPoint(text, StereoPass);
  if (const auto sigma = BaselineSigma(rig)) VSTCAL_CHECK(std::isfinite(*sigma), "a non-finite baseline sigma");
}
