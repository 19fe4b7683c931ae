// Stereo rectification by OpenCV's stereoRectify (Bouguet's method): each camera turned about its
// centre so that both share one orientation with the baseline along an image axis, and one
// intrinsic matrix, so that matching pixels lie on the same row (docs/math/stereo.md#rectification).
#pragma once

#include <string_view>

#include "vstcal/image/image.h"
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

// A check image of a stereo pair (issue 24 item 4): both images resampled into the rectified
// cameras of `rectification` (vstcal's own maps, image/undistort.h's RectifyMap: P_left's and
// P_right's 3×3, each camera's rect_from_camera), side by side (left | right), with dashed
// horizontal lines every `line_spacing` px: a point of the scene lies on the same row in both
// halves when the rig is right.
GrayImage RectifiedPairImage(const StereoRig& rig, const Rectification& rectification, const GrayImage& left, const GrayImage& right,
                             int line_spacing = 40);

}  // namespace vstcal
