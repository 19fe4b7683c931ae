// The seven VST error sources of seed 001 §4.1–4.7, under the keys DESIGN.md fixes, and what
// seed 001 suggests against each (§2, §4, §5, §6).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace vstcal {

enum class Source : int {
  kTrackerAlignment = 0,      // §4.1: tracker_from_virtual
  kTracking,                  // §4.2: hmd_from_tracker as measured, and its latency
  kCameraExtrinsic,           // §4.3: camera_from_hmd per eye
  kCameraIntrinsic,           // §4.4: K and distortion per eye
  kRendering,                 // §4.5: real-scene depth (occlusion) and render latency
  kDisplay,                   // §4.6: eyepoints, IPD, screen mapping, lens residual, display latency
  kVirtualObjectAlignment,    // §4.7: virtual_from_object
};
inline constexpr int kNumSources = 7;

inline constexpr std::array<std::string_view, kNumSources> kSourceKeys = {
    "tracker_alignment", "tracking", "camera_extrinsic", "camera_intrinsic",
    "rendering", "display", "virtual_object_alignment"};

inline constexpr std::string_view SourceKey(Source source) { return kSourceKeys[static_cast<int>(source)]; }
std::optional<Source> SourceFromKey(std::string_view key);

// The correction seed 001 suggests for a source, with the section it comes from.
std::string_view SourceCorrection(Source source);

}  // namespace vstcal
