// calib-synth: synthetic calibration volumes with ground truth (docs/tools/calib-synth.md).
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/camera/intrinsics.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/io/camera_io.h"
#include "vstcal/io/correspondences_io.h"

namespace {

using vstcal::InputError;
using vstcal::tools::kFinite;
using vstcal::tools::kLengthUnit;
using vstcal::tools::kNonEmpty;
using vstcal::tools::kSeed;
using vstcal::tools::ParseSize;

struct CameraFlags {
  std::string file, image_size, distortion;
  std::optional<double> fx, fy, hfov_deg, cx, cy;
  double skew_deg = 90;
};

vstcal::Camera MakeCamera(const CameraFlags& f) {
  using namespace vstcal;
  if (!f.file.empty()) return io::ReadCamera(f.file).camera;
  if (f.image_size.empty()) throw InputError("--image-size: required without --camera (e.g. --image-size 1280x720)");
  const auto [w, h] = ParseSize(f.image_size, "--image-size", "WxH (e.g. 1280x720)");
  if (f.fx.has_value() == f.hfov_deg.has_value()) throw InputError("--fx/--hfov-deg: give exactly one of them");
  if (f.hfov_deg && !(*f.hfov_deg > 0 && *f.hfov_deg < 180)) {
    char got[40];
    std::snprintf(got, sizeof got, "%.6g", *f.hfov_deg);
    throw InputError(std::string("--hfov-deg: must lie in (0, 180) degrees for a pinhole camera, got ") + got);
  }
  if (!(f.skew_deg > 0 && f.skew_deg < 180)) throw InputError("--skew-deg: must lie in (0, 180); 90 means no skew");
  const double fx = f.fx ? *f.fx : FocalFromHorizontalFov(w, DegToRad(*f.hfov_deg));
  if (!(fx > 0) || !(f.fy.value_or(fx) > 0)) throw InputError("--fx/--fy/--hfov-deg: focal lengths must be positive");
  Eigen::Matrix3d K;
  K << fx, f.skew_deg == 90 ? 0.0 : -fx / std::tan(DegToRad(f.skew_deg)), f.cx.value_or(0.5 * (w - 1)),  //
      0, f.fy.value_or(fx), f.cy.value_or(0.5 * (h - 1)),                                                 //
      0, 0, 1;
  std::vector<double> coefficients;
  AnyLensModel model = PinholeModel{};
  if (!f.distortion.empty()) {
    model = RadialTangentialModel{};
    for (const std::string& item : CLI::detail::split(f.distortion, ',')) {
      // The whole item must be one finite number: std::stod alone would take "0.1x" as 0.1.
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v)) {
        throw InputError("--distortion: \"" + item + "\" is not a finite number; give k1,k2,p1,p2,k3");
      }
      coefficients.push_back(v);
    }
    if (coefficients.size() != 5) throw InputError("--distortion: expected 5 numbers k1,k2,p1,p2,k3");
  }
  return Camera::FromK(K, ImageSize{w, h}, model, coefficients);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Writes synthetic correspondences (vstcal/correspondences@1) with the ground-truth camera (vstcal/camera@1, "
      "method \"synthetic\") beside them. --rig volume (default): a planar grid template moved along its normal "
      "from --near to --far every --interval, plus seed 000's five test points. --rig planar-views: a board shown at "
      "--views poses spread over the field of view. Gaussian pixel noise from a counter-based stream.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-synth"};
  std::string output, truth, grid = "13x9";
  CameraFlags cam;
  vstcal::VolumeSpec spec;
  std::string unit = "mm";
  bool no_test_points = false;
  app.add_option("-o,--output", output, "correspondences file to write")->required()->check(kNonEmpty);
  app.add_option("--truth", truth, "ground-truth camera file (default: OUTPUT with .truth.json)")->check(kNonEmpty);
  auto* camera_file = app.add_option("--camera", cam.file, "take K, distortion and image size from a camera@1 file")
                          ->check(kNonEmpty);
  for (auto* o : {app.add_option("--image-size", cam.image_size, "WxH in px, e.g. 1280x720")->check(kNonEmpty),
                  app.add_option("--fx", cam.fx, "K's fx, px")->check(kFinite),
                  app.add_option("--fy", cam.fy, "K's fy, px (default fx)")->check(kFinite),
                  app.add_option("--hfov-deg", cam.hfov_deg, "horizontal field of view instead of --fx")
                      ->check(kFinite),
                  app.add_option("--cx", cam.cx, "principal point u, px (default image centre)")->check(kFinite),
                  app.add_option("--cy", cam.cy, "principal point v, px (default image centre)")->check(kFinite),
                  app.add_option("--skew-deg", cam.skew_deg, "angle between pixel axes, 90 = no skew")
                      ->check(kFinite)
                      ->capture_default_str(),
                  app.add_option("--distortion", cam.distortion, "k1,k2,p1,p2,k3 (radial-tangential)")
                      ->check(kNonEmpty)}) {
    o->excludes(camera_file);
  }
  std::string rig = "volume";
  vstcal::PlanarViewsSpec views;
  app.add_option("--rig", rig, "volume (a template moved between planes) or planar-views (a board waved about)")
      ->check(CLI::IsMember({"volume", "planar-views"}))
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
  const std::vector<std::string> volume_only = {"--near", "--far", "--interval", "--camera-distance", "--tilt-deg",
                                                "--tilt-direction-deg", "--roll-deg", "--no-test-points"};
  app.add_option("--views", views.num_views, "planar views: number of board poses")->capture_default_str();
  app.add_option("--distance", views.distance, "planar views: typical board depth")->check(kFinite)->capture_default_str();
  app.add_option("--max-tilt-deg", views.max_tilt_deg, "planar views: largest board tilt")
      ->check(kFinite)
      ->capture_default_str();
  const std::vector<std::string> planar_only = {"--views", "--distance", "--max-tilt-deg"};

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    const bool planar = rig == "planar-views";
    for (const std::string& flag : planar ? volume_only : planar_only) {
      if (app.count(flag) > 0) {
        throw InputError(flag + ": applies to --rig " + (planar ? "volume" : "planar-views") + " only; remove it or change --rig");
      }
    }
    std::tie(spec.grid_cols, spec.grid_rows) = ParseSize(grid, "--grid", "COLSxROWS (e.g. 13x9)");
    spec.length_unit = *LengthUnitFromName(unit);
    const Camera camera = MakeCamera(cam);

    CalibratedCamera truth_camera;
    truth_camera.name = spec.camera_name;
    truth_camera.camera = camera;
    truth_camera.length_unit = spec.length_unit;
    truth_camera.method = "synthetic";
    Correspondences corners;
    if (planar) {
      views.grid_cols = spec.grid_cols;
      views.grid_rows = spec.grid_rows;
      views.spacing = spec.spacing;
      views.noise_px = spec.noise_px;
      views.seed = spec.seed;
      views.length_unit = spec.length_unit;
      views.camera_name = spec.camera_name;
      const SyntheticViews synthetic = SynthesizePlanarViews(camera, views);
      for (const std::string& w : synthetic.warnings) std::cerr << "calib-synth: warning: " << w << "\n";
      corners = synthetic.correspondences;
      for (size_t v = 0; v < corners.views.size(); ++v) {
        truth_camera.views.push_back({corners.views[v].name, synthetic.camera_from_board[v], 0});
      }
      truth_camera.fit = ComputeViewsFit(camera, synthetic.camera_from_board, corners);
      for (size_t v = 0; v < corners.views.size(); ++v) truth_camera.views[v].rms_px = truth_camera.fit->views[v].stats.rms_px;
    } else {
      const SyntheticVolume volume =
          SynthesizeVolume(camera, spec, no_test_points ? std::vector<TestPoint>{} : Seed000TestPoints(spec));
      corners = volume.correspondences;
      truth_camera.camera_from_world = volume.camera_from_world;
      truth_camera.fit = ComputeVolumeFit(camera, volume.camera_from_world, corners);
    }

    if (truth.empty()) {
      const std::filesystem::path p(output);
      truth = (p.parent_path() / (p.stem().string() + ".truth.json")).string();
    }
    const io::Provenance provenance = io::MakeProvenance("calib-synth", argc, argv, spec.seed);
    io::WriteFilesAtomically({{output, io::DumpJson(io::CorrespondencesToJson(corners, provenance))},
                              {truth, io::DumpJson(io::CameraToJson(truth_camera, provenance))}});
    std::cerr << "calib-synth: " << NumObservations(corners) << " points in " << corners.views.size() << " views, "
              << corners.test_points.size() << " test points; wrote " << output << " and " << truth << "\n";
    return 0;
  });
}
