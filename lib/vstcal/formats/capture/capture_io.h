// The output of calib-capture detect: a vstcal/correspondences@1 file whose extra "capture" block
// accounts for every image (docs/formats.md#capture). The solvers read the file as any
// correspondences; they ignore the block.
#pragma once

#include "vstcal/capture/detect_run.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

OrderedJson CaptureToJson(const CaptureResult& result, const DetectRequest& request, const Provenance& provenance);

std::string_view FinderName(ChessboardFinder finder);   // "classic", "sector-based", "classic+sector-based"
std::string_view RefinerName(CornerRefiner refiner);    // "symmetry", "cornersubpix", "none"

}  // namespace vstcal
