#include "vstcal/capture/target_pattern.h"

#include <opencv2/aruco/dictionary.hpp>
#include <opencv2/core.hpp>

#include "vstcal/capture/apriltag_family.h"
#include "vstcal/core/error.h"

namespace vstcal {

MarkerCells ArucoMarkerCells(std::string_view dictionary, int id) {
  const cv::Ptr<cv::aruco::Dictionary> dict = cv::aruco::getPredefinedDictionary(ArucoDictionaryIndex(dictionary));
  VSTCAL_CHECK(id >= 0 && id < dict->bytesList.rows, "marker id out of range");
  MarkerCells m;
  m.side = dict->markerSize + 2;
  cv::Mat image;
  dict->drawMarker(id, m.side, image, 1);  // one pixel per cell, 1-bit border
  m.black.resize(static_cast<size_t>(m.side) * m.side);
  for (int r = 0; r < m.side; ++r) {
    for (int c = 0; c < m.side; ++c) m.black[static_cast<size_t>(r) * m.side + c] = image.at<uint8_t>(r, c) < 128;
  }
  return m;
}

MarkerCells AprilGridTagCells(int id) {
  const cv::Ptr<cv::aruco::Dictionary> dict = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
  VSTCAL_CHECK(id >= 0 && id < dict->bytesList.rows, "tag id out of range");
  MarkerCells m;
  m.side = kAprilGridCells;
  cv::Mat image;
  dict->drawMarker(id, m.side, image, kAprilGridBorderCells);  // one pixel per cell
  // Kalibr's generator prints the code turned half a turn from OpenCV's drawing (target.h).
  cv::rotate(image, image, cv::ROTATE_180);
  m.black.resize(static_cast<size_t>(m.side) * m.side);
  for (int r = 0; r < m.side; ++r) {
    for (int c = 0; c < m.side; ++c) m.black[static_cast<size_t>(r) * m.side + c] = image.at<uint8_t>(r, c) < 128;
  }
  return m;
}

MarkerCells AprilTagCells(std::string_view family, int id) {
  const AprilTagFamilyPtr fam = CreateAprilTagFamily(family);
  VSTCAL_CHECK(id >= 0 && static_cast<uint32_t>(id) < fam->ncodes, "tag id out of range");
  VSTCAL_CHECK(!fam->reversed_border && fam->total_width == fam->width_at_border + 2, "not a classic AprilTag family");
  image_u8_t* image = apriltag_to_image(fam.get(), id);
  MarkerCells m;
  m.side = fam->width_at_border;
  m.black.resize(static_cast<size_t>(m.side) * m.side);
  for (int r = 0; r < m.side; ++r) {
    for (int c = 0; c < m.side; ++c) m.black[static_cast<size_t>(r) * m.side + c] = image->buf[(r + 1) * image->stride + (c + 1)] < 128;
  }
  image_u8_destroy(image);
  return m;
}

void AddMarkerCells(const MarkerCells& marker, double x0, double y0, double cell, std::vector<Rect>* black) {
  for (int r = 0; r < marker.side; ++r) {
    for (int c = 0; c < marker.side; ++c) {
      if (marker.black[static_cast<size_t>(r) * marker.side + c]) {
        black->push_back(Rect{x0 + c * cell, y0 + r * cell, x0 + (c + 1) * cell, y0 + (r + 1) * cell});
      }
    }
  }
}

Pattern TargetPattern(const Target& t) {
  VSTCAL_CHECK(!CheckTarget(t), "target not checked");
  std::vector<Rect> black;
  if (t.type == TargetType::kChessboard || t.type == TargetType::kCharuco) {
    // Squares (i, j), i = 0 … cols along X, j = 0 … rows along Y: square (i, j) spans
    // [(i − 1)·S, i·S] × [(j − 1)·S, j·S] (IsBlackSquare).
    const double S = t.square_size;
    for (int j = 0; j <= t.rows; ++j) {
      for (int i = 0; i <= t.cols; ++i) {
        if (IsBlackSquare(t, i, j)) black.push_back(Rect{(i - 1) * S, (j - 1) * S, i * S, j * S});
      }
    }
  }
  const std::vector<Quad> markers = MarkerQuads(t);
  for (size_t k = 0; k < markers.size(); ++k) {
    const int id = static_cast<int>(k);
    const MarkerCells cells = t.type == TargetType::kCharuco     ? ArucoMarkerCells(t.dictionary, t.first_id + id)
                              : t.type == TargetType::kAprilGrid ? AprilGridTagCells(id)
                                                                 : AprilTagCells(t.family, t.first_id + id);
    const double side = markers[k][1].x() - markers[k][0].x();
    AddMarkerCells(cells, markers[k][0].x(), markers[k][0].y(), side / cells.side, &black);
  }
  for (const Rect& r : AprilGridJunctionSquares(t)) black.push_back(r);
  return Pattern(SheetExtent(t), std::move(black));
}

}  // namespace vstcal
