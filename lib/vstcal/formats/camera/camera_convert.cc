#include "vstcal/formats/camera/camera_convert.h"

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/files/input_protection.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/kalibr_camchain.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/camera/opencv_yaml.h"
#include "vstcal/formats/camera/ros_camera_info.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {

std::optional<CameraFileFormat> CameraFileFormatFromPath(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return CameraFileFormat::kVstcal;
  if (ext == ".yaml" || ext == ".yml") return CameraFileFormat::kOpenCvYaml;
  if (ext == ".cameramodel") return CameraFileFormat::kMrcal;
  return std::nullopt;
}

bool ExtensionAllows(const std::filesystem::path& path, CameraFileFormat format) {
  const auto named = CameraFileFormatFromPath(path);
  if (named == CameraFileFormat::kOpenCvYaml) {
    return format == CameraFileFormat::kOpenCvYaml || format == CameraFileFormat::kRos ||
           format == CameraFileFormat::kKalibr;
  }
  return named == format;
}

std::optional<CameraFileFormat> DetectCameraFileFormat(const std::filesystem::path& path) {
  const auto named = CameraFileFormatFromPath(path);
  if (named != CameraFileFormat::kOpenCvYaml) return named;
  const std::string text = ReadInputFile(path, "a YAML file", limits::kMaxOpenCvYamlBytes, "OpenCV YAML");
  // cv::FileStorage starts every file with its directive; ROS and Kalibr files have none.
  if (text.starts_with("%YAML:")) return CameraFileFormat::kOpenCvYaml;
  // A file none of whose keys says ROS or Kalibr is left to the OpenCV reader, which says what is
  // wrong with it as an OpenCV file (the most common of the three).
  const bool ros_or_kalibr_words = text.find("distortion_model") != std::string::npos || text.find("cam0") != std::string::npos;
  YamlNode root;
  try {
    root = ParseYamlMap(text, path.string(), "a ROS camera_info or Kalibr camchain file");
  } catch (const InputError&) {
    if (ros_or_kalibr_words) throw;
    return CameraFileFormat::kOpenCvYaml;
  }
  auto has = [&](std::string_view key) {
    for (const auto& member : root.members) {
      if (member.first == key) return true;
    }
    return false;
  };
  if (has("cam0")) return CameraFileFormat::kKalibr;
  if (has("distortion_model")) return CameraFileFormat::kRos;
  return CameraFileFormat::kOpenCvYaml;
}

CameraFileFormat InputCameraFileFormat(const std::filesystem::path& path) {
  // A known name is read as its format, whose reader says what is wrong with the path; an unknown
  // one is explained by what the path names before its name.
  if (CameraFileFormatFromPath(path)) {
    if (const auto format = DetectCameraFileFormat(path)) return *format;
  }
  const std::string name = path.string();
  switch (KindOfPath(path)) {
    case PathKind::kMissing: throw InputError(name + ": no such file; check the path");
    case PathKind::kDirectory: throw InputError(name + ": is a directory, not a camera file; give the file's path");
    case PathKind::kSpecial:
      throw InputError(name + ": is not a regular file (a device, a pipe or a socket), not a camera file; give the file itself");
    case PathKind::kRegularFile:
    case PathKind::kUnknown: break;
  }
  throw InputError(name + ": cannot tell the format from the file name; name it .json (vstcal/camera@1 or stereo@1), "
                          ".yaml or .yml (OpenCV, ROS camera_info or Kalibr camchain) or .cameramodel (mrcal)");
}

std::optional<CameraFileFormat> CameraFileFormatFromName(std::string_view name) {
  if (name == "camera") return CameraFileFormat::kVstcal;
  if (name == "opencv") return CameraFileFormat::kOpenCvYaml;
  if (name == "mrcal") return CameraFileFormat::kMrcal;
  if (name == "ros") return CameraFileFormat::kRos;
  if (name == "kalibr") return CameraFileFormat::kKalibr;
  return std::nullopt;
}

std::string_view CameraFileFormatDescription(CameraFileFormat format) {
  switch (format) {
    case CameraFileFormat::kVstcal:
      return "vstcal/camera@1";
    case CameraFileFormat::kOpenCvYaml:
      return "OpenCV FileStorage YAML";
    case CameraFileFormat::kMrcal:
      return "mrcal .cameramodel";
    case CameraFileFormat::kRos:
      return "ROS camera_info YAML";
    case CameraFileFormat::kKalibr:
      return "Kalibr camchain.yaml";
  }
  return "?";
}

ImportedCamera ReadCameraFile(const std::filesystem::path& input, CameraFileFormat from, const ConvertOptions& options) {
  ImportedCamera in;
  switch (from) {
    case CameraFileFormat::kVstcal:
      in.camera = ReadCamera(input);
      break;
    case CameraFileFormat::kOpenCvYaml:
      in = ReadOpenCvYaml(input, options.length_unit.value_or(LengthUnit::kMillimetre));
      break;
    case CameraFileFormat::kMrcal:
      in = ReadMrcalCameramodel(input, options.length_unit);
      break;
    case CameraFileFormat::kRos:
      in = ReadRosCameraInfo(input, options.length_unit.value_or(LengthUnit::kMillimetre));
      break;
    case CameraFileFormat::kKalibr: {
      const std::string name = input.string();
      std::vector<KalibrCamera> chain =
          KalibrCamchainFromText(ReadInputFile(input, "a Kalibr camchain.yaml", limits::kMaxOpenCvYamlBytes, "Kalibr camchain YAML"), name, &in.notes);
      if (chain.size() != 1) {
        FailField(name, "cam" + std::to_string(chain.size() - 1),
                  "a chain of " + std::to_string(chain.size()) + " cameras where one camera was expected",
                  chain.size() == 2 ? "convert the chain of two as a stereo@1 rig (calib-convert, .json output)"
                                    : "keep one camera in a copy of the file");
      }
      in.camera = chain[0].camera;
      if (!chain[0].rostopic.empty()) {
        in.notes.push_back(name + ": cam0.rostopic: not kept: camera@1 has no field for it");
      }
      break;
    }
  }
  return in;
}

Conversion ConvertCamera(const std::filesystem::path& input, CameraFileFormat from, CameraFileFormat to,
                         const ConvertOptions& options, const Provenance& provenance) {
  ImportedCamera in = ReadCameraFile(input, from, options);
  ExportedCamera out;
  const std::string source = input.string();
  switch (to) {
    case CameraFileFormat::kVstcal:
      out.text = DumpJson(CameraToJson(in.camera, provenance));
      break;
    case CameraFileFormat::kOpenCvYaml:
      out = OpenCvYamlText(in.camera, source, provenance);
      break;
    case CameraFileFormat::kMrcal:
      out = MrcalCameramodelText(in.camera, source, {options.mrcal_lensmodel, options.length_unit, in.rotation_vector},
                                 provenance);
      break;
    case CameraFileFormat::kRos:
      out = RosCameraInfoText(in.camera, source, provenance);
      break;
    case CameraFileFormat::kKalibr: {
      KalibrCamera camera;
      camera.camera = in.camera;
      out = KalibrCamchainText({camera}, source, provenance);
      NoteUnwrittenName(in.camera, source, &out.notes);
      break;
    }
  }
  Conversion c{std::move(out.text), std::move(in.notes)};
  c.notes.insert(c.notes.end(), out.notes.begin(), out.notes.end());
  return c;
}

}  // namespace vstcal
