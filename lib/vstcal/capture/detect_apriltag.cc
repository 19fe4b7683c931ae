// AprilTag grids: libapriltag finds and decodes the tags; vstcal keeps this board's ids, checks
// the tags' layout against the target and measures the blur along the tags' edges.
#include <algorithm>
#include <map>
#include <memory>
#include <string>

#include "vstcal/capture/apriltag_family.h"
#include "vstcal/capture/aruco_tags.h"
#include "vstcal/capture/corner_refinement.h"
#include "vstcal/capture/detect_steps.h"
#include "vstcal/capture/detectors.h"
#include "vstcal/capture/miss_diagnosis.h"
#include "vstcal/capture/search_image.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

// libapriltag's corner k is the tag frame's (−1, +1), (+1, +1), (+1, −1), (−1, −1); its tag frame
// has y up the printed tag, so these are bottom-left, bottom-right, top-right, top-left: our
// corners 3, 2, 1, 0 (target.h).
constexpr int kOurCorner[4] = {3, 2, 1, 0};

// libapriltag measures pixels from the top-left corner of the top-left pixel; vstcal from its centre.
constexpr double kPixelOffset = -0.5;

// One detector per thread and family: creating one builds the family's decode table (a few ms).
class AprilTagDetector {
 public:
  explicit AprilTagDetector(std::string_view family) : family_(CreateAprilTagFamily(family)) {
    detector_ = apriltag_detector_create();
    detector_->nthreads = 1;  // vstcal runs one image per thread
    detector_->quad_decimate = 1;  // set per image (DetectAprilTagGrid)
    detector_->quad_sigma = 0;
    detector_->refine_edges = true;
    apriltag_detector_add_family_bits(detector_, family_.get(), 1);
  }
  ~AprilTagDetector() { apriltag_detector_destroy(detector_); }  // before the family it refers to
  AprilTagDetector(const AprilTagDetector&) = delete;
  AprilTagDetector& operator=(const AprilTagDetector&) = delete;

  apriltag_detector_t* get() { return detector_; }

 private:
  AprilTagFamilyPtr family_;
  apriltag_detector_t* detector_ = nullptr;
};

AprilTagDetector& DetectorFor(const std::string& family) {
  thread_local std::map<std::string, std::unique_ptr<AprilTagDetector>> detectors;
  std::unique_ptr<AprilTagDetector>& d = detectors[family];
  if (!d) d = std::make_unique<AprilTagDetector>(family);
  return *d;
}

}  // namespace

Detection DetectAprilTagGrid(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  image_u8_t wrapped{image.width, image.height, image.width, const_cast<uint8_t*>(image.pixels.data())};
  // Above 1 MP libapriltag looks for quads in the image decimated as the other finders' search
  // image (search_image.h), then fits their edges and decodes them at full resolution
  // (refine_edges): its time and memory are those of a 1 MP image, its corners as accurate.
  const int factor = SearchFactor(image.width, image.height);
  // libapriltag asserts (aborts) on a side of 32768 px or more: only a strip too thin to reduce
  // keeps such a side, and it holds no grid.
  if (std::max(image.width, image.height) / factor >= 32768) {
    Detection d;
    d.reason = "no " + target.family + " tag (a " + std::to_string(image.width) + "×" + std::to_string(image.height) +
               " image is searched only below 32768 px a side)";
    return d;
  }
  apriltag_detector_t* detector = DetectorFor(target.family).get();
  detector->quad_decimate = static_cast<float>(factor);
  zarray_t* found = apriltag_detector_detect(detector, &wrapped);
  const int num_tags = target.rows * target.cols;
  std::map<int, DetectedMarker> by_index;
  std::vector<int> repeated;
  int foreign = 0;
  for (int k = 0; k < zarray_size(found); ++k) {
    apriltag_detection_t* det = nullptr;
    zarray_get(found, k, &det);
    const int index = det->id - target.first_id;
    if (index < 0 || index >= num_tags) {
      ++foreign;
      continue;
    }
    DetectedMarker m{index, {}};
    for (int c = 0; c < 4; ++c) m.pixels[kOurCorner[c]] = Eigen::Vector2d(det->p[c][0] + kPixelOffset, det->p[c][1] + kPixelOffset);
    if (!by_index.emplace(index, m).second) repeated.push_back(index);
  }
  apriltag_detections_destroy(found);
  for (const int index : repeated) by_index.erase(index);  // a tag seen twice: neither can be trusted
  Detection d;
  if (by_index.empty()) {
    // Kalibr's aprilgrid has tag36h11 tags with a two-cell black border, which libapriltag does not
    // read: say so when OpenCV finds such tags where libapriltag found none of this board's.
    const int dictionary = ArucoDictionaryOfAprilTagFamily(target.family);
    const ArucoSearch two_cell_search = dictionary >= 0 ? FindArucoTags(image, dictionary, 2, MarkerSearch::kReduced) : ArucoSearch{};
    const size_t two_cell = two_cell_search.tags.size();
    if (two_cell > 0) {
      d.status = DetectionStatus::kRejected;
      d.reason = "another target type: " + std::to_string(two_cell) + " " + target.family +
                 " tags with a two-cell black border (Kalibr's aprilgrid), not the one-cell border of an apriltag-grid; "
                 "set the target's type to aprilgrid (calib-capture target reads Kalibr's target YAML)";
      return d;
    }
    d.reason = foreign > 0 ? std::to_string(foreign) + " " + target.family + " tags, none of this board's ids " +
                                 std::to_string(target.first_id) + " … " + std::to_string(target.first_id + num_tags - 1)
                           : "no " + target.family + " tag";
    // OpenCV's candidates are the same quadrilaterals whatever the border it then decodes: the
    // tags, where they are too small for libapriltag too.
    const MarkerFamily* family = FindMarkerFamily(AprilTagFamilies(), target.family);
    if (std::string hint = MissHint(image, options, TooSmallMarkers(two_cell_search.undecoded_sides_px, family->bits + 2, "tag")); !hint.empty()) {
      d.reason += "; " + hint;
    }
    return d;
  }
  std::vector<DetectedMarker> markers;
  for (const auto& [index, m] : by_index) markers.push_back(m);
  if (std::string mismatch = LayoutMismatch(CheckMarkerLayout(MarkerQuads(target), markers), markers, "tags", "rows, cols or first_id");
      !mismatch.empty()) {
    d.status = DetectionStatus::kRejected;
    d.reason = std::move(mismatch);
    return d;
  }
  std::vector<double> blur;
  for (const DetectedMarker& m : markers) {
    for (int c = 0; c < 4; ++c) {
      d.corners.push_back({4 * m.index + c, m.pixels[c]});
      // Across the tag's edge: its black border is one cell wide, so reach 0.4 cell.
      const Eigen::Vector2d& a = m.pixels[c];
      const Eigen::Vector2d& b = m.pixels[(c + 1) % 4];
      const MarkerFamily* family = FindMarkerFamily(AprilTagFamilies(), target.family);
      if (const auto s = EdgeBlur(image, a, b, 0.4 * (b - a).norm() / (family->bits + 2))) blur.push_back(*s);
    }
  }
  ConcludeFound(options, std::move(blur), &d);
  return d;
}

}  // namespace vstcal
