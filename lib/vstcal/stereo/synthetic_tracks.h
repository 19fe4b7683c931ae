// Synthetic tracking sequences with known truth, to measure binocular registration
// (docs/experiments/binocular-registration.md): a rig moving in front of embedded points, the
// points projected through the rig's true cameras, with counter-based Gaussian pixel noise
// (docs/conventions.md#randomness: the same seed gives the same pixels on any machine).
#pragma once

#include <cstdint>

#include "vstcal/scene/stereo_rig.h"
#include "vstcal/scene/tracks.h"

namespace vstcal {

struct SyntheticTracksSpec {
  size_t frames = 100;
  double noise_px = 0.3;     // σ per pixel coordinate
  uint64_t seed = 1;
  bool planar = true;        // seed 000's four coplanar points (a square), else six points in space
  double size = 200;         // side of the square / cube of embedded points, length unit
  double distance = 1000;    // distance of the rig from the embedded points, length unit
};

// Frame k's left_from_world: the left camera about `distance` in front of the points, its view
// swinging through ±9° of yaw, ±6° of pitch and ±3° of roll and its centre through ±10 % of the
// distance, smoothly over the sequence. Eight virtual points surround the embedded ones (a box
// twice their size, some outside their span as seed 000's test points are). Pixels outside an
// image are lost (null). Every frame carries its true pose.
Tracks SyntheticTracks(const StereoRig& rig, const SyntheticTracksSpec& spec);

}  // namespace vstcal
