#include "vstcal/capture/aruco_tags.h"

#include <opencv2/aruco.hpp>

#include "vstcal/capture/search_image.h"

namespace vstcal {

ArucoSearch FindArucoTags(const GrayImage& image, int dictionary, int border_cells, MarkerSearch where) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const SearchImage search = where == MarkerSearch::kReduced ? ReduceForSearch(gray) : SearchImage{gray, 1};
  const cv::Ptr<cv::aruco::DetectorParameters> params = cv::aruco::DetectorParameters::create();
  params->markerBorderBits = border_cells;
  if (border_cells >= 2) {
    // Kalibr's aprilgrid: 10 cells across a tag, so a tag of 34–40 px has cells of 3.4–4 px, and
    // OpenCV's default sampling (4 px a cell, ignoring 0.13 of a cell at each side: no pixel)
    // mixes neighbouring cells. 6 px a cell with 0.3 ignored (1 px each side) reads the cells'
    // middles: on 640×480 renders of tags 34, 37, 40 px, 135/136/141 of 144 tags decoded instead of
    // 129/136/134, tilted 45°–60° 70/79/99 instead of 53/69/88 (docs/experiments/corners.md#aprilgrid).
    // The cost is the same: a 12 MP view 0.37–0.40 s of CPU either way, a 640×480 one 5 ms.
    params->perspectiveRemovePixelPerCell = 6;
    params->perspectiveRemoveIgnoredMarginPerCell = 0.3;
  }
  std::vector<std::vector<cv::Point2f>> corners, rejected;
  std::vector<int> ids;
  cv::aruco::detectMarkers(search.image, cv::aruco::getPredefinedDictionary(dictionary), corners, ids, params, rejected);
  ArucoSearch out;
  out.factor = search.factor;
  out.tags.resize(ids.size());
  for (size_t k = 0; k < ids.size(); ++k) {
    out.tags[k].id = ids[k];
    for (int c = 0; c < 4; ++c) out.tags[k].corners[c] = ToFullResolution(search.factor, corners[k][c].x, corners[k][c].y);
  }
  for (const std::vector<cv::Point2f>& q : rejected) {
    double perimeter = 0;
    for (size_t c = 0; c < q.size(); ++c) perimeter += cv::norm(q[(c + 1) % q.size()] - q[c]);
    out.undecoded_sides_px.push_back(search.factor * perimeter / 4);
  }
  return out;
}

int ArucoDictionaryOfAprilTagFamily(std::string_view family) {
  if (family == "tag36h11") return cv::aruco::DICT_APRILTAG_36h11;
  if (family == "tag36h10") return cv::aruco::DICT_APRILTAG_36h10;
  if (family == "tag25h9") return cv::aruco::DICT_APRILTAG_25h9;
  if (family == "tag16h5") return cv::aruco::DICT_APRILTAG_16h5;
  return -1;
}

}  // namespace vstcal
