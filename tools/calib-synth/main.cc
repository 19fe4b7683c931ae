// calib-synth: synthetic calibration volumes with ground truth (docs/tools/calib-synth.md).
#include <iostream>
#include <optional>

#include "common/run_tool.h"
#include "vstcal/camera/intrinsics.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/io/camera_io.h"
#include "vstcal/io/correspondences_io.h"

namespace {

using vstcal::InputError;

// "1280x720" → {1280, 720}.
std::pair<int, int> ParsePair(const std::string& text, const std::string& flag) {
  int a = 0, b = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &a, &x, &b, &extra) != 3 || (x != 'x' && x != 'X') || a <= 0 || b <= 0) {
    throw InputError(flag + ": expected two positive integers as WxH (e.g. 1280x720), got \"" + text + "\"");
  }
  return {a, b};
}

struct CameraFlags {
  std::string file, image_size, distortion;
  std::optional<double> fx, fy, hfov_deg, cx, cy;
  double skew_deg = 90;
};

vstcal::Camera MakeCamera(const CameraFlags& f) {
  using namespace vstcal;
  if (!f.file.empty()) return io::ReadCamera(f.file).camera;
  if (f.image_size.empty()) throw InputError("--image-size: required without --camera (e.g. --image-size 1280x720)");
  const auto [w, h] = ParsePair(f.image_size, "--image-size");
  if (f.fx.has_value() == f.hfov_deg.has_value()) throw InputError("--fx/--hfov-deg: give exactly one of them");
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
      try {
        coefficients.push_back(std::stod(item));
      } catch (const std::exception&) {
        throw InputError("--distortion: \"" + item + "\" is not a number; give k1,k2,p1,p2,k3");
      }
    }
    if (coefficients.size() != 5) throw InputError("--distortion: expected 5 numbers k1,k2,p1,p2,k3");
  }
  return Camera::FromK(K, ImageSize{w, h}, model, coefficients);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Writes a synthetic calibration volume (vstcal/correspondences@1): a planar grid template moved along its "
      "normal from --near to --far every --interval, seen by a known camera with Gaussian pixel noise, plus seed "
      "000's five test points. The ground truth camera (vstcal/camera@1, method \"synthetic\") goes beside it.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-synth"};
  std::string output, truth, grid = "13x9";
  CameraFlags cam;
  vstcal::VolumeSpec spec;
  std::string unit = "mm";
  bool no_test_points = false;
  app.add_option("-o,--output", output, "correspondences file to write")->required();
  app.add_option("--truth", truth, "ground-truth camera file (default: OUTPUT with .truth.json)");
  auto* camera_file = app.add_option("--camera", cam.file, "take K, distortion and image size from a camera@1 file");
  for (auto* o : {app.add_option("--image-size", cam.image_size, "WxH in px, e.g. 1280x720"),
                  app.add_option("--fx", cam.fx, "K's fx, px"), app.add_option("--fy", cam.fy, "K's fy, px (default fx)"),
                  app.add_option("--hfov-deg", cam.hfov_deg, "horizontal field of view instead of --fx"),
                  app.add_option("--cx", cam.cx, "principal point u, px (default image centre)"),
                  app.add_option("--cy", cam.cy, "principal point v, px (default image centre)"),
                  app.add_option("--skew-deg", cam.skew_deg, "angle between pixel axes, 90 = no skew")->capture_default_str(),
                  app.add_option("--distortion", cam.distortion, "k1,k2,p1,p2,k3 (radial-tangential)")}) {
    o->excludes(camera_file);
  }
  app.add_option("--grid", grid, "template corners COLSxROWS")->capture_default_str();
  app.add_option("--spacing", spec.spacing, "corner spacing")->capture_default_str();
  app.add_option("--near", spec.near, "first template offset (world Z)")->capture_default_str();
  app.add_option("--far", spec.far, "last template offset")->capture_default_str();
  app.add_option("--interval", spec.interval, "step between template positions")->capture_default_str();
  app.add_option("--camera-distance", spec.camera_distance, "camera to near plane at zero tilt")->capture_default_str();
  app.add_option("--tilt-deg", spec.tilt_deg, "optical axis vs template normal")->capture_default_str();
  app.add_option("--tilt-direction-deg", spec.tilt_direction_deg, "0 = camera moves towards +X, 90 = +Y")
      ->capture_default_str();
  app.add_option("--roll-deg", spec.roll_deg, "camera roll about its optical axis")->capture_default_str();
  app.add_option("--noise", spec.noise_px, "pixel noise sigma, px")->capture_default_str();
  app.add_option("--seed", spec.seed, "noise seed")->capture_default_str();
  app.add_option("--length-unit", unit, "mm, cm or m")->check(CLI::IsMember({"mm", "cm", "m"}))->capture_default_str();
  app.add_option("--camera-name", spec.camera_name, "the \"camera\" field, e.g. left");
  app.add_flag("--no-test-points", no_test_points, "omit seed 000's five test points");

  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    std::tie(spec.grid_cols, spec.grid_rows) = ParsePair(grid, "--grid");
    spec.length_unit = *LengthUnitFromName(unit);
    const Camera camera = MakeCamera(cam);
    const SyntheticVolume volume =
        SynthesizeVolume(camera, spec, no_test_points ? std::vector<TestPoint>{} : Seed000TestPoints(spec));

    CalibratedCamera truth_camera;
    truth_camera.name = spec.camera_name;
    truth_camera.camera = camera;
    truth_camera.length_unit = spec.length_unit;
    truth_camera.method = "synthetic";
    truth_camera.camera_from_world = volume.camera_from_world;
    truth_camera.fit = ComputeVolumeFit(camera, volume.camera_from_world, volume.correspondences);

    if (truth.empty()) {
      const std::filesystem::path p(output);
      truth = (p.parent_path() / (p.stem().string() + ".truth.json")).string();
    }
    const io::Provenance provenance = io::MakeProvenance("calib-synth", argc, argv, spec.seed);
    io::WriteFilesAtomically({{output, io::DumpJson(io::CorrespondencesToJson(volume.correspondences, provenance))},
                              {truth, io::DumpJson(io::CameraToJson(truth_camera, provenance))}});
    std::cerr << "calib-synth: " << NumObservations(volume.correspondences) << " points in "
              << volume.correspondences.views.size() << " views, " << volume.correspondences.test_points.size()
              << " test points; wrote " << output << " and " << truth << "\n";
    return 0;
  });
}
