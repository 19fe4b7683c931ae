#include "vstcal/stereo/rectify.h"

#include "vstcal/image/undistort.h"

#include <opencv2/calib3d.hpp>

#include "vstcal/camera/opencv_mat.h"
#include "vstcal/core/error.h"
#include "vstcal/camera/opencv_distortion.h"

namespace vstcal {
namespace {

template <int Rows, int Cols>
Eigen::Matrix<double, Rows, Cols> FromCv(const cv::Mat& m) {
  Eigen::Matrix<double, Rows, Cols> out;
  cv::cv2eigen(m, out);
  return out;
}

}  // namespace

Rectification Rectify(const StereoRig& rig, const RectifyOptions& options, std::string_view source) {
  const ImageSize size = rig.left.camera.image_size;
  if (!(rig.right.camera.image_size == size)) {
    throw InputError(std::string(source) + ": right.image_size: " + std::to_string(rig.right.camera.image_size.width) +
                     "×" + std::to_string(rig.right.camera.image_size.height) + ", but the left camera's is " +
                     std::to_string(size.width) + "×" + std::to_string(size.height) +
                     "; OpenCV's stereoRectify takes one image size for both cameras: calibrate them at one size");
  }
  if (!(options.alpha == -1 || (options.alpha >= 0 && options.alpha <= 1))) {
    throw InputError("alpha: must be -1 or lie in [0, 1], got " + std::to_string(options.alpha) +
                     "; give OpenCV's free scaling parameter");
  }
  RefuseSkew(rig.left.camera, std::string(source) + ": left", "OpenCV's stereoRectify");
  RefuseSkew(rig.right.camera, std::string(source) + ": right", "OpenCV's stereoRectify");
  for (const auto& [camera, side] : {std::pair{&rig.left.camera, ": left"}, std::pair{&rig.right.camera, ": right"}}) {
    RefuseNonOpenCvModel(*camera, std::string(source) + side, "OpenCV's stereoRectify (a fisheye rig needs cv::fisheye::stereoRectify)",
                         "rectify the fisheye rig with cv::fisheye::stereoRectify from each camera's OpenCV YAML");
  }
  cv::Mat R1, R2, P1, P2, Q;
  cv::Rect roi1, roi2;
  cv::stereoRectify(ToCvMat(rig.left.camera.K()), OpenCvDistortionMat(rig.left.camera), ToCvMat(rig.right.camera.K()),
                    OpenCvDistortionMat(rig.right.camera), cv::Size(size.width, size.height), ToCvMat(rig.right_from_left.R),
                    ToCvMat(rig.right_from_left.t), R1, R2, P1, P2, Q, options.zero_disparity ? cv::CALIB_ZERO_DISPARITY : 0,
                    options.alpha, cv::Size(), &roi1, &roi2);
  Rectification r;
  r.alpha = options.alpha;
  r.zero_disparity = options.zero_disparity;
  r.left_rect_from_left = FromCv<3, 3>(R1);
  r.right_rect_from_right = FromCv<3, 3>(R2);
  r.P_left = FromCv<3, 4>(P1);
  r.P_right = FromCv<3, 4>(P2);
  r.Q = FromCv<4, 4>(Q);
  r.valid_roi_left = {roi1.x, roi1.y, roi1.width, roi1.height};
  r.valid_roi_right = {roi2.x, roi2.y, roi2.width, roi2.height};
  return r;
}

GrayImage RectifiedPairImage(const StereoRig& rig, const Rectification& r, const GrayImage& left, const GrayImage& right, int line_spacing) {
  const ImageSize size = rig.left.camera.image_size;
  const GrayImage l = Remap(left, RectifyMap(rig.left.camera, r.left_rect_from_left.transpose(), r.P_left.leftCols<3>(), size));
  const GrayImage rr = Remap(right, RectifyMap(rig.right.camera, r.right_rect_from_right.transpose(), r.P_right.leftCols<3>(), size));
  GrayImage pair(2 * size.width, size.height, 0);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      pair.at(u, v) = l.at(u, v);
      pair.at(size.width + u, v) = rr.at(u, v);
    }
  }
  // Dashed, black and white, so that a line shows on dark and light alike.
  for (int v = line_spacing / 2; line_spacing > 0 && v < size.height; v += line_spacing) {
    for (int u = 0; u < pair.width; ++u) pair.at(u, v) = (u / 8) % 2 ? 255 : 0;
  }
  return pair;
}

}  // namespace vstcal
