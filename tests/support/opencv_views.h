// Correspondences as cv::calibrateCamera takes them: one object/image point list per planar view,
// or one list of all of a volume rig's points (one pose), in float32 as OpenCV requires. Shared by
// the tests, the benchmarks and peer_calibrate that run OpenCV beside vstcal on the same data.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "vstcal/scene/correspondences.h"

namespace vstcal::testing {

struct OpenCvViews {
  std::vector<std::vector<cv::Point3f>> object;
  std::vector<std::vector<cv::Point2f>> image;
};

inline OpenCvViews ToOpenCvViews(const Correspondences& c) {
  OpenCvViews d;
  for (const View& v : c.views) {
    if (d.object.empty() || c.rig == Rig::kPlanarViews) {
      d.object.emplace_back();
      d.image.emplace_back();
    }
    for (const Observation& o : v.observations) {
      d.object.back().emplace_back(static_cast<float>(o.point.x()), static_cast<float>(o.point.y()),
                                   static_cast<float>(o.point.z()));
      d.image.back().emplace_back(static_cast<float>(o.pixel.x()), static_cast<float>(o.pixel.y()));
    }
  }
  return d;
}

}  // namespace vstcal::testing
