// Kalibr's calibration target YAML (the file kalibr_calibrate_cameras takes as --target; Kalibr's
// wiki "Calibration targets"), read into a vstcal target (docs/formats.md#kalibr-target):
//   target_type: 'aprilgrid'     tagCols, tagRows (tags), tagSize (m), tagSpacing (gap / tagSize)
//                                → an aprilgrid (target.h: Kalibr's layout and corner numbering)
//   target_type: 'checkerboard'  targetCols, targetRows (inner corners), colSpacingMeters,
//                                rowSpacingMeters → a chessboard (one square size: the two spacings
//                                must be equal; vstcal numbers its corners as OpenCV does)
//   target_type: 'circlegrid'    refused: vstcal has no circle grid
// Lengths stay in metres (length_unit m); the margin is the default of calib-capture target (the
// tag gap, or one square). Other keys are ignored, as Kalibr does.
#pragma once

#include <filesystem>
#include <string>

#include "vstcal/capture/target.h"

namespace vstcal {

// Throws InputError "<name>: <key>: <what>; <fix>" for a missing or bad key, a type vstcal cannot
// describe, or a target that fails CheckTarget (reported against Kalibr's key).
Target KalibrTargetFromText(const std::string& text, const std::string& name);
Target ReadKalibrTarget(const std::filesystem::path& path);

}  // namespace vstcal
