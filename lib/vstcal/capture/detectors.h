// One detector per target type, behind DetectTarget (detect.h). Internal to the capture module.
#pragma once

#include "vstcal/capture/detect.h"

namespace vstcal {

Detection DetectChessboard(const GrayImage& image, const Target& target, const DetectorOptions& options);
Detection DetectCharuco(const GrayImage& image, const Target& target, const DetectorOptions& options);
Detection DetectAprilTagGrid(const GrayImage& image, const Target& target, const DetectorOptions& options);
Detection DetectAprilGrid(const GrayImage& image, const Target& target, const DetectorOptions& options);

}  // namespace vstcal
