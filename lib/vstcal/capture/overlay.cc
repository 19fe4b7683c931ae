#include "vstcal/capture/overlay.h"

#include <algorithm>
#include <map>

#include <opencv2/imgproc.hpp>

#include "vstcal/core/error.h"
#include "vstcal/image/codecs.h"

namespace vstcal {

std::string OverlayPng(const GrayImage& image, const Target& target, const Detection& detection) {
  const cv::Mat gray(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  cv::Mat bgr;
  cv::cvtColor(gray, bgr, cv::COLOR_GRAY2BGR);
  const double scale = std::max(1.0, std::min(image.width, image.height) / 480.0);
  const int thickness = std::max(1, static_cast<int>(scale));
  auto point = [](const Eigen::Vector2d& p) { return cv::Point2d(p.x(), p.y()); };
  std::map<int, Eigen::Vector2d> by_id;
  for (const DetectedCorner& c : detection.corners) by_id[c.id] = c.pixel;
  // The axes from the lowest id: along its row (+X) and down its column (+Y).
  if (!by_id.empty()) {
    const int origin = by_id.begin()->first;
    // Tag corners 0 → 1 and 0 → 3; grid corners one column and one row on (Kalibr's aprilgrid
    // numbers its rows up the sheet: its arrow is Kalibr's y, −Y).
    const int step_x = 1, step_y = target.type == TargetType::kAprilTagGrid ? 3
                                   : target.type == TargetType::kAprilGrid  ? 2 * target.cols
                                                                            : target.cols;
    if (by_id.count(origin + step_x)) cv::arrowedLine(bgr, point(by_id[origin]), point(by_id[origin + step_x]), {0, 0, 255}, 2 * thickness, cv::LINE_AA);
    if (by_id.count(origin + step_y)) cv::arrowedLine(bgr, point(by_id[origin]), point(by_id[origin + step_y]), {0, 200, 0}, 2 * thickness, cv::LINE_AA);
  }
  const cv::Scalar colour = detection.status == DetectionStatus::kFound ? cv::Scalar(255, 160, 0) : cv::Scalar(0, 140, 255);
  for (const auto& [id, p] : by_id) {
    cv::circle(bgr, point(p), static_cast<int>(4 * scale), colour, thickness, cv::LINE_AA);
    cv::putText(bgr, std::to_string(id), point(p) + cv::Point2d(5 * scale, -5 * scale), cv::FONT_HERSHEY_PLAIN, 0.8 * scale, colour, 1,
                cv::LINE_AA);
  }
  const std::vector<uint8_t> bytes = PngBytes(bgr, "the detection overlay");
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace vstcal
