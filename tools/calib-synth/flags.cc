#include "flags.h"

#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"

namespace vstcal::tools {
namespace {

const std::vector<std::string> kVolumeOnly = {"--near",     "--far",          "--interval", "--camera-distance",
                                              "--tilt-deg", "--tilt-direction-deg", "--roll-deg", "--no-test-points"};
const std::vector<std::string> kPlanarOnly = {"--views", "--distance", "--max-tilt-deg"};
const std::vector<std::string> kHandEyeOnly = {"--time-offset", "--duration", "--rate", "--tracker-noise-deg", "--tracker-noise", "--view-jitter", "--images"};

}  // namespace

void SynthFlags::Add(CLI::App& app) {
  SyntheticCameraSpec& cam = request.camera;
  VolumeSpec& spec = request.volume;
  PlanarViewsSpec& views = request.views;
  app.add_option("-o,--output", request.output, "correspondences file to write")->required()->check(kNonEmpty);
  app.add_option("--truth", request.truth, "ground-truth camera file (default: OUTPUT with .truth.json)")->check(kNonEmpty);
  auto* camera_file = app.add_option("--camera", request.camera_file, "take K, distortion and image size from a camera@1 file")
                          ->check(kNonEmpty);
  for (auto* o : {app.add_option("--image-size", image_size, "WxH in px, e.g. 1280x720")->check(kNonEmpty),
                  app.add_option("--fx", cam.fx, "K's fx, px")->check(kFinite),
                  app.add_option("--fy", cam.fy, "K's fy, px (default fx)")->check(kFinite),
                  app.add_option("--hfov-deg", cam.hfov_deg, "horizontal field of view instead of --fx")
                      ->check(kFinite),
                  app.add_option("--cx", cam.cx, "principal point u, px (default image centre)")->check(kFinite),
                  app.add_option("--cy", cam.cy, "principal point v, px (default image centre)")->check(kFinite),
                  app.add_option("--skew-deg", cam.skew_deg, "angle between pixel axes, 90 = no skew")
                      ->check(kFinite)
                      ->capture_default_str(),
                  app.add_option("--distortion", cam.distortion,
                                 "k1,k2,p1,p2,k3 (radial-tangential) or k1,k2,p1,p2,k3,k4,k5,k6 (rational)")
                      ->delimiter(',')
                      ->check(kFinite)}) {
    o->excludes(camera_file);
  }
  app.add_option("--rig", rig,
                 "volume (a template moved between planes), planar-views (a board waved about) or handeye (a headset "
                 "carrying the camera moved in front of the board, with the tracker's log)")
      ->check(CLI::IsMember({"volume", "planar-views", "handeye"}))
      ->capture_default_str();
  app.add_option("--grid", grid, "template corners COLSxROWS")->capture_default_str();
  app.add_option("--spacing", spec.spacing, "corner spacing")->check(kFinite)->capture_default_str();
  app.add_option("--near", spec.near, "first template offset (world Z)")->check(kFinite)->capture_default_str();
  app.add_option("--far", spec.far, "last template offset")->check(kFinite)->capture_default_str();
  app.add_option("--interval", spec.interval, "step between template positions")->check(kFinite)->capture_default_str();
  app.add_option("--camera-distance", spec.camera_distance, "camera to near plane at zero tilt")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--tilt-deg", spec.tilt_deg, "optical axis vs template normal")->check(kFinite)->capture_default_str();
  app.add_option("--tilt-direction-deg", spec.tilt_direction_deg, "0 = camera moves towards +X, 90 = +Y")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--roll-deg", spec.roll_deg, "camera roll about its optical axis")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--noise", spec.noise_px, "pixel noise sigma, px")->check(kFinite)->capture_default_str();
  app.add_option("--seed", spec.seed, "noise seed")->check(kSeed)->capture_default_str();
  app.add_option("--length-unit", unit, "mm, cm, m or in")->check(kLengthUnit)->capture_default_str();
  app.add_option("--camera-name", spec.camera_name, "the \"camera\" field, e.g. left");
  app.add_flag("--no-test-points", no_test_points, "omit seed 000's five test points");
  app.add_flag("-q,--quiet", quiet, "print only warnings and errors (no summary)");
  app.add_option("--views", views.num_views, "planar views: number of board poses")->capture_default_str();
  app.add_option("--distance", views.distance, "planar views: typical board depth")->check(kFinite)->capture_default_str();
  app.add_option("--max-tilt-deg", views.max_tilt_deg, "planar views: largest board tilt")
      ->check(kFinite)
      ->capture_default_str();
  HandEyeSpec& he = request.handeye_spec;
  app.add_option("--time-offset", he.time_offset, "handeye: the tracker's clock ahead of the camera's, s")->check(kFinite)->capture_default_str();
  app.add_option("--duration", he.duration, "handeye: the recording's length, s")->check(kPositiveFinite)->capture_default_str();
  app.add_option("--rate", he.rate_hz, "handeye: the tracker's reports a second")->check(kPositiveFinite)->capture_default_str();
  app.add_option("--view-jitter", he.view_jitter,
                 "handeye: each view's time later by a uniform draw in [0, this) s — a camera clock not locked to the tracker's")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--tracker-noise-deg", he.tracker_noise_deg, "handeye: the tracker's rotation noise per axis, degrees")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--tracker-noise", he.tracker_noise, "handeye: the tracker's translation noise per axis (length unit)")
      ->check(kFinite)
      ->capture_default_str();
  app.add_option("--images", request.images_folder,
                 "handeye: also render each view as a chessboard photograph into this folder, with board.target.json and "
                 "times.txt (calib-capture detect --times)")
      ->check(kNonEmpty);
}

app::SynthRequest SynthFlags::Finish(const CLI::App& app) {
  request.planar_views = rig == "planar-views";
  request.handeye = rig == "handeye";
  // The flags of the other set-ups; --views and --distance serve hand-eye recordings too.
  std::vector<std::pair<std::string, const char*>> refused;
  if (rig != "volume") for (const std::string& f : kVolumeOnly) refused.emplace_back(f, "volume");
  if (rig == "volume") for (const std::string& f : kPlanarOnly) refused.emplace_back(f, "planar-views or handeye");
  if (rig == "handeye") refused.emplace_back("--max-tilt-deg", "planar-views");
  if (rig != "handeye") for (const std::string& f : kHandEyeOnly) refused.emplace_back(f, "handeye");
  for (const auto& [flag, where] : refused) {
    if (app.count(flag) > 0) throw InputError(flag + ": applies to --rig " + where + " only; remove it or change --rig");
  }
  if (request.handeye && app.count("--views") == 0) request.views.num_views = 30;
  if (request.handeye && app.count("--distance") == 0) request.views.distance = request.handeye_spec.distance;
  VolumeSpec& spec = request.volume;
  std::tie(spec.grid_cols, spec.grid_rows) =
      ParseSize(grid, "--grid", "COLSxROWS (e.g. 13x9)", static_cast<int>(limits::kMaxPoints));
  spec.length_unit = *LengthUnitFromName(unit);
  request.test_points = !no_test_points;
  if (request.camera_file.empty()) {
    if (image_size.empty()) throw InputError("--image-size: required without --camera (e.g. --image-size 1280x720)");
    const auto [w, h] = ParseSize(image_size, "--image-size", "WxH (e.g. 1280x720)", limits::kMaxImageSide);
    request.camera.image_size = ImageSize{w, h};
  }
  return request;
}

}  // namespace vstcal::tools
