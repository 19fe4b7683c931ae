#include "calib-stereo/subcommands.h"

#include <memory>

#include "common/calibration_flags.h"
#include "common/validators.h"
#include "vstcal/core/error.h"

namespace vstcal::tools {
namespace {

const std::vector<std::string> kUnits = {"mm", "cm", "m"};

// --rectify and --alpha, shared by assemble and export.
struct RectifyFlags {
  bool rectify = false;
  double alpha = -1;
  void Add(CLI::App* app) {
    app->add_flag("--rectify", rectify, "add OpenCV's stereoRectify (R1, R2, P1, P2, Q, valid rectangles)");
    app->add_option("--alpha", alpha, "stereoRectify's free scaling: -1 (OpenCV's default), 0 (valid pixels only) ... 1 (all pixels)")
        ->check(kFinite);
  }
  std::optional<RectifyOptions> Get(CLI::App* app) const {
    if (app->count("--alpha") && !rectify) throw InputError("--alpha: applies with --rectify only; add --rectify or drop --alpha");
    if (!rectify) return std::nullopt;
    return RectifyOptions{alpha, true};
  }
};

std::optional<LengthUnit> Unit(const std::string& name) {
  return name.empty() ? std::nullopt : LengthUnitFromName(name);
}

}  // namespace

Subcommand AddSolve(CLI::App& parent) {
  struct Flags {
    app::SolveRequest request;
    CalibrationFlags calibration;
    RectifyFlags rectify;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "solve",
      "a rig from two correspondences@1 files of the same target poses (views matched by name; a view in one file only "
      "serves that camera): each camera calibrated alone, right_from_left from the rotation average of the views, then "
      "both lenses, right_from_left and the board poses refined together, with right_from_left's covariance");
  app->add_option("LEFT", f->request.left, "left camera's correspondences (vstcal/correspondences@1)")->required()->check(kNonEmpty);
  app->add_option("RIGHT", f->request.right, "right camera's correspondences (vstcal/correspondences@1)")->required()->check(kNonEmpty);
  app->add_option("-o,--output", f->request.output, "rig to write (vstcal/stereo@1)")->required()->check(kNonEmpty);
  app->add_option("--left-camera", f->request.left_camera, "a calibrated left camera (.json, .yaml/.yml, .cameramodel): its intrinsics start the left lens")
      ->check(kNonEmpty);
  app->add_option("--right-camera", f->request.right_camera, "a calibrated right camera: its intrinsics start the right lens")->check(kNonEmpty);
  app->add_flag("--hold-left", f->request.options.hold_left, "hold the left intrinsics fixed (at --left-camera, else at its own calibration)");
  app->add_flag("--hold-right", f->request.options.hold_right, "hold the right intrinsics fixed (at --right-camera, else at its own calibration)");
  app->add_option("--match-views", f->request.options.view_key_pattern,
                  "match views by the first group of this regular expression in their names, e.g. '([0-9]+)$' pairs left01 "
                  "with right01 (default: by the whole name, or by the number in names that differ only by a left/right token)")
      ->check(kNonEmpty);
  app->add_option("--undistort", f->request.undistort_folder,
                  "check images: write each pair both cameras saw, rectified side by side with epipolar lines, as DIR/<view>.rectified.png")
      ->check(kNonEmpty)
      ->type_name("DIR");
  app->add_option("--min-common-views", f->request.options.min_common_views, "planar views both cameras must share (default 3)")
      ->check(CLI::Range(1, 1000000));
  // The joint problem is least squares: no --loss, --loss-scale.
  for (CLI::Option* option : f->calibration.AddRefinement(*app)) {
    if (option->check_lname("loss") || option->check_lname("loss-scale")) app->remove_option(option);
  }
  f->calibration.loss_scale_option = nullptr;
  f->rectify.Add(app);
  return {app, [f, app](const Provenance& provenance) {
            app::SolveRequest r = f->request;
            r.options.calibration.refinement = f->calibration.Refinement();
            r.lens_model_from_cameras = f->calibration.lens_model.empty() && f->calibration.distortion_option->count() == 0;
            r.rectify = f->rectify.Get(app);
            return app::Solve(r, provenance);
          }};
}

Subcommand AddAssemble(CLI::App& parent) {
  struct Flags {
    app::AssembleRequest request;
    std::vector<double> rotvec_deg, translation;
    std::string unit;
    RectifyFlags rectify;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "assemble",
      "a rig from two camera files (vstcal/camera@1 .json, OpenCV .yaml/.yml, mrcal .cameramodel) and right_from_left: "
      "given by --translation (and --rotvec-deg), or derived from the cameras' poses in one frame (two mrcal files "
      "sharing a reference, or two camera@1 files solved against one volume)");
  app->add_option("LEFT", f->request.left, "left camera file")->required()->check(kNonEmpty);
  app->add_option("RIGHT", f->request.right, "right camera file")->required()->check(kNonEmpty);
  app->add_option("-o,--output", f->request.output, "rig to write (vstcal/stereo@1)")->required()->check(kNonEmpty);
  app->add_option("--translation", f->translation, "t of right_from_left: tx,ty,tz (x_right = R x_left + t), length unit")
      ->delimiter(',')->expected(3)->check(kFinite);
  app->add_option("--rotvec-deg", f->rotvec_deg, "R of right_from_left as a rotation vector in degrees: rx,ry,rz (default 0,0,0)")
      ->delimiter(',')->expected(3)->check(kFinite);
  app->add_option("--length-unit", f->unit, "mm, cm or m: the unit of --translation (default mm) and of .cameramodel and OpenCV YAML inputs")
      ->check(CLI::IsMember(kUnits));
  f->rectify.Add(app);
  return {app, [f, app](const Provenance& provenance) {
            app::AssembleRequest r = f->request;
            if (!f->rotvec_deg.empty() && f->translation.empty()) {
              throw InputError("--rotvec-deg: given without --translation; give both, or neither to derive right_from_left from the cameras' poses");
            }
            if (!f->translation.empty()) {
              Eigen::Vector3d rotvec = Eigen::Vector3d::Zero();
              if (!f->rotvec_deg.empty()) rotvec << DegToRad(f->rotvec_deg[0]), DegToRad(f->rotvec_deg[1]), DegToRad(f->rotvec_deg[2]);
              r.right_from_left = Rigid3d::FromRotvec(rotvec, Eigen::Vector3d(f->translation[0], f->translation[1], f->translation[2]));
            }
            r.length_unit = Unit(f->unit);
            r.rectify = f->rectify.Get(app);
            return app::Assemble(r, provenance);
          }};
}

Subcommand AddExport(CLI::App& parent) {
  struct Flags {
    app::ExportRequest request;
    std::vector<std::string> mrcal;
    std::string unit;
    RectifyFlags rectify;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "export", "the rig for OpenCV (one stereo YAML: M1, D1, M2, D2, R, T, E, F and, with a rectification, R1, R2, P1, "
                "P2, Q) and/or for mrcal (two .cameramodel files whose reference frame is the left camera)");
  app->add_option("RIG", f->request.rig, "rig file (vstcal/stereo@1)")->required()->check(kNonEmpty);
  app->add_option("--opencv", f->request.opencv, "OpenCV FileStorage YAML to write")->check(kNonEmpty);
  app->add_option("--mrcal", f->mrcal, "the left and the right .cameramodel to write")->expected(2)->check(kNonEmpty);
  app->add_option("--length-unit", f->unit, "mm, cm or m: unit of the .cameramodel translation (default: the rig's)")
      ->check(CLI::IsMember(kUnits));
  f->rectify.Add(app);
  return {app, [f, app](const Provenance& provenance) {
            app::ExportRequest r = f->request;
            if (r.opencv.empty() && f->mrcal.empty()) throw InputError("export: nothing to write; give --opencv FILE and/or --mrcal LEFT RIGHT");
            if (!f->mrcal.empty()) std::tie(r.mrcal_left, r.mrcal_right) = std::tie(f->mrcal[0], f->mrcal[1]);
            if (!f->unit.empty() && f->mrcal.empty()) throw InputError("--length-unit: applies to --mrcal output only; drop it");
            r.mrcal_length_unit = Unit(f->unit);
            r.rectify = f->rectify.Get(app);
            if (r.rectify && r.opencv.empty()) throw InputError("--rectify: the rectification goes into --opencv's YAML; give --opencv");
            return app::Export(r, provenance);
          }};
}

Subcommand AddSimulate(CLI::App& parent) {
  struct Flags {
    app::SimulateRequest request;
    std::string layout = "planar";
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "simulate", "synthetic tracks (vstcal/tracks@1) with the true pose of every frame: the rig moving in front of 4 "
                  "coplanar (or 6 spatial) embedded points, Gaussian pixel noise; input for `register`");
  SyntheticTracksSpec& s = f->request.spec;
  app->add_option("RIG", f->request.rig, "rig file (vstcal/stereo@1)")->required()->check(kNonEmpty);
  app->add_option("-o,--output", f->request.output, "tracks to write")->required()->check(kNonEmpty);
  app->add_option("--frames", s.frames, "frames")->check(CLI::Range(1, 1000000))->capture_default_str();
  app->add_option("--noise", s.noise_px, "pixel noise σ per coordinate, px")->check(kNonNegativeFinite)->capture_default_str();
  app->add_option("--seed", s.seed, "random seed")->check(kSeed)->capture_default_str();
  app->add_option("--layout", f->layout, "planar (4 points in a square) or spatial (6 points)")
      ->check(CLI::IsMember({"planar", "spatial"}))->capture_default_str();
  app->add_option("--size", s.size, "side of the square or cube of embedded points, the rig's length unit")->check(kPositiveFinite)->capture_default_str();
  app->add_option("--distance", s.distance, "distance of the rig from the points, the rig's length unit")->check(kPositiveFinite)->capture_default_str();
  return {app, [f](const Provenance& provenance) {
            app::SimulateRequest r = f->request;
            r.spec.planar = f->layout == "planar";
            return app::Simulate(r, provenance);
          }};
}

Subcommand AddRegister(CLI::App& parent) {
  struct Flags {
    app::RegisterRequest request;
    std::string mode = "left";
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "register", "binocular registration of every frame of a tracks file: the left pose by PnP (closed form, then "
                  "Levenberg-Marquardt), the right one by composition with the rig (seed 000 §4.3), and the virtual points "
                  "in both images; or each eye on its own (per-eye), or both eyes in one solve (joint)");
  app->add_option("RIG", f->request.rig, "rig file (vstcal/stereo@1)")->required()->check(kNonEmpty);
  app->add_option("TRACKS", f->request.tracks, "tracks file (vstcal/tracks@1)")->required()->check(kNonEmpty);
  app->add_option("-o,--output", f->request.output, "registration to write (vstcal/registration@1)")->required()->check(kNonEmpty);
  app->add_option("--mode", f->mode, "left (seed 000), per-eye or joint")
      ->check(CLI::IsMember(NamesOf(kRegistrationModeNames)))->capture_default_str();
  app->add_flag("--warm-start", f->request.options.warm_start,
                "start each frame from the previous frame's pose instead of the closed form (tracking)");
  return {app, [f](const Provenance& provenance) {
            app::RegisterRequest r = f->request;
            r.options.mode = *FromName(kRegistrationModeNames, f->mode);
            return app::Register(r, provenance);
          }};
}

Subcommand AddPlan(CLI::App& parent) {
  struct Flags {
    app::DisplayPlanRequest request;
    double hfov_deg = 0, focal = 0, z0 = 0;
    int capture_width = 0;
    std::string viewer = "none", unit;
  };
  auto f = std::make_shared<Flags>();
  CLI::App* app = parent.add_subcommand(
      "plan", "stereo display planning (seed 000 Eq. 3-6): disparity and screen parallax at each depth before and after "
              "translating the images so that z0 has zero parallax, the translation, the capture width it needs, and what "
              "a viewer with another IPD than the baseline perceives (seed 001 §4.6)");
  DisplayPlanInput& in = f->request.input;
  app->add_option("-o,--output", f->request.output, "plan to write (vstcal/stereo-plan@1)")->required()->check(kNonEmpty);
  app->add_option("--rig", f->request.rig, "take the baseline, focal length and capture width from this rig")->check(kNonEmpty);
  app->add_option("--baseline", in.baseline, "camera baseline b")->check(kPositiveFinite);
  app->add_option("--focal-px", f->focal, "the capture's horizontal focal length, px")->check(kPositiveFinite);
  app->add_option("--hfov-deg", f->hfov_deg, "the capture's horizontal field of view across its width (seed 000's θ), degrees")
      ->check(kPositiveFinite);
  app->add_option("--capture-width", f->capture_width, "the camera's image width, px, to check against the need")
      ->check(kPositiveCount);
  app->add_option("--display-width", in.display_width, "the display's width A, px")->required()->check(kPositiveCount);
  app->add_option("--z0", f->z0, "zero-parallax depth (default: none, the images shown as captured)")->check(kPositiveFinite);
  app->add_option("--depths", in.depths, "depths to tabulate: z1,z2,...")->delimiter(',')->check(kPositiveFinite);
  app->add_option("--viewer", f->viewer, "none, hmd (each eye its own display at the camera's field of view, as err-sim) or screen")
      ->check(CLI::IsMember(NamesOf(kViewerNames)))->capture_default_str();
  app->add_option("--ipd", in.ipd, "the viewer's interpupillary distance")->check(kPositiveFinite);
  app->add_option("--screen-width", in.screen_width, "screen viewer: the screen's width")->check(kPositiveFinite);
  app->add_option("--viewing-distance", in.viewing_distance, "screen viewer: the eyes' distance from the screen")->check(kPositiveFinite);
  app->add_option("--length-unit", f->unit, "mm, cm or m: the unit of the lengths given (default mm; the rig's with --rig)")
      ->check(CLI::IsMember(kUnits));
  return {app, [f, app](const Provenance& provenance) {
            app::DisplayPlanRequest r = f->request;
            if (app->count("--focal-px")) r.input.focal_px = f->focal;
            if (app->count("--hfov-deg")) r.input.hfov_rad = DegToRad(f->hfov_deg);
            if (app->count("--capture-width")) r.input.capture_width = f->capture_width;
            if (app->count("--z0")) r.input.z0 = f->z0;
            r.input.viewer = *FromName(kViewerNames, f->viewer);
            if (r.input.viewer == Viewer::kNone && app->count("--ipd")) throw InputError("--ipd: applies with --viewer hmd or screen; add --viewer");
            if (r.input.viewer != Viewer::kScreen && (app->count("--screen-width") || app->count("--viewing-distance"))) {
              throw InputError("--screen-width, --viewing-distance: apply with --viewer screen only; drop them or add --viewer screen");
            }
            if (r.input.viewer != Viewer::kNone && !app->count("--ipd")) throw InputError("--ipd: required with --viewer " + f->viewer);
            if (r.input.viewer == Viewer::kScreen && (!app->count("--screen-width") || !app->count("--viewing-distance"))) {
              throw InputError("--screen-width, --viewing-distance: both required with --viewer screen");
            }
            if (!r.rig.empty() && !f->unit.empty()) throw InputError("--length-unit: with --rig, lengths are in the rig's unit; drop --length-unit");
            if (r.rig.empty() && !app->count("--baseline")) throw InputError("--baseline: required without --rig");
            if (!f->unit.empty()) r.length_unit = *LengthUnitFromName(f->unit);
            return app::Plan(r, provenance);
          }};
}

}  // namespace vstcal::tools
