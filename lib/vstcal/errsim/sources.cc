#include "vstcal/errsim/sources.h"

#include <algorithm>
#include <vector>

namespace vstcal {

std::optional<Source> SourceFromKey(std::string_view key) {
  for (int i = 0; i < kNumSources; ++i) {
    if (kSourceKeys[i] == key) return static_cast<Source>(i);
  }
  return std::nullopt;
}

std::string_view SourceCorrection(Source source) {
  switch (source) {
    case Source::kTrackerAlignment:
      return "measure tracker_from_world (the virtual-world origin) instead of setting it by hand: a "
             "single-point alignment (Baillot et al., seed 001 §2) or a closed-loop system calibration (§6)";
    case Source::kTracking:
      return "improve tracking: more or better placed sensors (§4.2), and shorten or predict the pose latency "
             "(latency minimization, predictive tracking, §2)";
    case Source::kCameraExtrinsic:
      return "calibrate camera_from_hmd closed-loop against the tracked HMD instead of trusting the mount "
             "drawing (§6, closed-loop calibration)";
    case Source::kCameraIntrinsic:
      return "re-calibrate the intrinsics with a calibration volume (DLT/Tsai, §5.1; calib-dlt) and model the "
             "lens distortion (§5.2) instead of the factory profile";
    case Source::kRendering:
      return "improve the real-scene depth used for occlusion (resolution, algorithm, §4.5) and shorten the "
             "render path (just-in-time image generation, §2)";
    case Source::kDisplay:
      return "fit the HMD to the user: measure the IPD and eyepoint per user and per adjustment (§4.6), "
             "calibrate the screen mapping and lens distortion, shorten the display path";
    case Source::kVirtualObjectAlignment:
      return "register the virtual object closed-loop (task registration, §6): more fiducials, spread wider "
             "around the working volume, localized more accurately";
  }
  return "";
}

}  // namespace vstcal
