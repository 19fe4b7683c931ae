// calib-synth: synthetic calibration volumes with ground truth (docs/tools/calib-synth.md).
#include <filesystem>
#include <iostream>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace {

using vstcal::tools::kFinite;
using vstcal::tools::kLengthUnit;
using vstcal::tools::kNonEmpty;
using vstcal::tools::kSeed;

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Writes synthetic correspondences (vstcal/correspondences@1) with the ground-truth camera (vstcal/camera@1, "
      "method \"synthetic\") beside them. --rig volume (default): a planar grid template moved along its normal "
      "from --near to --far every --interval, plus seed 000's five test points. --rig planar-views: a board shown at "
      "--views poses spread over the field of view. Gaussian pixel noise from a counter-based stream.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-synth"};
  std::string output, truth, grid = "13x9", camera_path, image_size;
  vstcal::SyntheticCameraSpec cam;
  vstcal::VolumeSpec spec;
  std::string unit = "mm";
  bool no_test_points = false, quiet = false;
  app.add_option("-o,--output", output, "correspondences file to write")->required()->check(kNonEmpty);
  app.add_option("--truth", truth, "ground-truth camera file (default: OUTPUT with .truth.json)")->check(kNonEmpty);
  auto* camera_file = app.add_option("--camera", camera_path, "take K, distortion and image size from a camera@1 file")
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
  app.add_flag("-q,--quiet", quiet, "print only warnings and errors (no summary)");
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
    std::tie(spec.grid_cols, spec.grid_rows) =
        tools::ParseSize(grid, "--grid", "COLSxROWS (e.g. 13x9)", static_cast<int>(limits::kMaxPoints));
    spec.length_unit = *LengthUnitFromName(unit);
    if (truth.empty()) truth = std::filesystem::path(output).replace_extension(".truth.json").string();
    DeclareOutputs({output, truth});
    if (camera_path.empty()) {
      if (image_size.empty()) throw InputError("--image-size: required without --camera (e.g. --image-size 1280x720)");
      const auto [w, h] = tools::ParseSize(image_size, "--image-size", "WxH (e.g. 1280x720)", limits::kMaxImageSide);
      cam.image_size = ImageSize{w, h};
    }
    const Camera camera = camera_path.empty() ? MakeSyntheticCamera(cam) : ReadCamera(camera_path).camera;

    CalibratedCamera truth_camera;
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
      truth_camera = PlanarViewsTruthCamera(camera, views, synthetic);
      corners = synthetic.correspondences;
    } else {
      const SyntheticVolume volume =
          SynthesizeVolume(camera, spec, no_test_points ? std::vector<TestPoint>{} : Seed000TestPoints(spec));
      truth_camera = VolumeTruthCamera(camera, spec, volume);
      corners = volume.correspondences;
    }

    const Provenance provenance = MakeProvenance("calib-synth", argc, argv, spec.seed);
    WriteFilesAtomically({{output, DumpJson(CorrespondencesToJson(corners, provenance))},
                              {truth, DumpJson(CameraToJson(truth_camera, provenance))}});
    if (!quiet) std::cerr << "calib-synth: " << NumObservations(corners) << " points in " << corners.views.size() << " views, "
              << corners.test_points.size() << " test points; wrote " << output << " and " << truth << "\n";
    return 0;
  });
}
