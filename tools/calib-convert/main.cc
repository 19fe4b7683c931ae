// calib-convert: a camera between vstcal, OpenCV and mrcal files (docs/tools/calib-convert.md).
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_convert.h"
#include "vstcal/json/json_writer.h"

namespace {

using vstcal::InputError;
using vstcal::CameraFileFormat;

CameraFileFormat InputFormat(const std::string& input) { return vstcal::InputCameraFileFormat(input); }

CameraFileFormat OutputFormat(const std::string& output, const std::string& to) {
  const auto named = vstcal::CameraFileFormatFromPath(output);
  if (!to.empty()) {
    const CameraFileFormat format = *vstcal::CameraFileFormatFromName(to);
    if (named && *named != format) {
      throw InputError("--to: " + to + " contradicts the output's name " + output + ", which says " +
                       std::string(vstcal::CameraFileFormatDescription(*named)) +
                       "; rename the output or drop --to");
    }
    return format;
  }
  if (named) return *named;
  throw InputError(output +
                   ": cannot tell the output format from the file name; name it .json, .yaml, .yml or "
                   ".cameramodel, or give --to camera|opencv|mrcal");
}

// A flag that would change nothing is refused: the user expected it to do something.
void CheckFlagsApply(CameraFileFormat from, CameraFileFormat to, bool length_unit, bool mrcal_model) {
  using F = CameraFileFormat;
  const std::string conversion = std::string(vstcal::CameraFileFormatDescription(from)) + " to " +
                                 std::string(vstcal::CameraFileFormatDescription(to));
  if (length_unit && from != F::kMrcal && to != F::kMrcal && !(from == F::kOpenCvYaml && to == F::kVstcal)) {
    throw InputError("--length-unit: has no effect converting " + conversion +
                     " (it is the unit of a .cameramodel's lengths, or of a camera read from OpenCV YAML); drop it");
  }
  if (mrcal_model && to != F::kMrcal) {
    throw InputError("--mrcal-model: applies to .cameramodel output only, not to " + conversion + "; drop it");
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Converts a camera between vstcal/camera@1 (.json), OpenCV FileStorage YAML (.yaml, .yml: image_width, "
      "image_height, camera_matrix, distortion_coefficients, as OpenCV's calibration sample writes them) and mrcal "
      ".cameramodel files. Numbers are copied exactly. Lens models: none (mrcal LENSMODEL_PINHOLE), "
      "radial-tangential (OpenCV 4 or 5 coefficients, mrcal OPENCV4/OPENCV5), rational (8 coefficients, "
      "OPENCV8). What the output cannot hold is refused (skew, for OpenCV and mrcal) or said on stderr (a pose, "
      "for OpenCV YAML).\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-convert"};
  std::string input, output, to, unit, mrcal_model;
  app.add_option("IN", input, "camera file to read: .json, .yaml/.yml or .cameramodel")
      ->required()
      ->check(vstcal::tools::kNonEmpty);
  app.add_option("-o,--output", output, "file to write")->required()->check(vstcal::tools::kNonEmpty);
  app.add_option("--to", to, "output format: camera (vstcal/camera@1), opencv or mrcal (default: from OUT's name)")
      ->check(CLI::IsMember({"camera", "opencv", "mrcal"}));
  app.add_option("--length-unit", unit,
                 "mm, cm, m or in: the unit of a .cameramodel's translation, which mrcal does not record (reading: "
                 "default the file's vstcal_length_unit, else mm; writing: default the camera's unit); for OpenCV "
                 "YAML input, the camera@1 length_unit (default mm)")
      ->check(vstcal::tools::kLengthUnit);
  app.add_option("--mrcal-model", mrcal_model,
                 "OPENCV4 (needs k3 = 0), OPENCV5 or OPENCV8 (default: the shortest that holds the camera exactly)")
      ->check(CLI::IsMember({"OPENCV4", "OPENCV5", "OPENCV8"}));

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    DeclareOutputs({output});
    const CameraFileFormat from = InputFormat(input), to_format = OutputFormat(output, to);
    CheckFlagsApply(from, to_format, !unit.empty(), !mrcal_model.empty());
    ConvertOptions options;
    if (!unit.empty()) options.length_unit = LengthUnitFromName(unit);
    if (!mrcal_model.empty()) options.mrcal_lensmodel = "LENSMODEL_" + mrcal_model;
    const Conversion c =
        ConvertCamera(input, from, to_format, options, MakeProvenance("calib-convert", argc, argv));
    WriteFileAtomically(output, c.text);
    for (const std::string& note : c.notes) std::cerr << "calib-convert: note: " << note << "\n";
    std::cerr << "calib-convert: wrote " << output << " (" << CameraFileFormatDescription(to_format) << ")\n";
    return 0;
  });
}
