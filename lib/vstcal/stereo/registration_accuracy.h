// How far a binocular registration is from the truth of a synthetic sequence, per frame and over
// the sequence (docs/experiments/binocular-registration.md).
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "vstcal/scene/fit.h"
#include "vstcal/stereo/registration.h"

namespace vstcal {

// Per eye (0 left, 1 right): the angle between the estimated and the true camera_from_world
// rotations, the distance between the estimated and the true camera centres (length unit), and
// the pixel distance between the virtual points projected with the estimated and the true pose
// (the overlay's misregistration, px).
struct FrameAccuracy {
  std::array<double, 2> rotation_deg{};
  std::array<double, 2> centre_error{};
  std::array<ResidualStats, 2> virtual_px{};
};

// nullopt when the frame has no truth or was not registered.
std::optional<FrameAccuracy> AccuracyOf(const StereoRig& rig, const TrackedFrame& frame, const FrameRegistration& registration,
                                        std::span<const NamedPoint> virtual_points);

// Over the registered frames with truth: RMS and max of each quantity, per eye.
struct SequenceAccuracy {
  size_t frames = 0;
  std::array<ResidualStats, 2> rotation_deg{}, centre_error{}, virtual_px{};
};
std::optional<SequenceAccuracy> SummarizeAccuracy(std::span<const std::optional<FrameAccuracy>> frames);

}  // namespace vstcal
