#include "vstcal/image/undistort.h"

#include <Eigen/LU>
#include <opencv2/imgproc.hpp>

namespace vstcal {

PixelMap RectifyMap(const Camera& camera, const Eigen::Matrix3d& camera_from_rect, const Eigen::Matrix3d& rect_K, ImageSize size) {
  PixelMap map;
  map.size = size;
  const size_t n = static_cast<size_t>(size.width) * static_cast<size_t>(size.height);
  map.x.assign(n, -1.0f);
  map.y.assign(n, -1.0f);
  const Eigen::Matrix3d ray_from_pixel = camera_from_rect * rect_K.inverse();
  // Beyond the lens's valid disc a ray can fold back into the image: left black rather than wrong.
  const double valid_r2 = camera.ValidRadiusSquared();
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const Eigen::Vector3d ray = ray_from_pixel * Eigen::Vector3d(u, v, 1);
      if (!(ray.z() > 0) || ray.head<2>().squaredNorm() / (ray.z() * ray.z()) > valid_r2) continue;
      const std::optional<Eigen::Vector2d> px = camera.Project(ray);
      if (!px) continue;
      const size_t k = static_cast<size_t>(v) * static_cast<size_t>(size.width) + static_cast<size_t>(u);
      map.x[k] = static_cast<float>(px->x());
      map.y[k] = static_cast<float>(px->y());
    }
  }
  return map;
}

PixelMap UndistortMap(const Camera& camera) {
  return RectifyMap(camera, Eigen::Matrix3d::Identity(), camera.K(), camera.image_size);
}

GrayImage Remap(const GrayImage& image, const PixelMap& map) {
  const cv::Mat in(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const cv::Mat mx(map.size.height, map.size.width, CV_32F, const_cast<float*>(map.x.data()));
  const cv::Mat my(map.size.height, map.size.width, CV_32F, const_cast<float*>(map.y.data()));
  GrayImage out(map.size.width, map.size.height, 0);
  cv::Mat dst(out.height, out.width, CV_8U, out.pixels.data());
  // OpenCV's remap samples with pixel centres at integers, as vstcal's convention.
  cv::remap(in, dst, mx, my, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
  return out;
}

}  // namespace vstcal
