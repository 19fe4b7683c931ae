#include "vstcal/formats/camera/camera_convert.h"

#include "vstcal/core/error.h"
#include "vstcal/files/input_protection.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/camera/opencv_yaml.h"

namespace vstcal {

std::optional<CameraFileFormat> CameraFileFormatFromPath(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".json") return CameraFileFormat::kVstcal;
  if (ext == ".yaml" || ext == ".yml") return CameraFileFormat::kOpenCvYaml;
  if (ext == ".cameramodel") return CameraFileFormat::kMrcal;
  return std::nullopt;
}

CameraFileFormat InputCameraFileFormat(const std::filesystem::path& path) {
  // A known name is read as its format, whose reader says what is wrong with the path; an unknown
  // one is explained by what the path names before its name.
  if (const auto format = CameraFileFormatFromPath(path)) return *format;
  const std::string name = path.string();
  switch (KindOfPath(path)) {
    case PathKind::kMissing: throw InputError(name + ": no such file; check the path");
    case PathKind::kDirectory: throw InputError(name + ": is a directory, not a camera file; give the file's path");
    case PathKind::kSpecial:
      throw InputError(name + ": is not a regular file (a device, a pipe or a socket), not a camera file; give the file itself");
    case PathKind::kRegularFile:
    case PathKind::kUnknown: break;
  }
  throw InputError(name + ": cannot tell the format from the file name; name it .json (vstcal/camera@1), .yaml or .yml "
                          "(OpenCV) or .cameramodel (mrcal)");
}

std::optional<CameraFileFormat> CameraFileFormatFromName(std::string_view name) {
  if (name == "camera") return CameraFileFormat::kVstcal;
  if (name == "opencv") return CameraFileFormat::kOpenCvYaml;
  if (name == "mrcal") return CameraFileFormat::kMrcal;
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
  }
  Conversion c{std::move(out.text), std::move(in.notes)};
  c.notes.insert(c.notes.end(), out.notes.begin(), out.notes.end());
  return c;
}

}  // namespace vstcal
