// Synthetic calibration volumes (seed 000 §4.1, Fig. 3): a planar template of grid corners moved
// along its normal at fixed steps between a near and a far plane, seen by a known camera, with
// Gaussian pixel noise from a counter-based stream; plus seed 000's five test points (Fig. 4).
// Geometry and defaults: docs/tools/calib-synth.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

// World frame: X right and Y down in the template plane, Z along the template's motion (away
// from the camera); the template grid is centred on X = Y = 0 and sits at Z = plane offset.
struct VolumeSpec {
  int grid_cols = 13;      // corners along X
  int grid_rows = 9;       // corners along Y
  double spacing = 100;    // corner spacing, length unit
  double near = 0;         // first template offset (world Z)
  double far = 2000;       // last template offset; planes at near, near + interval, … ≤ far
  double interval = 200;   // step between template positions
  double camera_distance = 2000;  // camera centre to the near plane along the normal at tilt 0
  double tilt_deg = 0;            // angle between the optical axis and the template normal
  double tilt_direction_deg = 0;  // where the camera moves as it tilts: 0 = towards +X, 90 = +Y
  double roll_deg = 0;            // rotation of the camera about its optical axis
  double noise_px = 0;            // σ of the Gaussian noise on u and on v, px
  uint64_t seed = 1;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  std::string camera_name;  // "camera" field of the output
};

struct SyntheticVolume {
  Correspondences correspondences;  // noisy pixels, points outside the image dropped
  Rigid3d camera_from_world;        // ground truth pose
};

// The camera's pose for a spec: on a sphere around the volume centre (0, 0, (near + far)/2) of
// radius camera_distance + (far − near)/2, looking at the centre, image y along world +Y.
Rigid3d VolumeCameraPose(const VolumeSpec& spec);

// Seed 000's five test points (Fig. 4): "Left" 440 mm beyond the template's left edge and
// "Right" 160 mm beyond its right edge (outside the measured volume, at mid depth), and
// "Middle 1–3" inside it at ¼, ½ and ¾ depth. Lengths converted to spec.length_unit.
std::vector<TestPoint> Seed000TestPoints(const VolumeSpec& spec);

// Throws InputError (naming the flag-like field) for impossible specs: non-positive spacing or
// interval, far < near, a length beyond limits::kMaxSyntheticScale, more planes than
// limits::kMaxViews or points than limits::kMaxPoints, a camera inside the volume, no visible
// point, a test point outside the image or behind the camera.
SyntheticVolume SynthesizeVolume(const Camera& camera, const VolumeSpec& spec, std::vector<TestPoint> test_points);

// The ground truth as a vstcal/camera@1 file holds it: the camera, camera_from_world (P = K[R | t]
// is written from them), method "synthetic", and the fit of the true camera to the noisy pixels
// (its rms_px is the noise actually drawn, about σ·√2).
CalibratedCamera VolumeTruthCamera(const Camera& camera, const VolumeSpec& spec, const SyntheticVolume& volume);

}  // namespace vstcal
