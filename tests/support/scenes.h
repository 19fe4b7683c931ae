// Synthetic scenes shared by unit tests and benchmarks: a known camera looking at random points
// spread through a box, with counter-based pixel noise.
#pragma once

#include <cstdint>
#include <vector>

#include "vstcal/scene/correspondences.h"
#include "vstcal/camera/camera.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal::testing {

struct Scene {
  Camera camera;
  Rigid3d camera_from_world;
  std::vector<Observation> observations;
  std::vector<Eigen::Vector2d> true_pixels;
};

// A 1280×1024 camera with fx 1700, slight skew and off-centre principal point, 2.5–4.5 m from
// `n` points drawn uniformly in a 1.2 × 0.9 × 2 m box (mm), all visible.
Scene RandomVolumeScene(size_t n, double noise_px, uint64_t seed);

// `n` points in a camera frame, 0.3 to 4.3 units in front, with normalized coordinates spread
// uniformly over ±half_width × ±half_height (about ±42° × ±27° for the defaults).
std::vector<Eigen::Vector3d> PointsInFront(int n, uint64_t seed, double half_width = 0.9, double half_height = 0.5);

// A near calibration volume for a wide (ZED-mini-like) camera: a 15×9 grid at 60 mm, moved by
// 100 mm from 500 mm out to 1 m, tilted 8°; noise-free until the caller sets noise_px.
VolumeSpec NearWideVolumeSpec();

// A 1280×720 camera with a ZED-mini-like lens: fx 700.2, fy 698.4, principal point (641.3, 361.7),
// k1 −0.171, k2 0.028, p1 0.0007, p2 −0.0004.
Camera DistortedWideCamera();

// `clean` with fresh Gaussian pixel noise σ on u and v, from the counter-based stream `seed`
// (one draw per observation, in file order): a Monte Carlo trial.
Correspondences WithNoise(const Correspondences& clean, double sigma_px, uint64_t seed);

}  // namespace vstcal::testing
