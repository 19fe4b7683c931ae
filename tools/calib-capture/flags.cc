#include "flags.h"

#include "common/validators.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/capture/image_times.h"

namespace vstcal::tools {

namespace {

// The poses of render and plan: a volume's template positions or planar views' board poses.
void AddPoseFlags(CLI::App* app, VolumeSpec* v, PlanarViewsSpec* p) {
  app->add_option("--near", v->near, "volume: first template offset")->check(kFinite)->capture_default_str();
  app->add_option("--far", v->far, "volume: last template offset")->check(kFinite)->capture_default_str();
  app->add_option("--interval", v->interval, "volume: step between template positions")->check(kFinite)->capture_default_str();
  app->add_option("--camera-distance", v->camera_distance, "volume: camera to the near plane")->check(kFinite)->capture_default_str();
  app->add_option("--tilt-deg", v->tilt_deg, "volume: optical axis vs template normal")->check(kFinite)->capture_default_str();
  app->add_option("--tilt-direction-deg", v->tilt_direction_deg, "volume: 0 = camera moves towards +X")->check(kFinite);
  app->add_option("--roll-deg", v->roll_deg, "volume: camera roll about its optical axis")->check(kFinite);
  app->add_option("--views", p->num_views, "planar views: number of board poses")->capture_default_str();
  app->add_option("--distance", p->distance, "planar views: typical board depth")->check(kFinite)->capture_default_str();
  app->add_option("--max-tilt-deg", p->max_tilt_deg, "planar views: largest board tilt")->check(kFinite)->capture_default_str();
}

// Refuses a flag of the other rig: AddPoseFlags' own and a subcommand's `extra` ones (first: a
// volume-only flag, second: a planar-views-only flag; "" for none).
void RefuseOtherRigFlags(CLI::App* app, bool planar, const std::pair<std::string, std::string>& extra) {
  std::vector<std::string> volume_only = {"--near", "--far", "--interval", "--camera-distance", "--tilt-deg", "--tilt-direction-deg",
                                          "--roll-deg"};
  std::vector<std::string> planar_only = {"--views", "--distance", "--max-tilt-deg"};
  if (!extra.first.empty()) volume_only.push_back(extra.first);
  if (!extra.second.empty()) planar_only.push_back(extra.second);
  for (const std::string& flag : planar ? volume_only : planar_only) {
    if (app->count(flag) > 0) throw InputError(flag + ": applies to --rig " + (planar ? "volume" : "planar-views") + " only; remove it or change --rig");
  }
}

}  // namespace

void TargetFlags::Add(CLI::App* app) {
  Target& t = request.target;
  t.dictionary = "DICT_5X5_1000";
  t.family = "tag36h11";
  app->add_option("--type", type, "chessboard, charuco, apriltag-grid or aprilgrid (Kalibr's)")
      ->check(CLI::IsMember(NamesOf(kTargetTypeNames)))
      ->capture_default_str();
  app->add_option("--kalibr", request.kalibr_file,
                  "Kalibr's target YAML (target_type aprilgrid or checkerboard): the board's type, counts and sizes (m) "
                  "instead of --type, --rows, --cols and the sizes")
      ->check(kNonEmpty);
  app->add_option("--rows", t.rows, "inner corners (tags for apriltag-grid and aprilgrid) along Y, down the sheet (required without --kalibr)");
  app->add_option("--cols", t.cols, "inner corners (tags) along X, across the sheet (required without --kalibr)");
  app->add_option("--square-size", t.square_size, "chessboard, charuco: side of a square (with --paper: default the largest that fits)")
      ->check(kPositiveFinite);
  app->add_option("--marker-size", marker_size, "charuco: side of a marker (default 0.75 × square size)")->check(kFinite);
  app->add_option("--dictionary", t.dictionary, "charuco: OpenCV ArUco dictionary")->capture_default_str();
  app->add_option("--tag-size", t.tag_size, "apriltag-grid: side of a tag's black square (with --paper: default the largest that fits)")
      ->check(kPositiveFinite);
  app->add_option("--tag-gap", tag_gap, "apriltag-grid: white between tags (default tag size / 4)")->check(kFinite);
  app->add_option("--family", t.family, "apriltag-grid: libapriltag family")->capture_default_str();
  app->add_option("--first-id", t.first_id, "apriltag-grid: id of the top-left tag; charuco: id of the first marker (OpenCV's boards: 0)")->capture_default_str();
  app->add_flag("--legacy", t.legacy,
                "charuco: OpenCV's legacy pattern, for boards drawn before OpenCV 4.6 (with an even number of square rows, i.e. odd "
                "--rows, their top-left square is white)");
  app->add_option("--tag-spacing", tag_spacing, "aprilgrid: gap between tags (and side of the black junction squares) / tag size")
      ->check(kFinite)
      ->capture_default_str();
  app->add_option("--margin", margin, "white border around the pattern (default a square, or the tag gap)")->check(kFinite);
  app->add_option("--paper", paper,
                  "a4, letter, a3 or WxH (mm): the sheet to print on; the board gets the largest square (tag) size that fits, "
                  "or a size given that does not fit is refused with the one that would");
  app->add_option("--length-unit", unit, "mm, cm, m or in")->check(kLengthUnit)->capture_default_str();
  app->add_option("--dpi", request.dpi, "resolution of the PNG (0: no PNG)")->check(kFinite)->capture_default_str();
  app->add_option("-o,--output", request.output, "writes OUTPUT.target.json, OUTPUT.svg, OUTPUT.png")->required()->check(kNonEmpty);
}

app::TargetRequest TargetFlags::Finish() {
  Target& t = request.target;
  t.type = *TargetTypeFromName(type);
  t.length_unit = *LengthUnitFromName(unit);
  if (!request.kalibr_file.empty()) {
    for (const auto& [flag, given] : {std::pair<const char*, bool>{"--type", type != "chessboard"}, {"--rows", t.rows != 0},
                                      {"--cols", t.cols != 0}, {"--square-size", t.square_size != 0}, {"--tag-size", t.tag_size != 0},
                                      {"--tag-spacing", tag_spacing != kKalibrDefaultSpacing}, {"--length-unit", unit != "mm"},
                                      {"--legacy", t.legacy}}) {
      if (given) throw InputError(std::string(flag) + ": the board comes from --kalibr " + request.kalibr_file + "; remove " + flag);
    }
    request.given.margin = margin;
    if (!paper.empty()) request.paper = PaperFromName(paper);
    if (!paper.empty() && !request.paper) throw InputError("--paper: \"" + paper + "\" is not a paper size; give a4, letter, a3 or WxH in mm (e.g. 250x350)");
    return request;
  }
  for (const auto& [flag, n] : {std::pair<const char*, int>{"--rows", t.rows}, {"--cols", t.cols}}) {
    if (n == 0) throw InputError(std::string(flag) + ": required (or give --kalibr with Kalibr's target YAML)");
  }
  const bool tags = t.type == TargetType::kAprilTagGrid || t.type == TargetType::kAprilGrid;
  if (tags && t.square_size != 0) throw InputError("--square-size: an " + type + " has tags, not squares; give --tag-size");
  if (!tags && t.tag_size != 0) throw InputError("--tag-size: applies to --type apriltag-grid or aprilgrid; give --square-size");
  if (t.type == TargetType::kAprilGrid) t.tag_spacing = tag_spacing;
  if (t.type == TargetType::kChessboard && t.first_id != 0) throw InputError("--first-id: a chessboard has no ids; remove it");
  if (!paper.empty()) {
    request.paper = PaperFromName(paper);
    if (!request.paper) throw InputError("--paper: \"" + paper + "\" is not a paper size; give a4, letter, a3 or WxH in mm (e.g. 250x350)");
  }
  const double size = tags ? t.tag_size : t.square_size;
  if (!(size > 0) && !request.paper) {
    throw InputError(tags ? "--tag-size: required for --type " + type + " (side of a tag's black square), or give --paper to fit the largest"
                          : "--square-size: required for --type " + type + " (side of a square), or give --paper to fit the largest");
  }
  request.given = {margin, tag_gap, marker_size};
  if (size > 0) t = WithSize(t, size, request.given);
  return request;
}

void DetectFlags::Add(CLI::App* app) {
  app::DetectCommand& c = command;
  app->add_option("TARGET", c.target_file, "the board's vstcal/target@1 file")->required()->check(kNonEmpty);
  app->add_option("IMAGES", c.images, "image files, folders (their images, sorted) or quoted globs");
  app->add_option("--manifest", c.manifest, "volume: vstcal/volume-manifest@1 file: each image with its plane_offset")->check(kNonEmpty);
  app->add_option("--offset-from-name", c.offset_pattern, "volume: regex whose first group in each file name is the plane offset, e.g. 'z(-?[0-9.]+)'")
      ->check(kNonEmpty);
  app->add_option("--video", c.video.file, "a video file instead of images (planar views)")->check(kNonEmpty);
  app->add_option("--camera-index", c.video.camera_index, "a live camera (0: the first) instead of images; needs --frames");
  app->add_option("--times", c.times_file,
                  "images: a text file of each image's file name and the time it was taken (for calib-handeye)")
      ->check(kNonEmpty);
  app->add_option("--times-unit", c.times_unit, "the --times file's unit")
      ->check(CLI::IsMember(NamesOf(kTimeUnitNames)))
      ->capture_default_str();
  app->add_option("--every", c.video.every, "video/camera: keep every k-th frame")->check(kPositiveCount)->capture_default_str();
  app->add_option("--frames", c.video.max_frames, "video/camera: frames to keep (0: the whole video)")->check(kCount);
  app->add_option("--finder", finder, "chessboard: classic, sector-based or classic+sector-based (the second where the first fails)")
      ->check(CLI::IsMember(NamesOf(kChessboardFinderNames)))
      ->capture_default_str();
  app->add_option("--refine", refiner, "symmetry (vstcal), cornersubpix (OpenCV) or none")
      ->check(CLI::IsMember(NamesOf(kCornerRefinerNames)))
      ->capture_default_str();
  app->add_option("--min-corners", c.detect.detector.min_corners, "a view with fewer corners is rejected")->capture_default_str();
  app->add_option("--max-blur-px", c.detect.detector.max_blur_px, "a view whose edges are blurrier (σ, px) is rejected")
      ->check(kPositiveFinite)
      ->capture_default_str();
  app->add_option("--min-views", c.detect.min_views, "fewer usable images is an error (exit code 3)")->capture_default_str();
  app->add_flag("--skip-unreadable", c.detect.skip_unreadable, "list unreadable images as rejected instead of stopping");
  app->add_option("--threads", c.detect.threads, "threads (0: all cores; the output does not depend on it)");
  app->add_option("--camera-name", c.detect.camera_name, "the output's \"camera\" field, e.g. left");
  app->add_option("--overlay", c.overlay_folder, "write each image with its corners drawn into this folder")->check(kNonEmpty);
  app->add_option("-o,--output", c.output, "vstcal/correspondences@1 file to write")->required()->check(kNonEmpty);
  app->add_flag("-q,--quiet", quiet, "print only errors");
}

app::DetectCommand DetectFlags::Finish() {
  DetectorOptions& d = command.detect.detector;
  d.finder = *FromName(kChessboardFinderNames, finder);
  d.refiner = *FromName(kCornerRefinerNames, refiner);
  if (d.min_corners < 4) throw InputError("--min-corners: must be at least 4 (a homography needs 4 points)");
  if (command.detect.min_views < 1) throw InputError("--min-views: must be at least 1");
  return command;
}

void RenderFlags::Add(CLI::App* app) {
  app::RenderCommand& c = command;
  SceneSpec& s = c.scene;
  app->add_option("TARGET", c.target_file, "the vstcal/target@1 file to draw")->required()->check(kNonEmpty);
  app->add_option("--camera", c.camera_file, "vstcal/camera@1 file: image size, K and distortion (its pose is not used)")
      ->required()
      ->check(kNonEmpty);
  app->add_option("-o,--output", c.output_folder, "folder to write the images, truth.json, camera.truth.json, manifest.json")
      ->required()
      ->check(kNonEmpty);
  app->add_option("--rig", rig, "volume (the template moved along its normal) or planar-views (the board held at poses)")
      ->check(CLI::IsMember({"volume", "planar-views"}))
      ->capture_default_str();
  AddPoseFlags(app, &s.volume, &s.views);
  app->add_option("--blur-px", s.render.blur_px, "Gaussian blur σ, px")->check(kFinite)->capture_default_str();
  app->add_option("--noise", s.render.noise, "Gaussian noise σ, grey levels")->check(kFinite)->capture_default_str();
  app->add_option("--lighting", s.render.lighting, "uneven lighting: the far side is (1 − L) as bright, 0 ≤ L < 1")->check(kFinite);
  app->add_option("--seed", s.render.seed, "noise (and planar-view pose) seed")->check(kSeed)->capture_default_str();
  app->add_option("--threads", s.threads, "threads (0: all cores; the images do not depend on it)");
}

app::RenderCommand RenderFlags::Finish(CLI::App* app) {
  SceneSpec& s = command.scene;
  s.rig = rig == "volume" ? Rig::kVolume : Rig::kPlanarViews;
  const bool planar = s.rig == Rig::kPlanarViews;
  RefuseOtherRigFlags(app, planar, {});
  s.views.seed = s.render.seed;
  if (!(s.render.blur_px >= 0 && s.render.blur_px <= 50)) throw InputError("--blur-px: must lie in [0, 50] px");
  if (!(s.render.noise >= 0 && s.render.noise <= 255)) throw InputError("--noise: must lie in [0, 255] grey levels");
  if (!(s.render.lighting >= 0 && s.render.lighting < 1)) throw InputError("--lighting: must lie in [0, 1)");
  return command;
}

void PlanFlags::Add(CLI::App* app) {
  app::PlanCommand& c = command;
  PlanRequest& r = c.request;
  CLI::Option* target = app->add_option("TARGET", c.target_file, "the board's vstcal/target@1 file")->check(kNonEmpty);
  app->add_option("--compare", c.compare, "PLAN_A PLAN_B: put two vstcal/capture-plan@1 files side by side instead of planning")
      ->expected(2)
      ->check(kNonEmpty)
      ->excludes(target);
  CLI::Option* camera = app->add_option("--camera", c.camera_file, "vstcal/camera@1 file: image size, K, distortion")->check(kNonEmpty);
  for (CLI::Option* o : {app->add_option("--image-size", image_size, "nominal camera: WxH in px, e.g. 1280x720")->check(kNonEmpty),
                         app->add_option("--fx", c.nominal.fx, "nominal camera: focal length, px")->check(kFinite),
                         app->add_option("--hfov-deg", c.nominal.hfov_deg, "nominal camera: horizontal field of view")->check(kFinite),
                         app->add_option("--focal-mm", c.focal_mm, "nominal camera: focal length, mm (with --pixel-pitch-um)")->check(kFinite),
                         app->add_option("--pixel-pitch-um", c.pixel_pitch_um, "nominal camera: pixel size, µm")->check(kFinite)}) {
    o->excludes(camera);
  }
  app->add_option("--rig", rig, "volume (the template moved along its normal) or planar-views (the board held at poses)")
      ->check(CLI::IsMember({"volume", "planar-views"}))
      ->capture_default_str();
  AddPoseFlags(app, &r.volume, &r.views);
  app->add_option("--seed", r.views.seed, "planar views: pose pattern seed")->check(kSeed)->capture_default_str();
  app->add_option("--pixel-sigma", r.pixel_sigma, "corner noise σ the prediction assumes, px")->check(kPositiveFinite)->capture_default_str();
  app->add_option("--method", r.method, "the solve to predict: dlt or tsai (one plane: tsai holds fx/fy and the principal point)")
      ->check(CLI::IsMember({"dlt", "tsai"}))
      ->capture_default_str();
  app->add_option("--distortion", calibration.distortion, "distortion terms the solve estimates (k1,k2,p1,p2,k3,k4,k5,k6) or none")
      ->capture_default_str();
  app->add_flag("--skew", calibration.skew, "the solve also estimates the skew s");
  app->add_option("--test-point", test_points, "volume: world point X,Y,Z to predict the projection uncertainty at (repeatable; "
                                                "default seed 000's five)")
      ->delimiter(',')
      ->check(kFinite)
      ->type_name("X,Y,Z");
  app->add_option("--uncertainty-pixel", pixel_points, "pixel U,V at depth D to predict the uncertainty at (repeatable)")
      ->delimiter(',')
      ->check(kFinite)
      ->type_name("U,V,DEPTH");
  app->add_option("--depth-of-field", depth_of_field, "NEAR,FAR: depths (along the optical axis) in focus; warns outside")
      ->delimiter(',')
      ->check(kFinite)
      ->type_name("NEAR,FAR");
  app->add_option("--format", format, "json (vstcal/capture-plan@1) or text")->check(CLI::IsMember({"json", "text"}))->capture_default_str();
  app->add_option("-o,--output", c.output, "file to write")->required()->check(kNonEmpty);
}

namespace {

std::vector<double> Expect(const std::vector<std::vector<double>>& lists, size_t i, size_t n, const std::string& flag,
                           const std::string& form) {
  if (lists[i].size() != n) {
    throw InputError(flag + ": expected " + std::to_string(n) + " numbers " + form + ", got " + std::to_string(lists[i].size()) +
                     "; give each as its own " + flag);
  }
  return lists[i];
}

}  // namespace

app::PlanCommand PlanFlags::Finish(CLI::App* app) {
  PlanRequest& r = command.request;
  command.text = format == "text";
  if (!command.compare.empty()) {
    for (const CLI::Option* o : app->get_options()) {
      const std::string name = o->get_name();
      if (o->count() > 0 && name != "--compare" && name != "--format" && name != "--output" && name != "--help") {
        throw InputError(name + ": --compare reads its two plans as they are; remove " + name);
      }
    }
    return command;
  }
  if (command.target_file.empty()) throw InputError("TARGET: give the board's vstcal/target@1 file (or --compare PLAN_A PLAN_B)");
  r.rig = rig == "volume" ? Rig::kVolume : Rig::kPlanarViews;
  const bool planar = r.rig == Rig::kPlanarViews;
  RefuseOtherRigFlags(app, planar, {"--test-point", "--seed"});
  if (command.camera_file.empty()) {
    if (image_size.empty()) throw InputError("--image-size: required without --camera (e.g. --image-size 1280x720)");
    const auto [w, h] = ParseSize(image_size, "--image-size", "WxH (e.g. 1280x720)", limits::kMaxImageSide);
    command.nominal.image_size = ImageSize{w, h};
  }
  r.options = calibration.Refinement();
  command.default_test_points = test_points.empty();
  for (size_t i = 0; i < test_points.size(); ++i) {
    const std::vector<double> p = Expect(test_points, i, 3, "--test-point", "X,Y,Z");
    r.test_points.push_back({"point " + std::to_string(i), Eigen::Vector3d(p[0], p[1], p[2]), std::nullopt});
  }
  for (size_t i = 0; i < pixel_points.size(); ++i) {
    const std::vector<double> p = Expect(pixel_points, i, 3, "--uncertainty-pixel", "U,V,DEPTH");
    r.pixel_points.emplace_back(p[0], p[1], p[2]);
  }
  if (!depth_of_field.empty()) {
    if (depth_of_field.size() > 1) throw InputError("--depth-of-field: give it once, as NEAR,FAR");
    const std::vector<double> d = Expect(depth_of_field, 0, 2, "--depth-of-field", "NEAR,FAR");
    r.sharp_near = d[0];
    r.sharp_far = d[1];
  }
  return command;
}

}  // namespace vstcal::tools
