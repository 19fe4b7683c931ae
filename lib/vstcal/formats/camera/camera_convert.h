// A camera from one file format to another: vstcal/camera@1, OpenCV FileStorage YAML, mrcal
// .cameramodel, ROS camera_info YAML, Kalibr camchain.yaml (docs/tools/calib-convert.md). A rig
// (stereo@1, a camchain of two) goes through ConvertFile (formats/stereo/file_convert.h).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/core/units.h"
#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

enum class CameraFileFormat { kVstcal, kOpenCvYaml, kMrcal, kRos, kKalibr };

// From a file name's extension: .json, .yaml or .yml (OpenCV: the default of the three YAML
// formats), .cameramodel; nullopt otherwise.
std::optional<CameraFileFormat> CameraFileFormatFromPath(const std::filesystem::path& path);
// Whether a file of this name may hold `format` (.yaml and .yml hold OpenCV, ROS and Kalibr).
bool ExtensionAllows(const std::filesystem::path& path, CameraFileFormat format);
// A file's format from its extension and, for .yaml and .yml, its keys: "%YAML:" at the start is
// OpenCV's; otherwise a top-level cam0 is Kalibr's, a distortion_model ROS's, and anything else
// OpenCV's (whose reader then says what is wrong). Throws InputError for a file it cannot read, or
// one with ROS's or Kalibr's words that is not valid YAML; nullopt for an unknown extension.
std::optional<CameraFileFormat> DetectCameraFileFormat(const std::filesystem::path& path);
// The format of a camera file to read, from its name and, for .yaml and .yml, its keys (its
// reader then refuses a path that is no file). A name of no camera format throws InputError saying what the path is: no such file, a
// directory, a device or a pipe, or a file whose format its name does not tell.
CameraFileFormat InputCameraFileFormat(const std::filesystem::path& path);
// From calib-convert's --to names: "camera", "opencv", "mrcal", "ros", "kalibr"; nullopt otherwise.
std::optional<CameraFileFormat> CameraFileFormatFromName(std::string_view name);
// "vstcal/camera@1", "OpenCV FileStorage YAML", "mrcal .cameramodel", "ROS camera_info YAML",
// "Kalibr camchain.yaml".
std::string_view CameraFileFormatDescription(CameraFileFormat format);

struct ConvertOptions {
  // The unit of a .cameramodel's lengths (read: instead of the file's vstcal_length_unit, or mm;
  // written: converted to it, instead of the camera's unit), and the length_unit of a camera read
  // from OpenCV or ROS YAML, which hold no lengths (default mm).
  std::optional<LengthUnit> length_unit;
  // The mrcal lens model to write (MrcalWriteOptions::lensmodel), e.g. "LENSMODEL_OPENCV5".
  std::optional<std::string> mrcal_lensmodel;
};

struct Conversion {
  std::string text;                // the output file
  std::vector<std::string> notes;  // what was assumed, kept or not written: for the user
};

// Reads a camera file of any of the formats (`options.length_unit` as ConvertOptions says; a
// Kalibr file must hold one camera, in metres).
ImportedCamera ReadCameraFile(const std::filesystem::path& input, CameraFileFormat from, const ConvertOptions& options);

// Reads `input` as `from` and returns the text of `to`. Throws InputError for bad input and for a
// camera that `to` cannot hold exactly (skew in OpenCV or mrcal; a coefficient the chosen mrcal
// model lacks). camera@1 output carries `provenance`; the others carry it in a comment.
Conversion ConvertCamera(const std::filesystem::path& input, CameraFileFormat from, CameraFileFormat to,
                         const ConvertOptions& options, const Provenance& provenance);

}  // namespace vstcal
