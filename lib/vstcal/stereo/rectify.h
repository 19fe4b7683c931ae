// Stereo rectification by OpenCV's stereoRectify (Bouguet's method): each camera turned about its
// centre so that both share one orientation with the baseline along an image axis, and one
// intrinsic matrix, so that matching pixels lie on the same row (docs/math/stereo.md#rectification).
#pragma once

#include <string_view>

#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

struct RectifyOptions {
  double alpha = -1;           // OpenCV's free scaling: −1 its default, 0 valid pixels only … 1 all pixels
  bool zero_disparity = true;  // CALIB_ZERO_DISPARITY: the principal points at the same pixel
};

// cv::stereoRectify of the rig, at the cameras' image size. Throws InputError (naming `source`,
// e.g. the rig's file) when the two cameras' image sizes differ (stereoRectify takes one size for
// both) or a camera has skew (OpenCV's model has none), and when alpha is neither −1 nor in [0, 1].
Rectification Rectify(const StereoRig& rig, const RectifyOptions& options, std::string_view source);

}  // namespace vstcal
