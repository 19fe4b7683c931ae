#include "vstcal/capture/detect.h"

#include "vstcal/capture/detectors.h"
#include "vstcal/core/error.h"

namespace vstcal {

Detection DetectTarget(const GrayImage& image, const Target& target, const DetectorOptions& options) {
  VSTCAL_CHECK(image.width > 0 && image.height > 0 && image.pixels.size() == static_cast<size_t>(image.width) * image.height,
               "empty or inconsistent image");
  switch (target.type) {
    case TargetType::kChessboard: return DetectChessboard(image, target, options);
    case TargetType::kCharuco: return DetectCharuco(image, target, options);
    case TargetType::kAprilTagGrid: return DetectAprilTagGrid(image, target, options);
    case TargetType::kAprilGrid: return DetectAprilGrid(image, target, options);
  }
  VSTCAL_CHECK(false, "unknown target type");
}

}  // namespace vstcal
