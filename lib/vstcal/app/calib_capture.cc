#include "vstcal/app/calib_capture.h"

#include <glob.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include "vstcal/formats/capture/capture_io.h"
#include "vstcal/image/image_io.h"
#include "vstcal/capture/overlay.h"
#include "vstcal/capture/target_drawing.h"
#include "vstcal/formats/capture/kalibr_target.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/formats/capture/volume_manifest.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/capture/image_times.h"
#include "vstcal/files/input_protection.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

namespace fs = std::filesystem;

constexpr size_t kMaxOverlays = 2000;

bool IsImageName(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* known : {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".pnm", ".webp"}) {
    if (ext == known) return true;
  }
  return false;
}

constexpr std::string_view kOverlaySuffix = ".overlay.png";

bool IsOverlayName(const fs::path& p) { return p.filename().string().ends_with(kOverlaySuffix); }

fs::path Canonical(const fs::path& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(p, ec);
  return ec ? p.lexically_normal() : c;
}

// Outputs never replace an input.
void RefuseOverwriting(const Outcome& outputs, const std::vector<fs::path>& inputs) {
  std::set<fs::path> in;
  for (const fs::path& p : inputs) in.insert(Canonical(p));
  for (const auto& [path, bytes] : outputs.files) {
    if (in.count(Canonical(path))) {
      throw InputError(path.string() + ": is an input of this run; writing it would destroy the input: choose another output");
    }
  }
}

std::string Join(const std::vector<std::pair<fs::path, std::string>>& files, size_t max) {
  std::string out;
  for (size_t k = 0; k < files.size() && k < max; ++k) out += (k ? ", " : "") + files[k].first.string();
  if (files.size() > max) out += " and " + std::to_string(files.size() - max) + " more";
  return out;
}

std::string Flag(std::string field) {
  std::replace(field.begin(), field.end(), '_', '-');
  return "--" + field;
}

}  // namespace

namespace {

std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string Sheet(double w_mm, double h_mm) { return Number(std::round(w_mm * 10) / 10) + " × " + Number(std::round(h_mm * 10) / 10) + " mm"; }

std::string PaperName(const Paper& p) {
  return p.name.find("mm") != std::string::npos ? p.name : p.name + " (" + Number(p.width_mm) + " × " + Number(p.height_mm) + " mm)";
}

// The target with its size fitted to the paper, or checked against it.
Target FitTarget(const TargetRequest& request) {
  Target t = request.target;
  if (!request.paper) return t;
  const Paper& paper = *request.paper;
  const bool tags = t.type == TargetType::kAprilTagGrid || t.type == TargetType::kAprilGrid;
  const double size = tags ? t.tag_size : t.square_size;
  const std::string field = tags ? VSTCAL_OPT("tag_size") : VSTCAL_OPT("square_size");
  const std::string unit(LengthUnitName(t.length_unit));
  const std::optional<PaperFit> fit = FitToPaper(t, request.given, paper);
  if (size == 0) {
    if (!fit) {
      throw InputError(VSTCAL_OPT("paper") ": the margin" + std::string(tags ? " and tag gap" : "") + " given leave no room for the board on " +
                       PaperName(paper) + "; give a smaller " VSTCAL_OPT("margin") + (tags ? " or " VSTCAL_OPT("tag_gap") : "") + ", or a larger " VSTCAL_OPT("paper"));
    }
    return WithSize(t, fit->size, request.given);
  }
  t = WithSize(t, size, request.given);
  const Rect sheet = SheetExtent(t);
  const double mm = MetresPer(t.length_unit) * 1000;
  if (SheetFitsPaper(sheet.width() * mm, sheet.height() * mm, paper)) return t;
  throw InputError(field + ": " + Number(size) + " " + unit + (tags ? " tags" : " squares") + " make a " +
                   Sheet(sheet.width() * mm, sheet.height() * mm) + " sheet, larger than " + PaperName(paper) + " either way; " +
                   (fit ? "at most " + Number(fit->size) + " " + unit + " fits (" + (fit->landscape ? "landscape" : "portrait") + "): give " +
                              field + " " + Number(fit->size) + ", or leave it out to fit the paper"
                        : "the margin given leaves no room: give a smaller " VSTCAL_OPT("margin") " or a larger " VSTCAL_OPT("paper")));
}

}  // namespace

Outcome MakeTarget(const TargetRequest& request_in, const Provenance& provenance) {
  TargetRequest request = request_in;
  if (!request.kalibr_file.empty()) {
    const Target kalibr = ReadKalibrTarget(request.kalibr_file);
    request.target = WithSize(kalibr, kalibr.type == TargetType::kAprilGrid ? kalibr.tag_size : kalibr.square_size, request.given);
  }
  request.target = FitTarget(request);
  if (const auto problem = CheckTarget(request.target)) throw InputError(Flag(problem->field) + ": " + problem->reason + "; " + problem->fix);
  if (request.output.empty()) throw InputError(VSTCAL_OPT("output") ": give the output's name (e.g. board)");
  if (!(request.dpi >= 0)) throw InputError(VSTCAL_OPT("dpi") ": must be ≥ 0 (0: no PNG)");
  Outcome out;
  out.files.emplace_back(request.output + ".target.json", DumpJson(TargetToJson(request.target, provenance)));
  out.files.emplace_back(request.output + ".svg", TargetSvg(request.target));
  std::string png;
  if (request.dpi > 0) {
    const GrayImage image = RasterizeTarget(request.target, request.dpi);
    out.files.emplace_back(request.output + ".png", EncodePng(image, request.dpi));
    char buf[96];
    std::snprintf(buf, sizeof buf, " (%g dpi, %d × %d px)", request.dpi, image.width, image.height);
    png = buf;
  }
  const Rect sheet = SheetExtent(request.target);
  const double mm = MetresPer(request.target.length_unit) * 1000;
  const double w = sheet.width() * mm, h = sheet.height() * mm;
  std::string on = "";
  if (request.paper) {
    on = " (fits " + PaperName(*request.paper) + (w > h ? " landscape" : " portrait") + ")";
  } else if (!SheetFitsPaper(w, h, StandardPapers()[0]) && !SheetFitsPaper(w, h, StandardPapers()[1])) {
    const std::optional<Paper> needs = SmallestStandardPaper(w, h);
    out.warnings.push_back("calib-capture: warning: the " + Sheet(w, h) + " sheet fits neither A4 nor Letter; it needs " +
                           (needs ? PaperName(*needs) : "a sheet larger than A3: " + Sheet(w, h)) +
                           " (or give " VSTCAL_OPT("paper") " a4 or " VSTCAL_OPT("paper") " letter to fit the board)");
  }
  out.summary = "calib-capture: " + DescribeTarget(request.target) + " on a " + Sheet(w, h) + " sheet" + on + "; wrote " + Join(out.files, 3) +
                png + "; print at 100 % (actual size)";
  return out;
}

std::string OverlayFileName(const std::string& view) { return view + std::string(kOverlaySuffix); }

ImageArguments ExpandImageArguments(const std::vector<std::string>& arguments) {
  ImageArguments out;
  std::vector<std::string>& images = out.images;
  for (const std::string& arg : arguments) {
    std::error_code ec;
    if (arg.empty()) throw InputError("an image argument is empty; give an image file, a folder or a glob");
    if (fs::is_directory(arg, ec)) {
      std::vector<std::string> found;
      size_t overlays = 0;
      for (const fs::directory_entry& e : fs::directory_iterator(arg, ec)) {
        if (!e.is_regular_file(ec) || !IsImageName(e.path())) continue;
        if (IsOverlayName(e.path())) {
          ++overlays;
        } else {
          found.push_back(e.path().string());
        }
      }
      if (found.empty()) {
        throw InputError(arg + ": no images (.png, .jpg, .jpeg, .bmp, .tif, .pgm …) in this folder" +
                         (overlays ? " but overlays (*.overlay.png) of an earlier " VSTCAL_OPT("overlay") : "") +
                         "; give the folder of the images");
      }
      out.overlays_left_out += overlays;
      std::sort(found.begin(), found.end());
      images.insert(images.end(), found.begin(), found.end());
    } else if (fs::exists(arg, ec)) {
      if (KindOfPath(arg) == PathKind::kSpecial) {
        throw InputError(arg + ": is not a regular file (a device, a pipe or a socket), not an image; give image files, a folder or a glob");
      }
      if (IsOverlayName(arg)) {
        throw InputError(arg + ": is an overlay an earlier " VSTCAL_OPT("overlay") " wrote (corners drawn on an image), not a view of the board; "
                               "give the image it was drawn on");
      }
      images.push_back(arg);
    } else if (arg.find_first_of("*?[") != std::string::npos) {
      glob_t matches{};
      const int status = glob(arg.c_str(), 0, nullptr, &matches);
      std::vector<std::string> found;
      if (status == 0) {
        for (size_t k = 0; k < matches.gl_pathc; ++k) {
          if (fs::is_directory(matches.gl_pathv[k], ec)) continue;
          if (IsOverlayName(matches.gl_pathv[k])) {
            ++out.overlays_left_out;
          } else {
            found.emplace_back(matches.gl_pathv[k]);
          }
        }
      }
      globfree(&matches);
      if (found.empty()) throw InputError(arg + ": no file matches this pattern; check the folder and the pattern (quote it for the shell)");
      std::sort(found.begin(), found.end());
      images.insert(images.end(), found.begin(), found.end());
    } else {
      throw InputError(arg + ": no such file or folder; check the path");
    }
  }
  return out;
}

namespace {

// Each image's time from the --times file, every image checked before any is searched.
std::map<std::string, double> ImageTimes(const DetectCommand& command, const std::vector<CaptureInput>& files) {
  if (command.times_file.empty()) return {};
  if (files.empty()) throw InputError(VSTCAL_OPT("times") ": gives image files their times; a video's frames have theirs (drop " VSTCAL_OPT("times") ")");
  const auto unit = FromName(kTimeUnitNames, command.times_unit);
  if (!unit) throw InputError(VSTCAL_OPT("times_unit") ": \"" + command.times_unit + "\" is not a time unit; use " + JoinedNames(kTimeUnitNames));
  std::vector<std::string> names;
  std::map<std::string, std::string> seen;  // file name → the image that has it
  for (const CaptureInput& f : files) {
    const std::string name = fs::path(f.image).filename().string();
    if (const auto [it, added] = seen.emplace(name, f.image); !added) {
      throw InputError(VSTCAL_OPT("times") ": " + it->second + " and " + f.image + " have one file name, which the times file cannot tell apart; "
                       "rename one, or detect each folder on its own");
    }
    names.push_back(name);
  }
  std::map<std::string, double> times = ReadImageTimes(command.times_file, names, *unit);
  for (const std::string& name : names) {
    if (!times.count(name)) throw InputError(command.times_file + ": no line for the image \"" + name + "\"; give every image its time");
  }
  return times;
}

}  // namespace

DetectedCorners DetectCorners(DetectCommand command, const Provenance& provenance, const Progress& progress) {
  const int sources = !command.images.empty() + !command.manifest.empty() + !command.video.file.empty() + (command.video.camera_index >= 0);
  if (sources != 1) {
    throw InputError(std::string(sources == 0 ? "no images: give" : "several image sources: give only one of") +
                     " image files/folders/globs, " VSTCAL_OPT("manifest") ", " VSTCAL_OPT("video") " or " VSTCAL_OPT("camera_index"));
  }
  if (!command.offset_pattern.empty() && command.images.empty()) {
    throw InputError(VSTCAL_OPT("offset_from_name") ": reads offsets from image file names; give the images, or use " VSTCAL_OPT("manifest"));
  }
  if (!command.overlay_folder.empty() && (!command.video.file.empty() || command.video.camera_index >= 0)) {
    throw InputError(VSTCAL_OPT("overlay") ": draws on image files; it does not apply to " VSTCAL_OPT("video") " or " VSTCAL_OPT("camera_index"));
  }
  DetectRequest& request = command.detect;
  request.target_file = command.target_file;
  request.target = ReadTarget(command.target_file);
  request.rig = !command.manifest.empty() || !command.offset_pattern.empty() ? Rig::kVolume : Rig::kPlanarViews;
  // One world frame for every view: a numbering flipped in one view would put its corners at the
  // wrong world points, so an ambiguous orientation is refused (chessboard_orientation.h).
  request.detector.refuse_ambiguous_orientation = request.rig == Rig::kVolume;

  std::vector<fs::path> inputs = {command.target_file};
  std::vector<CaptureInput> files;
  size_t overlays_left_out = 0;
  if (!command.manifest.empty()) {
    inputs.push_back(command.manifest);
    const VolumeManifest manifest = ReadVolumeManifest(command.manifest);
    const double to_target = MetresPer(manifest.length_unit) / MetresPer(request.target.length_unit);
    for (const ManifestImage& m : manifest.images) files.push_back({m.path.lexically_normal().string(), m.path, m.plane_offset * to_target});
  } else {
    const ImageArguments expanded = ExpandImageArguments(command.images);
    overlays_left_out = expanded.overlays_left_out;
    for (const std::string& image : expanded.images) {
      std::optional<double> offset;
      if (!command.offset_pattern.empty()) offset = OffsetFromName(image, command.offset_pattern, VSTCAL_OPT("offset_from_name"));
      files.push_back({image, image, offset});
    }
  }
  // Overlays are written with the output, all-or-nothing, so they are held in memory until then.
  if (!command.overlay_folder.empty() && files.size() > kMaxOverlays) {
    throw InputError(VSTCAL_OPT("overlay") ": " + std::to_string(files.size()) + " images; overlays are drawn for at most " + std::to_string(kMaxOverlays) +
                     " at a time: run without " VSTCAL_OPT("overlay") ", or on fewer images");
  }
  for (const CaptureInput& f : files) inputs.push_back(f.path);
  if (!command.video.file.empty()) inputs.push_back(command.video.file);
  const std::map<std::string, double> times = ImageTimes(command, files);
  if (!command.times_file.empty()) inputs.push_back(command.times_file);

  if (!command.output.empty()) {
    Outcome planned;
    planned.files.emplace_back(command.output, "");
    RefuseOverwriting(planned, inputs);  // before the work, not only after it
  }
  CaptureResult result = files.empty() ? DetectInVideo(command.video, request, progress) : DetectInFiles(files, request, progress);
  for (View& view : result.correspondences.views) {
    if (!times.empty()) view.time = times.at(fs::path(view.image).filename().string());
  }
  DetectedCorners detected;
  Outcome& out = detected.outcome;
  out.folders = {command.overlay_folder};
  // The corners as the file holds them, read back by the file's reader: a solver given the images
  // then solves exactly what it would solve from the written file.
  const std::string corners_json = DumpJson(CaptureToJson(result, request, provenance));
  detected.correspondences =
      CorrespondencesFromJson(JsonDocument::Parse(corners_json, command.output.empty() ? "the detected corners" : command.output));
  if (!command.output.empty()) out.files.emplace_back(command.output, corners_json);
  if (!command.overlay_folder.empty()) {
    for (size_t k = 0; k < result.images.size(); ++k) {
      if (result.detections[k].corners.empty()) continue;
      const LoadedImage loaded = LoadImageFile(files[k].path);
      if (!loaded.problem.empty()) continue;
      const std::string name = result.images[k].view.empty() ? fs::path(files[k].image).stem().string() : result.images[k].view;
      out.files.emplace_back(fs::path(command.overlay_folder) / OverlayFileName(name), OverlayPng(loaded.image, request.target, result.detections[k]));
    }
  }
  RefuseOverwriting(out, inputs);
  out.summary = command.tool + ": " + DescribeCounts(result.images) + "; " + std::to_string(NumObservations(result.correspondences)) +
                " corners in " + std::to_string(result.correspondences.views.size()) + " views (rig " +
                (request.rig == Rig::kVolume ? "volume" : "planar-views") + ")" + (out.files.empty() ? "" : "; wrote " + Join(out.files, 2));
  if (overlays_left_out > 0) {
    out.summary += "; left out " + std::to_string(overlays_left_out) + " overlays (*.overlay.png) of an earlier " VSTCAL_OPT("overlay");
  }
  return detected;
}

Outcome RunDetect(DetectCommand command, const Provenance& provenance, const Progress& progress) {
  if (command.output.empty()) throw InputError(VSTCAL_OPT("output") ": give the correspondences file to write");
  return DetectCorners(std::move(command), provenance, progress).outcome;
}

Outcome RunRender(const RenderCommand& command, const Provenance& provenance) {
  const Target target = ReadTarget(command.target_file);
  const CalibratedCamera camera = ReadCamera(command.camera_file);
  if (command.output_folder.empty()) throw InputError(VSTCAL_OPT("output") ": give the folder to write the images to");
  CheckRenderSize(camera.camera.image_size, command.camera_file);
  const RenderedScene scene = RenderScene(camera.camera, target, command.scene);
  const fs::path folder(command.output_folder);
  Outcome out;
  out.folders = {folder};
  for (size_t k = 0; k < scene.names.size(); ++k) out.files.emplace_back(folder / (scene.names[k] + ".png"), EncodePng(scene.images[k]));
  out.files.emplace_back(folder / "truth.json", DumpJson(CorrespondencesToJson(scene.truth, provenance)));
  CalibratedCamera truth = scene.truth_camera;
  truth.name = camera.name;
  out.files.emplace_back(folder / "camera.truth.json", DumpJson(CameraToJson(truth, provenance)));
  if (command.scene.rig == Rig::kVolume) {
    VolumeManifest manifest;
    manifest.length_unit = target.length_unit;
    for (const View& v : scene.truth.views) manifest.images.push_back({v.image, folder / v.image, *v.plane_offset});
    out.files.emplace_back(folder / "manifest.json", DumpJson(VolumeManifestToJson(manifest, provenance)));
  }
  RefuseOverwriting(out, {command.target_file, command.camera_file});
  out.summary = "calib-capture: rendered " + std::to_string(scene.names.size()) + " " + std::to_string(camera.camera.image_size.width) + "×" +
                std::to_string(camera.camera.image_size.height) + " images of the " + DescribeTarget(target) + "; wrote " + Join(out.files, 2) +
                " … in " + folder.string();
  return out;
}

}  // namespace vstcal::app
