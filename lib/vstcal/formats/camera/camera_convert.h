// A camera from one file format to another: vstcal/camera@1, OpenCV FileStorage YAML, mrcal
// .cameramodel (docs/tools/calib-convert.md). calib-convert's one library call.
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

enum class CameraFileFormat { kVstcal, kOpenCvYaml, kMrcal };

// From a file name's extension: .json, .yaml or .yml, .cameramodel; nullopt otherwise.
std::optional<CameraFileFormat> CameraFileFormatFromPath(const std::filesystem::path& path);
// The format of a camera file to read, from its name (its reader then refuses a path that is no
// file). A name of no camera format throws InputError saying what the path is: no such file, a
// directory, a device or a pipe, or a file whose format its name does not tell.
CameraFileFormat InputCameraFileFormat(const std::filesystem::path& path);
// From calib-convert's --to names: "camera", "opencv", "mrcal"; nullopt otherwise.
std::optional<CameraFileFormat> CameraFileFormatFromName(std::string_view name);
// "vstcal/camera@1", "OpenCV FileStorage YAML", "mrcal .cameramodel".
std::string_view CameraFileFormatDescription(CameraFileFormat format);

struct ConvertOptions {
  // The unit of a .cameramodel's lengths (read: instead of the file's vstcal_length_unit, or mm;
  // written: converted to it, instead of the camera's unit), and the length_unit of a camera read
  // from OpenCV YAML, which holds no lengths (default mm).
  std::optional<LengthUnit> length_unit;
  // The mrcal lens model to write (MrcalWriteOptions::lensmodel), e.g. "LENSMODEL_OPENCV5".
  std::optional<std::string> mrcal_lensmodel;
};

struct Conversion {
  std::string text;                // the output file
  std::vector<std::string> notes;  // what was assumed, kept or not written: for the user
};

// Reads a camera file of any of the three formats (`options.length_unit` as ConvertOptions says).
ImportedCamera ReadCameraFile(const std::filesystem::path& input, CameraFileFormat from, const ConvertOptions& options);

// Reads `input` as `from` and returns the text of `to`. Throws InputError for bad input and for a
// camera that `to` cannot hold exactly (skew in OpenCV or mrcal; a coefficient the chosen mrcal
// model lacks). camera@1 output carries `provenance`; the others carry it in a comment.
Conversion ConvertCamera(const std::filesystem::path& input, CameraFileFormat from, CameraFileFormat to,
                         const ConvertOptions& options, const Provenance& provenance);

}  // namespace vstcal
