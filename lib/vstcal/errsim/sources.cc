#include "vstcal/errsim/sources.h"

#include <algorithm>
#include <vector>

namespace vstcal::errsim {

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

namespace {

size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

std::optional<std::string_view> ClosestMatch(std::string_view word, std::span<const std::string_view> candidates) {
  std::optional<std::string_view> best;
  size_t best_distance = std::max<size_t>(1, word.size() / 3) + 1;
  for (const std::string_view c : candidates) {
    const size_t d = EditDistance(word, c);
    if (d < best_distance) {
      best_distance = d;
      best = c;
    }
  }
  return best;
}

std::string SuggestKey(std::string_view word, std::span<const std::string_view> candidates) {
  std::string known;
  for (const std::string_view c : candidates) known += (known.empty() ? "" : ", ") + std::string(c);
  const auto match = ClosestMatch(word, candidates);
  if (match) return "did you mean \"" + std::string(*match) + "\"? (known: " + known + ")";
  return "use one of " + known;
}

}  // namespace vstcal::errsim
