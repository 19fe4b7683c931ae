// Detection over a whole capture (docs/tools/calib-capture.md#detect): every image (or video
// frame) is read and searched for the target in parallel over the cores, the results are kept in
// input order (the output does not depend on the thread count), every image is accounted for,
// and the corners found become vstcal/correspondences@1 views: in the board frame (Z = 0) for
// planar views, in the volume's world frame (Z = the image's plane_offset) for a volume.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/correspondences.h"
#include "vstcal/capture/detect.h"
#include "vstcal/image/image.h"
#include "vstcal/capture/target.h"

namespace vstcal {

using Progress = std::function<void(double fraction)>;

// One image file to detect in.
struct CaptureInput {
  std::string image;                   // as the output names it (the path as given)
  std::filesystem::path path;          // the file to read
  std::optional<double> plane_offset;  // required for a volume, in the target's length unit
};

struct DetectRequest {
  Target target;
  std::string target_file;  // named in messages ("the target" when empty)
  DetectorOptions detector;
  Rig rig = Rig::kPlanarViews;
  std::string camera_name;   // the output's "camera" field
  int min_views = 3;         // fewer usable images: DegenerateError (exit code 3)
  bool skip_unreadable = false;  // list unreadable images as rejected instead of failing
  unsigned threads = 0;      // 0: all cores
};

// What became of one image: the accounting written to the output's "capture.images".
struct ImageRecord {
  std::string image;
  std::string view;  // the view's name when found
  DetectionStatus status = DetectionStatus::kNotFound;
  std::string reason;
  int corners = 0;
  double blur_px = 0;  // NaN when not measured
  int width = 0, height = 0;
};

struct CaptureResult {
  Correspondences correspondences;
  std::vector<ImageRecord> images;     // every input, in input order
  std::vector<Detection> detections;  // parallel to images
};

// Reads and searches every file. Throws InputError (exit code 2) for an unreadable image (unless
// skip_unreadable), images of different sizes, two files with the same bytes, a volume image
// without an offset, and when no image shows the target; DegenerateError (exit code 3) when fewer
// than min_views images are usable or a volume's views all share one plane offset.
CaptureResult DetectInFiles(const std::vector<CaptureInput>& inputs, const DetectRequest& request, const Progress& progress = {});

// Frames of a video file, or of a live camera (camera_index ≥ 0), every `every`-th frame from the
// first, at most max_frames of them (0: to the end of a file; required for a camera). Planar
// views only; views are named "frame-000120" and images "<file>#120" (or "camera<i>#120").
struct VideoRequest {
  std::string file;
  int camera_index = -1;
  int every = 1;
  int max_frames = 0;
};
CaptureResult DetectInVideo(const VideoRequest& video, const DetectRequest& request, const Progress& progress = {});

// "14 images: 12 found, 1 not found, 1 rejected (1 blurred)".
std::string DescribeCounts(const std::vector<ImageRecord>& images);

}  // namespace vstcal
