// Reading and writing the vstcal formats (docs/formats.md) from Python: `read` checks a file with
// the same reader the tools use and returns it as Python objects; `write` checks a document the
// same way and writes it in vstcal's layout, atomically; `convert_camera` is calib-convert's call.
#include <algorithm>
#include <filesystem>
#include <functional>
#include <optional>

#include <pybind11/stl.h>

#include "bindings.h"
#include "vstcal/core/error.h"
#include "vstcal/core/units.h"
#include "vstcal/files/atomic_write.h"
#include "vstcal/formats/camera/camera_convert.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/capture/plan_compare.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/formats/capture/volume_manifest.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/shard_format.h"
#include "vstcal/formats/stereo/registration_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/json/reader_common.h"

namespace vstcal::python {
namespace {

// A format's validating reader; `folder` resolves the files a document names (a chain's cameras,
// a manifest's images).
using Check = std::function<void(const JsonDocument&, const std::filesystem::path& folder)>;

struct FormatEntry {
  std::string_view format;
  Check check;  // empty: vstcal writes the format but has no reader for it
};

const std::vector<FormatEntry>& Formats() {
  static const std::vector<FormatEntry> formats = {
      {"vstcal/correspondences@1", [](const JsonDocument& d, const auto&) { CorrespondencesFromJson(d); }},
      {"vstcal/camera@1", [](const JsonDocument& d, const auto&) { CameraFromJson(d); }},
      {"vstcal/stereo@1", [](const JsonDocument& d, const auto&) { StereoRigFromJson(d); }},
      {"vstcal/vst-chain@1", [](const JsonDocument& d, const auto& folder) { ChainSpecFromJson(d, folder); }},
      {"vstcal/target@1", [](const JsonDocument& d, const auto&) { TargetFromJson(d); }},
      {"vstcal/volume-manifest@1", [](const JsonDocument& d, const auto& folder) { VolumeManifestFromJson(d, folder); }},
      {"vstcal/tracks@1", [](const JsonDocument& d, const auto&) { TracksFromJson(d); }},
      {"vstcal/capture-plan@1", [](const JsonDocument& d, const auto&) { PlanPredictionFromJson(d); }},
      {"vstcal/err-sim-shard@2",
       [](const JsonDocument& d, const auto&) {
         RunDescription run;
         ShardFromJson(d, &run);
       }},
      {"vstcal/residuals@1", {}},
      {"vstcal/registration@1", {}},
      {"vstcal/stereo-plan@1", {}},
      {"vstcal/capture-plan-comparison@1", {}},
      {"vstcal/err-sim-report@3", {}},
      {"vstcal/err-sim-report@2", {}},
      {"vstcal/err-sim-sweep@2", {}},
      {"vstcal/err-sim-sobol@2", {}},
      {"vstcal/err-sim-linear@2", {}},
      {"vstcal/reproj-report@1", {}},
  };
  return formats;
}

std::string KnownFormats() {
  std::string s;
  for (const FormatEntry& f : Formats()) s += (s.empty() ? "" : ", ") + std::string(f.format);
  return s;
}

// The entry of a document's "format" (or of `expect` when given: its reader then says if the
// document is another format, in the tools' words).
const FormatEntry& EntryOf(const JsonDocument& doc, const std::optional<std::string>& expect) {
  std::string format;
  if (expect) {
    format = *expect;
  } else {
    doc.root().ExpectObject();
    format = doc.root().at("format").String();
  }
  const auto& formats = Formats();
  const auto it = std::find_if(formats.begin(), formats.end(), [&](const FormatEntry& f) { return f.format == format; });
  if (it == formats.end()) {
    throw InputError(doc.name() + ": format: \"" + format + "\" is not a vstcal format; expected one of " + KnownFormats());
  }
  return *it;
}

void CheckDocument(const JsonDocument& doc, const std::filesystem::path& folder, const std::optional<std::string>& expect) {
  const FormatEntry& entry = EntryOf(doc, expect);
  if (entry.check) {
    entry.check(doc, folder);
  } else if (expect) {  // no reader: the format field at least
    const std::string format = doc.root().at("format").String();
    if (format != *expect) {
      throw InputError(doc.name() + ": format: this is a \"" + format + "\" file, expected \"" + *expect + "\"; pass the right file");
    }
  }
}

std::optional<LengthUnit> UnitNamed(const std::optional<std::string>& name) {
  if (!name) return std::nullopt;
  for (size_t i = 0; i < kLengthUnits.size(); ++i) {
    if (kLengthUnitNames[i] == *name) return kLengthUnits[i];
  }
  throw InputError("length_unit: unknown unit \"" + *name + "\"; use mm, cm, m or in");
}

}  // namespace

void RegisterFiles(py::module_& m) {
  m.def(
      "read",
      [](const py::object& path, const std::optional<std::string>& expect) {
        const std::string file = PathOf(path, "path");
        const JsonDocument doc = JsonDocument::Load(file);
        CheckDocument(doc, std::filesystem::path(file).parent_path(), expect);
        const std::string text = ReadInputFile(file, "a JSON file");
        return ToPython(OrderedJson::parse(text));
      },
      py::arg("path"), py::arg("format") = py::none(),
      "Reads a vstcal file (any format of docs/formats.md), checked by the reader the tools use, as Python objects "
      "(dicts, lists, numbers, strings) in file order. `format` (e.g. \"vstcal/camera@1\"): refuse any other. "
      "Raises vstcal.InputError with the tools' one-line message.");
  m.def(
      "write",
      [](const py::object& path, const py::dict& document, const std::optional<std::string>& expect) {
        const std::string file = PathOf(path, "path");
        const JsonDocument doc = DocumentOf(document, "document");
        CheckDocument(doc, std::filesystem::path(file).parent_path(), expect);
        const std::string text = py::module_::import("json").attr("dumps")(document).cast<std::string>();
        WriteFileAtomically(file, DumpJson(OrderedJson::parse(text)));
      },
      py::arg("path"), py::arg("document"), py::arg("format") = py::none(),
      "Checks a document (a dict with a \"format\") by the reader the tools use, then writes it in vstcal's layout "
      "(two-space indent, shortest round-trip numbers), atomically. Formats vstcal only writes (reports) are written "
      "as given.");
  m.def("formats", [] {
    std::vector<std::string> names;
    for (const FormatEntry& f : Formats()) names.emplace_back(f.format);
    return names;
  }, "Every vstcal format `read` and `write` know.");
  m.def(
      "load_camera",
      [](const py::object& source) { return CameraFromJson(DocumentOf(source, "camera")).camera; },
      py::arg("camera"), "The vstcal.Camera of a vstcal/camera@1 file (path) or document (dict).");
  m.def(
      "convert_camera",
      [](const py::object& input, const std::string& to, const std::optional<std::string>& length_unit,
         const std::optional<std::string>& mrcal_lensmodel) {
        const std::string file = PathOf(input, "input");
        const std::optional<CameraFileFormat> from = CameraFileFormatFromPath(file);
        if (!from) throw InputError(file + ": unknown extension; give a .json (vstcal/camera@1), .yaml/.yml (OpenCV) or .cameramodel (mrcal) file");
        const std::optional<CameraFileFormat> target = CameraFileFormatFromName(to);
        if (!target) throw InputError("to: unknown format \"" + to + "\"; use camera, opencv or mrcal");
        ConvertOptions options;
        options.length_unit = UnitNamed(length_unit);
        options.mrcal_lensmodel = mrcal_lensmodel;
        const Conversion c = ConvertCamera(file, *from, *target, options, PythonProvenance("convert_camera"));
        return py::make_tuple(c.text, c.notes);
      },
      py::arg("input"), py::arg("to"), py::arg("length_unit") = py::none(), py::arg("mrcal_lensmodel") = py::none(),
      "calib-convert: the text of the camera file `input` (.json, .yaml/.yml or .cameramodel) in format `to` "
      "(\"camera\", \"opencv\" or \"mrcal\"), and the notes calib-convert prints.");
}

}  // namespace vstcal::python
