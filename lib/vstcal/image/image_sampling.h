// Reading a GrayImage between pixel centres (pixel (u, v)'s centre at integer (u, v)).
#pragma once

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "vstcal/image/image.h"

namespace vstcal {

// Bilinear interpolation; outside the image the nearest border pixel.
inline double SampleBilinear(const GrayImage& image, const Eigen::Vector2d& p) {
  const double x = std::clamp(p.x(), 0.0, image.width - 1.0), y = std::clamp(p.y(), 0.0, image.height - 1.0);
  const int u = std::min(static_cast<int>(x), image.width - 2 < 0 ? 0 : image.width - 2);
  const int v = std::min(static_cast<int>(y), image.height - 2 < 0 ? 0 : image.height - 2);
  const int u1 = std::min(u + 1, image.width - 1), v1 = std::min(v + 1, image.height - 1);
  const double fx = x - u, fy = y - v;
  return (1 - fy) * ((1 - fx) * image.at(u, v) + fx * image.at(u1, v)) + fy * ((1 - fx) * image.at(u, v1) + fx * image.at(u1, v1));
}

}  // namespace vstcal
