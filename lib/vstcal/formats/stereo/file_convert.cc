#include "vstcal/formats/stereo/file_convert.h"

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/formats/stereo/rig_interop.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/reader_common.h"
#include "vstcal/core/option_name.h"

namespace vstcal {

bool HoldsRig(const std::filesystem::path& input, CameraFileFormat from) {
  if (from == CameraFileFormat::kVstcal) return IsStereoRigDocument(JsonDocument::Load(input));
  if (from != CameraFileFormat::kKalibr) return false;
  const YamlNode root = ParseYamlMap(ReadInputFile(input, "a Kalibr camchain.yaml", limits::kMaxOpenCvYamlBytes, "Kalibr camchain YAML"), input.string(), "a Kalibr camchain.yaml");
  for (const auto& member : root.members) {
    if (member.first == "cam1") return true;
  }
  return false;
}

FileConversion ConvertFile(const std::filesystem::path& input, CameraFileFormat from, CameraFileFormat to,
                           const ConvertOptions& options, const Provenance& provenance) {
  FileConversion out;
  if (!HoldsRig(input, from)) {
    Conversion c = ConvertCamera(input, from, to, options, provenance);
    out.texts.push_back(std::move(c.text));
    out.notes = std::move(c.notes);
    return out;
  }
  out.rig = true;
  const std::string source = input.string();
  StereoRig rig;
  if (from == CameraFileFormat::kVstcal) {
    rig = ReadStereoRig(input);
  } else {
    rig = RigFromKalibr(KalibrCamchainFromText(ReadInputFile(input, "a Kalibr camchain.yaml", limits::kMaxOpenCvYamlBytes, "Kalibr camchain YAML"), source, &out.notes),
                        source, &out.notes);
  }
  ExportedCamera written;
  switch (to) {
    case CameraFileFormat::kVstcal:
      written.text = DumpJson(StereoRigToJson(rig, provenance));
      break;
    case CameraFileFormat::kKalibr:
      written = KalibrCamchainText(rig, source, provenance);
      break;
    case CameraFileFormat::kRos: {
      auto [left, right] = RosStereoTexts(rig, source, provenance);
      out.texts.push_back(std::move(left.text));
      out.notes.insert(out.notes.end(), left.notes.begin(), left.notes.end());
      written = std::move(right);
      break;
    }
    case CameraFileFormat::kOpenCvYaml:
    case CameraFileFormat::kMrcal:
      throw InputError(source + ": a stereo rig, and calib-convert writes a rig as stereo@1 (.json), Kalibr or ROS; "
                                "write it for " + std::string(CameraFileFormatDescription(to)) +
                       " with calib-stereo export (" VSTCAL_OPT("opencv") " FILE or " VSTCAL_OPT("mrcal") " LEFT RIGHT)");
  }
  out.texts.push_back(std::move(written.text));
  out.notes.insert(out.notes.end(), written.notes.begin(), written.notes.end());
  return out;
}

}  // namespace vstcal
