// calib-convert's one library call: a camera or a stereo rig from one file format to another
// (docs/tools/calib-convert.md). A rig is a vstcal/stereo@1 file or a Kalibr camchain of two
// cameras; it can be written as stereo@1 (.json), a Kalibr camchain, or a left and a right ROS
// camera_info. Everything else is a camera (ConvertCamera).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "vstcal/formats/camera/camera_convert.h"

namespace vstcal {

struct FileConversion {
  bool rig = false;                // the input was a stereo rig
  std::vector<std::string> texts;  // the output files: one, or a rig's left and right camera_info
  std::vector<std::string> notes;
};

// Whether `input` (of format `from`) holds a stereo rig: a stereo@1 JSON file, or a camchain with
// more than one camera (three or more are refused when converted).
bool HoldsRig(const std::filesystem::path& input, CameraFileFormat from);

// Reads `input` as `from` and returns `to`'s text(s). A rig written as OpenCV or mrcal is refused
// (calib-stereo export writes those); a rig written as ROS gives two texts.
FileConversion ConvertFile(const std::filesystem::path& input, CameraFileFormat from, CameraFileFormat to,
                           const ConvertOptions& options, const Provenance& provenance);

}  // namespace vstcal
