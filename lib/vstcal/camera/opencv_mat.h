// Eigen matrices and a camera's distortion as cv::Mat, for the .cc files that call OpenCV. This
// header includes OpenCV: keep it out of other headers (no OpenCV type is in vstcal's interfaces).
#pragma once

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "vstcal/camera/opencv_distortion.h"

namespace vstcal {

inline cv::Mat ToCvMat(const Eigen::MatrixXd& m) {
  cv::Mat out;
  cv::eigen2cv(m, out);
  return out;
}

// The camera's OpenCV distortion vector, of the shortest length that holds it exactly, as N×1.
inline cv::Mat OpenCvDistortionMat(const Camera& camera) {
  return cv::Mat(OpenCvDistortion(camera, ShortestOpenCvLength(camera)), true);
}

}  // namespace vstcal
