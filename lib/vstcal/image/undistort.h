// Check images (issue 24 item 4): an image seen through a calibrated camera, resampled as a pinhole
// camera would have seen it. The maps are vstcal's own (the one projection, camera.h), the
// resampling OpenCV's cv::remap (bilinear); so the check shows this camera model, not OpenCV's.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/image/image.h"

namespace vstcal {

// For every output pixel (u, v) (pixel centres at integers), the input pixel it samples; (−1, −1)
// where no ray of the lens's valid domain reaches it (drawn black).
struct PixelMap {
  ImageSize size;
  std::vector<float> x, y;  // row by row
};

// Undistortion: the output is the pinhole camera with the same K and image size: its pixel p is
// the ray K⁻¹ (p, 1), projected through `camera` (its lens) to the input pixel.
PixelMap UndistortMap(const Camera& camera);

// Rectification (a stereo rig's, docs/math/stereo.md#rectification): the output is the pinhole
// camera `rect_K` of `size` in the rectified frame; its pixel p is the ray rect_K⁻¹ (p, 1) in that
// frame, turned into the camera's frame (camera_from_rect) and projected through `camera`.
PixelMap RectifyMap(const Camera& camera, const Eigen::Matrix3d& camera_from_rect, const Eigen::Matrix3d& rect_K, ImageSize size);

// `image` resampled through `map` (cv::remap, bilinear, black outside).
GrayImage Remap(const GrayImage& image, const PixelMap& map);

}  // namespace vstcal
