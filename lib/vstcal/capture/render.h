// Renders a printed target seen by a camera: per-pixel inverse mapping through the one projection
// (Camera::UnprojectRay, any lens model, past 90° for a fisheye) with exact area coverage as anti-aliasing, then optional
// uneven lighting, Gaussian blur and Gaussian noise (docs/math/rendering.md).
//
// Pixel (u, v) integrates the scene over its square [u − ½, u + ½] × [v − ½, v + ½] (a box
// filter, 100 % fill factor). Its four corners are unprojected to rays and intersected with the
// board plane; the quadrilateral they bound is the pixel's footprint on the board, and the exact
// areas of its intersections with the black cells and the sheet give the pixel's grey level:
//   I = background·(1 − f_sheet) + white·(f_sheet − f_black) + black·f_black
// (fractions of the footprint's area). Lighting multiplies I by a gain ramp; blur convolves with
// a normalised Gaussian (replicated border); noise adds N(0, σ²) per pixel from a Philox stream
// keyed by (seed, view, pixel); the result is rounded to 8 bits. Everything is in double without
// threads inside a view: the same inputs give the same bytes on any x86-64 machine.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/image/image.h"
#include "vstcal/capture/pattern.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

struct RenderOptions {
  double white = 220;       // grey level of the paper
  double black = 30;        // grey level of the ink
  double background = 110;  // grey level around the sheet
  double blur_px = 0;       // σ of the Gaussian blur, px (0: none)
  double noise = 0;         // σ of the Gaussian noise, grey levels (0: none)
  double lighting = 0;      // gain falls linearly across the image from 1 to 1 − lighting, in [0, 1)
  double lighting_direction_deg = 30;  // direction of the fall, from +u towards +v
  uint64_t seed = 1;
};

// The rays through the corners of every pixel: (W + 1) × (H + 1) points (u, v) = (i − ½, j − ½),
// unprojected once per camera and reused for every pose. A corner outside the lens model's
// domain has no ray.
class PixelCornerRays {
 public:
  explicit PixelCornerRays(const Camera& camera);
  int width() const { return width_; }    // image width W
  int height() const { return height_; }  // image height H
  // Ray (x, y, 1) through corner (i, j), 0 ≤ i ≤ W, 0 ≤ j ≤ H; valid() false where there is none.
  const Eigen::Vector3d& ray(int i, int j) const { return rays_[Index(i, j)]; }
  bool valid(int i, int j) const { return valid_[Index(i, j)] != 0; }

 private:
  size_t Index(int i, int j) const { return static_cast<size_t>(j) * (width_ + 1) + i; }
  int width_, height_;
  std::vector<Eigen::Vector3d> rays_;
  std::vector<uint8_t> valid_;
};

// The image of `pattern` (board frame) at pose camera_from_board. `view` keys the noise stream.
GrayImage RenderView(const PixelCornerRays& rays, const Pattern& pattern, const Rigid3d& camera_from_board,
                     const RenderOptions& options, uint32_t view);

// The noise-free, unblurred, unlit grey level of every pixel as doubles (the first stage above).
std::vector<double> RenderCoverage(const PixelCornerRays& rays, const Pattern& pattern, const Rigid3d& camera_from_board,
                                   const RenderOptions& options);

}  // namespace vstcal
