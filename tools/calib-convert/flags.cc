#include "flags.h"

#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/stereo/file_convert.h"
#include "vstcal/json/json_writer.h"

namespace vstcal::tools {
namespace {

CameraFileFormat InputFormat(const std::string& input) { return InputCameraFileFormat(input); }

CameraFileFormat OutputFormat(const std::string& output, const std::string& to) {
  const auto named = CameraFileFormatFromPath(output);
  if (!to.empty()) {
    const CameraFileFormat format = *CameraFileFormatFromName(to);
    if (named && !ExtensionAllows(output, format)) {
      throw InputError("--to: " + to + " contradicts the output's name " + output + ", which says " +
                       std::string(CameraFileFormatDescription(*named)) +
                       "; rename the output or drop --to");
    }
    return format;
  }
  if (named) return *named;
  throw InputError(output +
                   ": cannot tell the output format from the file name; name it .json, .yaml, .yml or "
                   ".cameramodel, or give --to camera|opencv|mrcal|ros|kalibr");
}

// A flag that would change nothing is refused: the user expected it to do something.
void CheckFlagsApply(CameraFileFormat from, CameraFileFormat to, bool length_unit, bool mrcal_model) {
  using F = CameraFileFormat;
  const std::string conversion = std::string(CameraFileFormatDescription(from)) + " to " +
                                 std::string(CameraFileFormatDescription(to));
  const bool unitless_to_json = (from == F::kOpenCvYaml || from == F::kRos) && to == F::kVstcal;
  if (length_unit && from != F::kMrcal && to != F::kMrcal && !unitless_to_json) {
    throw InputError("--length-unit: has no effect converting " + conversion +
                     " (it is the unit of a .cameramodel's lengths, or of a camera read from OpenCV or ROS YAML); "
                     "drop it");
  }
  if (mrcal_model && to != F::kMrcal) {
    throw InputError("--mrcal-model: applies to .cameramodel output only, not to " + conversion + "; drop it");
  }
}

}  // namespace

void ConvertFlags::Add(CLI::App& app) {
  app.add_option("IN", input, "file to read: .json (camera@1 or stereo@1), .yaml/.yml or .cameramodel")
      ->required()
      ->check(kNonEmpty);
  app.add_option("-o,--output", output, "file to write (a rig as ROS: the left camera's camera_info)")
      ->required()
      ->check(kNonEmpty);
  app.add_option("--output-right", output_right, "a rig as ROS: the right camera's camera_info")
      ->check(kNonEmpty);
  app.add_option("--to", to,
                 "output format: camera (vstcal JSON), opencv, mrcal, ros or kalibr (default: from OUT's name; "
                 ".yaml means opencv)")
      ->check(CLI::IsMember({"camera", "opencv", "mrcal", "ros", "kalibr"}));
  app.add_option("--length-unit", unit,
                 "mm, cm, m or in: the unit of a .cameramodel's translation, which mrcal does not record (reading: "
                 "default the file's vstcal_length_unit, else mm; writing: default the camera's unit); for OpenCV "
                 "or ROS YAML input, the camera@1 length_unit (default mm)")
      ->check(kLengthUnit);
  app.add_option("--mrcal-model", mrcal_model,
                 "OPENCV4 (needs k3 = 0), OPENCV5 or OPENCV8 (default: the shortest that holds the camera exactly)")
      ->check(CLI::IsMember({"OPENCV4", "OPENCV5", "OPENCV8"}));
}

app::Outcome ConvertFlags::Convert(const Provenance& provenance) const {
  const CameraFileFormat from = InputFormat(input), to_format = OutputFormat(output, to);
  CheckFlagsApply(from, to_format, !unit.empty(), !mrcal_model.empty());
  ConvertOptions options;
  if (!unit.empty()) options.length_unit = LengthUnitFromName(unit);
  if (!mrcal_model.empty()) options.mrcal_lensmodel = "LENSMODEL_" + mrcal_model;
  const FileConversion c = ConvertFile(input, from, to_format, options, provenance);
  if (c.texts.size() == 2 && output_right.empty()) {
    throw InputError("--output-right: missing: a stereo rig as ROS camera_info is two files; give the right "
                     "camera's file with --output-right");
  }
  if (c.texts.size() == 1 && !output_right.empty()) {
    throw InputError("--output-right: applies to a stereo rig written as ROS camera_info only; drop it");
  }
  app::Outcome outcome;
  outcome.files.emplace_back(output, c.texts[0]);
  if (c.texts.size() == 2) outcome.files.emplace_back(output_right, c.texts[1]);
  for (const std::string& note : c.notes) outcome.summary += "calib-convert: note: " + note + "\n";
  const std::string_view written =
      c.rig && to_format == CameraFileFormat::kVstcal ? "vstcal/stereo@1" : CameraFileFormatDescription(to_format);
  outcome.summary += "calib-convert: wrote " + output + (c.texts.size() == 2 ? " and " + output_right : "") + " (" +
                    std::string(written) + (c.rig ? ", a stereo rig" : "") + ")";
  return outcome;
}

}  // namespace vstcal::tools
