#include "vstcal/capture/aruco_tags.h"

#include <opencv2/aruco.hpp>

namespace vstcal {

std::vector<ArucoTag> FindArucoTags(const GrayImage& image, int dictionary, int border_cells) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = border_cells;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(gray, cv::aruco::getPredefinedDictionary(dictionary), corners, ids, params);
  std::vector<ArucoTag> tags(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    tags[k].id = ids[k];
    for (int c = 0; c < 4; ++c) tags[k].corners[c] = Eigen::Vector2d(corners[k][c].x, corners[k][c].y);
  }
  return tags;
}

int ArucoDictionaryOfAprilTagFamily(std::string_view family) {
  if (family == "tag36h11") return cv::aruco::DICT_APRILTAG_36h11;
  if (family == "tag36h10") return cv::aruco::DICT_APRILTAG_36h10;
  if (family == "tag25h9") return cv::aruco::DICT_APRILTAG_25h9;
  if (family == "tag16h5") return cv::aruco::DICT_APRILTAG_16h5;
  return -1;
}

}  // namespace vstcal
