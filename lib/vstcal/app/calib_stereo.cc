#include "vstcal/app/calib_stereo.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <map>

#include "vstcal/capture/target_drawing.h"
#include "vstcal/core/error.h"
#include "vstcal/image/image_io.h"
#include "vstcal/stereo/rectify.h"
#include "vstcal/core/string_printf.h"
#include "vstcal/formats/camera/camera_convert.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/stereo/display_plan_io.h"
#include "vstcal/formats/stereo/registration_io.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/formats/stereo/stereo_peer_formats.h"
#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/estimators/uncertainty.h"
#include "vstcal/report/fit_summary.h"
#include "vstcal/core/option_name.h"

namespace vstcal::app {
namespace {

std::string Format(const char* format, auto... values) { return StringPrintf(format, values...); }

ImportedCamera ReadAnyCamera(const std::string& path, std::optional<LengthUnit> unit) {
  const CameraFileFormat format = InputCameraFileFormat(path);
  ImportedCamera in = ReadCameraFile(path, format, {unit, std::nullopt});
  // mrcal's all-zero extrinsics mean "this camera is the reference".
  if (format == CameraFileFormat::kMrcal && !in.camera.camera_from_world) in.camera.camera_from_world = Rigid3d::Identity();
  return in;
}

std::string RigSummary(const StereoRig& rig) {
  const std::string unit(LengthUnitName(rig.length_unit));
  const Eigen::Vector3d c = rig.right_from_left.inverse().t;  // right camera centre in the left frame
  std::string s = Format("baseline %.6g %s; right camera centre in the left frame (%.6g, %.6g, %.6g) %s; rotation %.4g deg\n",
                         rig.baseline(), unit.c_str(), c.x(), c.y(), c.z(), unit.c_str(),
                         RadToDeg(AngleBetween(rig.right_from_left.R, Eigen::Matrix3d::Identity())));
  if (const auto sigma = BaselineSigma(rig)) s += Format("baseline sigma %.3g %s\n", *sigma, unit.c_str());
  return s;
}

// Each camera's lens parameters ± σ and right_from_left's tangent σ (issue 24: a solver shows
// what it estimated with its uncertainty).
std::string RigParametersText(const StereoRig& rig) {
  std::string text = "left camera:\n" + ParametersText(rig.left, {}) + "right camera:\n" + ParametersText(rig.right, {});
  if (rig.covariance) {
    std::string line = "right_from_left 1-sigma:";
    for (const std::string& name : RelativePoseTangentNames()) {
      if (const auto k = rig.covariance->Find(name)) {
        line += Format(" %s %.3g", name.substr(name.rfind('.') + 1).c_str(), std::sqrt(rig.covariance->matrix(*k, *k)));
      }
    }
    text += line + " (rad, " + std::string(LengthUnitName(rig.length_unit)) + ")\n";
  }
  // The views that fit worst, by their epipolar error (both cameras at once), as calib-tsai names its own.
  if (rig.fit && rig.fit->views.size() > 1) {
    std::vector<StereoViewFit> views = rig.fit->views;
    std::stable_sort(views.begin(), views.end(), [](const StereoViewFit& a, const StereoViewFit& b) { return a.epipolar.rms_px > b.epipolar.rms_px; });
    text += "worst views by epipolar RMS:";
    for (size_t i = 0; i < std::min<size_t>(3, views.size()); ++i) text += Format("%s %s %.4f px", i ? "," : "", views[i].name.c_str(), views[i].epipolar.rms_px);
    text += "\n";
  }
  // What a user of each camera inherits (intrinsics only: a camera-frame direction, so any depth).
  const auto at_centre = [](const CalibratedCamera& c) -> std::string {
    const Eigen::Vector2d centre(0.5 * c.camera.image_size.width - 0.5, 0.5 * c.camera.image_size.height - 0.5);
    const auto e = ProjectionUncertaintyAtPixel(c, centre, 1000.0, ProjectionUncertaintyKind::kIntrinsicsOnly);
    return e ? Format("%.4f px", e->sigma_major_px) : std::string("(no covariance)");
  };
  text += "projection 1-sigma (major axis), intrinsics only, at the image centre: left " + at_centre(rig.left) + ", right " +
          at_centre(rig.right) + "\n";
  return text;
}

}  // namespace

Outcome Assemble(const AssembleRequest& request, const Provenance& provenance) {
  AssembleInput input;
  ImportedCamera left = ReadAnyCamera(request.left, request.length_unit);
  ImportedCamera right = ReadAnyCamera(request.right, request.length_unit);
  input.left = std::move(left.camera);
  input.right = std::move(right.camera);
  input.left_name = request.left;
  input.right_name = request.right;
  input.right_from_left = request.right_from_left;
  input.length_unit = request.length_unit.value_or(LengthUnit::kMillimetre);
  StereoRig rig = AssembleRig(input);
  if (request.rectify) rig.rectification = Rectify(rig, *request.rectify, request.output);
  Outcome out;
  out.files.emplace_back(request.output, DumpJson(StereoRigToJson(rig, provenance)));
  for (const auto& note : left.notes) out.summary += "note: " + note + "\n";
  for (const auto& note : right.notes) out.summary += "note: " + note + "\n";
  out.summary += RigSummary(rig);
  return out;
}

namespace {

// The image a view names, as given or beside its correspondences file; `field` names it in errors.
GrayImage LoadViewImage(const std::string& image, const std::string& file, const std::string& field, const ImageSize& size) {
  namespace fs = std::filesystem;
  fs::path path = image;
  if (!fs::exists(path) && path.is_relative()) path = fs::path(file).parent_path() / image;
  if (!fs::is_regular_file(path)) {
    throw InputError(field + "\"" + image + "\" not found (as given or beside the correspondences); run from the folder the path is " +
                     "relative to, or leave out " VSTCAL_OPT("undistort"));
  }
  LoadedImage loaded = LoadImageFile(path);
  if (!loaded.problem.empty()) throw InputError(field + path.string() + ": " + loaded.problem + "; give a PNG or JPEG");
  if (loaded.image.width != size.width || loaded.image.height != size.height) {
    throw InputError(field + path.string() + " is " + std::to_string(loaded.image.width) + "x" + std::to_string(loaded.image.height) +
                     " px but image_size is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                     "; give the image the corners were detected in");
  }
  return std::move(loaded.image);
}

// FOLDER/<key>.rectified.png for each view key both files name an image for; the summary's line.
std::string AddRectifiedPairs(const StereoRig& rig, Correspondences left, Correspondences right, const SolveRequest& request, Outcome* out) {
  const Rectification rectification = rig.rectification ? *rig.rectification : Rectify(rig, {}, request.output);
  if (rig.view_pairing) {
    KeyViews(rig.view_pairing->match_views, request.left, &left);
    KeyViews(rig.view_pairing->match_views, request.right, &right);
  }
  std::map<std::string, size_t> right_index;
  for (size_t v = 0; v < right.views.size(); ++v) right_index.emplace(right.views[v].name, v);
  size_t written = 0;
  for (size_t v = 0; v < left.views.size(); ++v) {
    const auto it = right_index.find(left.views[v].name);
    if (it == right_index.end() || left.views[v].image.empty() || right.views[it->second].image.empty()) continue;
    const GrayImage l = LoadViewImage(left.views[v].image, request.left, request.left + ": views[" + std::to_string(v) + "].image: ",
                                      rig.left.camera.image_size);
    const GrayImage r = LoadViewImage(right.views[it->second].image, request.right,
                                      request.right + ": views[" + std::to_string(it->second) + "].image: ", rig.right.camera.image_size);
    out->files.emplace_back(std::filesystem::path(request.undistort_folder) / (left.views[v].name + ".rectified.png"),
                            EncodePng(RectifiedPairImage(rig, rectification, l, r)));
    ++written;
  }
  if (written == 0) {
    throw InputError(VSTCAL_OPT("undistort") ": no view both cameras saw names its image in " + request.left + " and " + request.right +
                     " (views[].image); detect the corners with calib-capture detect, which records each view's image, or leave out " VSTCAL_OPT("undistort"));
  }
  out->folders.push_back(request.undistort_folder);
  return "wrote " + std::to_string(written) + " rectified pairs (<view>.rectified.png, left | right, epipolar lines every 40 px) in " +
         request.undistort_folder + (rig.rectification ? "" : " (OpenCV's default rectification; " VSTCAL_OPT("rectify") " keeps it in the rig)") + "\n";
}

// Neither a lens model nor terms were asked for: a given camera of another family than the default
// terms' model (a fisheye beside Brown–Conrady's k1, k2, p1, p2) chooses the lens model, and its
// own terms are estimated — rather than refusing the terms nobody asked for.
void ChooseLensModelFromCameras(const SolveRequest& request, StereoSolveOptions* options, Outcome* out) {
  RefineOptions& refinement = options->calibration.refinement;
  const AnyLensModel by_default = RefinedModel(PinholeModel{}, refinement);
  const std::pair<const std::string*, const std::optional<Camera>*> given[2] = {{&request.left_camera, &options->left_camera},
                                                                              {&request.right_camera, &options->right_camera}};
  const std::string* chosen_from = nullptr;
  const Camera* chosen = nullptr;
  for (const auto& [file, camera] : given) {
    if (!*camera) continue;
    const AnyLensModel& m = (**camera).model;
    if (chosen || LensModelExtends(by_default, m) || LensModelExtends(m, by_default)) continue;
    chosen = &**camera;
    chosen_from = file;
  }
  if (!chosen) return;
  // One lens model solves both cameras: two given cameras must agree on it.
  for (const auto& [file, camera] : given) {
    if (!*camera || (**camera).model.index() == chosen->model.index()) continue;
    throw InputError(*file + ": lens model \"" + std::string(LensModelName((**camera).model)) + "\", but " + *chosen_from +
                     " is \"" + std::string(LensModelName(chosen->model)) + "\"; give cameras of one lens model, or " +
                     VSTCAL_OPT("lens_model") " and " VSTCAL_OPT("distortion") " without the other camera");
  }
  if (!chosen) return;
  refinement.lens_model = std::string(LensModelName(chosen->model));
  refinement.free_distortion.clear();
  std::string terms;
  const auto names = LensModelParamNames(chosen->model);
  for (auto it = names.begin() + kNumIntrinsicParams; it != names.end(); ++it) {
    refinement.free_distortion.emplace_back(*it);
    terms.append(terms.empty() ? "" : ",").append(*it);
  }
  // Appended, not "literal" + std::string: GCC 12's -Wrestrict misfires on that.
  out->summary.append("note: lens model \"").append(refinement.lens_model).append("\" (terms ").append(terms);
  out->summary.append(") from ").append(*chosen_from);
  out->summary.append(", as neither " VSTCAL_OPT("lens_model") " nor " VSTCAL_OPT("distortion") " was given\n");
}

}  // namespace

Outcome Solve(const SolveRequest& request, const Provenance& provenance) {
  std::error_code ec;
  if (std::filesystem::equivalent(request.left, request.right, ec)) {
    throw InputError(request.left + " and " + request.right +
                     ": are the same file; give the left camera's correspondences, then the right camera's");
  }
  const Correspondences left = ReadCorrespondences(request.left), right = ReadCorrespondences(request.right);
  StereoSolveOptions options = request.options;
  Outcome out;
  for (auto [file, camera] : {std::pair{&request.left_camera, &options.left_camera}, std::pair{&request.right_camera, &options.right_camera}}) {
    if (file->empty()) continue;
    ImportedCamera in = ReadAnyCamera(*file, left.length_unit);
    *camera = in.camera.camera;
    for (const auto& note : in.notes) out.summary += "note: " + note + "\n";
  }
  if (request.lens_model_from_cameras) ChooseLensModelFromCameras(request, &options, &out);
  if ((options.hold_left && !options.left_camera) || (options.hold_right && !options.right_camera)) {
    out.summary += "note: a held camera without " VSTCAL_OPT("left_camera") "/" VSTCAL_OPT("right_camera") " is held at its own calibration from its file\n";
  }
  StereoSolveResult solved = SolveStereo(left, right, options, request.left, request.right);
  if (solved.exit_code != ExitCode::kOk) throw Error(solved.exit_code, solved.message);
  StereoRig& rig = solved.rig;
  if (request.rectify) rig.rectification = Rectify(rig, *request.rectify, request.output);
  out.files.emplace_back(request.output, DumpJson(StereoRigToJson(rig, provenance)));
  if (!request.undistort_folder.empty()) out.summary += AddRectifiedPairs(rig, left, right, request, &out);
  for (const auto& note : solved.notes) out.summary += "note: " + note + "\n";
  // A volume is one board pose (the world) whatever its planes; say so rather than "1 views".
  const std::string seen = left.rig == Rig::kVolume
                               ? Format("the volume (one pose, %zu planes) seen by both cameras", left.views.size())
                               : Format("%zu views seen by both cameras", solved.common_views.size());
  out.summary += Format("%s; reprojection RMS %.3g px (left), %.3g px (right); sigma %.3g px; epipolar RMS %.3g px; "
                     "%d iterations\n",
                     seen.c_str(), solved.rms_left_px, solved.rms_right_px, solved.sigma_px,
                     rig.fit ? rig.fit->epipolar.rms_px : 0.0, solved.iterations);
  out.summary += RigSummary(rig);
  out.summary += RigParametersText(rig);
  return out;
}

Outcome Export(const ExportRequest& request, const Provenance& provenance) {
  StereoRig rig = ReadStereoRig(request.rig);
  if (request.rectify) rig.rectification = Rectify(rig, *request.rectify, request.rig);
  Outcome out;
  std::vector<std::string> notes;
  if (!request.opencv.empty()) {
    const ExportedCamera yaml = OpenCvStereoYamlText(rig, request.rig, provenance);
    out.files.emplace_back(request.opencv, yaml.text);
    notes.insert(notes.end(), yaml.notes.begin(), yaml.notes.end());
  }
  if (!request.mrcal_left.empty()) {
    MrcalWriteOptions options;
    options.length_unit = request.mrcal_length_unit;
    const auto [l, r] = MrcalStereoTexts(rig, request.rig, options, provenance);
    out.files.emplace_back(request.mrcal_left, l.text);
    out.files.emplace_back(request.mrcal_right, r.text);
    for (const auto* e : {&l, &r}) notes.insert(notes.end(), e->notes.begin(), e->notes.end());
  }
  // Both mrcal files, and the YAML, say the same of the rig (its covariance and fit not written): once.
  std::vector<std::string> said;
  for (const auto& note : notes) {
    if (std::find(said.begin(), said.end(), note) != said.end()) continue;
    said.push_back(note);
    out.summary += "note: " + note + "\n";
  }
  return out;
}

Outcome Simulate(const SimulateRequest& request, const Provenance& provenance) {
  const StereoRig rig = ReadStereoRig(request.rig);
  const Tracks tracks = SyntheticTracks(rig, request.spec);
  Outcome out;
  out.files.emplace_back(request.output, DumpJson(TracksToJson(tracks, provenance)));
  out.summary = Format("%zu frames, %zu embedded points, %zu virtual points, noise %.3g px\n", tracks.frames.size(),
                    tracks.embedded.size(), tracks.virtual_points.size(), request.spec.noise_px);
  return out;
}

Outcome Register(const RegisterRequest& request, const Provenance& provenance) {
  const StereoRig rig = ReadStereoRig(request.rig);
  const Tracks tracks = ReadTracks(request.tracks);
  CheckTracksAgainstRig(rig, tracks, request.rig, request.tracks);
  if (request.options.mode == RegistrationMode::kPerEye) {
    for (size_t i = 0; i < tracks.frames.size(); ++i) {
      if (tracks.frames[i].right.empty()) {
        throw InputError(request.tracks + ": frames[" + std::to_string(i) +
                         "].right: missing; per-eye registration needs the right image's pixels in every frame "
                         "(or use " VSTCAL_OPT("mode") " left)");
      }
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<FrameRegistration> frames = RegisterSequence(rig, tracks, request.options);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  size_t registered = 0;
  for (const auto& f : frames) registered += f.status == PoseStatus::kOk;
  if (registered == 0) {
    throw DegenerateError(request.tracks + ": frames: no frame could be registered (frame \"" + tracks.frames[0].name +
                          "\": " + frames[0].failed_eye + " eye: " + std::string(PoseStatusText(frames[0].status)) +
                          "); track at least 4 embedded points, not on one line, in each frame");
  }
  Outcome out;
  const OrderedJson json = RegistrationToJson({request.rig, request.tracks, request.options}, rig, tracks, frames, provenance);
  out.files.emplace_back(request.output, DumpJson(json));
  out.summary = Format("%s registration: %zu of %zu frames registered, %.1f us per frame (%s start)\n",
                    std::string(RegistrationModeName(request.options.mode)).c_str(), registered, frames.size(),
                    1e6 * seconds / static_cast<double>(frames.size()),
                    request.options.warm_start ? "previous-frame" : "closed-form");
  for (const auto& f : json["frames"]) {
    if (f["status"] == "excluded") out.summary += "excluded " + f["name"].get<std::string>() + ": " + f["reason"].get<std::string>() + "\n";
  }
  const auto& accuracy = json["summary"]["accuracy"];
  if (!accuracy.is_null()) {
    for (const char* eye : {"left", "right"}) {
      out.summary += Format("%-5s vs truth: rotation RMS %.3g deg, centre RMS %.3g %s, virtual points RMS %.3g px (max %.3g)\n",
                         eye, accuracy[eye]["rotation_deg"]["rms"].get<double>(),
                         accuracy[eye]["centre_error"]["rms"].get<double>(), std::string(LengthUnitName(rig.length_unit)).c_str(),
                         accuracy[eye]["virtual_px"]["rms"].get<double>(), accuracy[eye]["virtual_px"]["max"].get<double>());
    }
  }
  return out;
}

Outcome Plan(const DisplayPlanRequest& request, const Provenance& provenance) {
  DisplayPlanInput input = request.input;
  LengthUnit unit = request.length_unit;
  std::string text;
  if (!request.rig.empty()) {
    if (input.baseline != 0 || input.focal_px || input.hfov_rad || input.capture_width) {
      throw InputError(VSTCAL_OPT("rig") ": the rig gives the baseline, the focal length and the capture width; drop " VSTCAL_OPT("baseline") ", "
                       VSTCAL_OPT("focal_px") ", " VSTCAL_OPT("hfov_deg") " and " VSTCAL_OPT("capture_width") ", or drop " VSTCAL_OPT("rig"));
    }
    const StereoRig rig = ReadStereoRig(request.rig);
    unit = rig.length_unit;
    input.baseline = rig.baseline();
    input.focal_px = rig.left.camera.params[intrinsic::kFx];
    input.capture_width = rig.left.camera.image_size.width;
    const double converge = RadToDeg(AngleBetween(rig.right_from_left.R, Eigen::Matrix3d::Identity()));
    if (converge > 0.5) {
      text += Format("note: %s: the cameras are rotated %.3g deg from each other; the plan assumes parallel cameras\n",
                     request.rig.c_str(), converge);
    }
  }
  const DisplayPlan plan = PlanDisplay(input);
  Outcome out;
  out.files.emplace_back(request.output, DumpJson(DisplayPlanToJson(input, plan, unit, provenance)));
  const std::string u(LengthUnitName(unit));
  text += Format("focal %.6g px, translation %.4g px, capture width needed %.6g px", plan.focal_px, plan.translation_px,
                 plan.capture_width_needed);
  if (plan.capture_margin_px) text += Format(" (margin %d px)", *plan.capture_margin_px);
  text += "\n";
  if (plan.diverges_beyond) text += Format("the viewer's eyes diverge beyond %.6g %s\n", *plan.diverges_beyond, u.c_str());
  for (const DepthRow& r : plan.rows) {
    text += Format("depth %10.6g %s: disparity %9.4g px, parallax %9.4g px (%s)", r.depth, u.c_str(), r.disparity_px,
                   r.parallax_px, r.side < 0 ? "in front" : r.side > 0 ? "behind" : "on the screen");
    if (input.viewer != Viewer::kNone) {
      text += r.perceived_depth ? Format(", perceived at %.6g %s", *r.perceived_depth, u.c_str()) : std::string(", diverges");
    }
    text += "\n";
  }
  out.summary = text;
  return out;
}

}  // namespace vstcal::app
