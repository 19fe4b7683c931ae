// Finding a target's corners in one image (docs/tools/calib-capture.md#detectors): OpenCV's
// chessboard detectors and ChArUco interpolation, libapriltag for AprilTag grids, each followed
// by vstcal's own steps — the chessboard's orientation (chessboard_orientation.h), sub-pixel
// refinement by point symmetry (corner_refinement.h), an edge-blur estimate, and checks that the
// corners found are where the target file puts them.
#pragma once

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "vstcal/image/image.h"
#include "vstcal/capture/target.h"
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class DetectionStatus {
  kFound,     // corners usable for calibration
  kNotFound,  // the target was not seen
  kRejected,  // seen, but unusable: too few corners, blurred, orientation ambiguous, …
};
inline constexpr EnumNames<DetectionStatus, 3> kDetectionStatusNames = {{{DetectionStatus::kFound, "found"}, {DetectionStatus::kNotFound, "not-found"}, {DetectionStatus::kRejected, "rejected"}}};
// "found", "not-found", "rejected". Inline, so the capture file's writer needs none of the detectors.
inline std::string_view DetectionStatusName(DetectionStatus status) { return NameOf(kDetectionStatusNames, status); }

struct DetectedCorner {
  int id = 0;            // the target's corner id (target.h)
  Eigen::Vector2d pixel;  // px, (0, 0) the centre of the top-left pixel
};

struct Detection {
  DetectionStatus status = DetectionStatus::kNotFound;
  std::string reason;                   // why not found or rejected (one phrase); empty when found
  std::vector<DetectedCorner> corners;  // by increasing id (also kept when rejected, for overlays)
  double blur_px = std::numeric_limits<double>::quiet_NaN();  // median edge blur σ, px (NaN: not measured)
};

// The chessboard detector whose corners start the refinement.
enum class ChessboardFinder {
  kClassic,                 // cv::findChessboardCorners (adaptive threshold, quads)
  kSectorBased,             // cv::findChessboardCornersSB (localized Radon transform)
  kClassicThenSectorBased,  // the classic one, and the sector-based one where it finds nothing
};
inline constexpr EnumNames<ChessboardFinder, 3> kChessboardFinderNames = {{{ChessboardFinder::kClassic, "classic"}, {ChessboardFinder::kSectorBased, "sector-based"}, {ChessboardFinder::kClassicThenSectorBased, "classic+sector-based"}}};
// What refines the corners a detector returns (ChArUco's are always cornerSubPix'd by OpenCV first).
enum class CornerRefiner {
  kSymmetry,      // vstcal's point-symmetry fit (corner_refinement.h)
  kCornerSubPix,  // cv::cornerSubPix, half-window 0.4 × the local square size
  kNone,          // the detector's own positions
};
inline constexpr EnumNames<CornerRefiner, 3> kCornerRefinerNames = {{{CornerRefiner::kSymmetry, "symmetry"}, {CornerRefiner::kCornerSubPix, "cornersubpix"}, {CornerRefiner::kNone, "none"}}};

struct DetectorOptions {
  ChessboardFinder finder = ChessboardFinder::kClassicThenSectorBased;
  CornerRefiner refiner = CornerRefiner::kSymmetry;
  // Views that share one world frame (a calibration volume) refuse an ambiguous orientation.
  bool refuse_ambiguous_orientation = false;
  int min_corners = 6;       // fewer (partial ChArUco and AprilTag views): rejected
  double max_blur_px = 3.0;  // median edge blur σ above this: rejected
};

// Detects the target in an 8-bit grey image. Never throws for what the image shows: every outcome
// is a status with its reason.
Detection DetectTarget(const GrayImage& image, const Target& target, const DetectorOptions& options);

}  // namespace vstcal
