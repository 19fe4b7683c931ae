// CLI tests of calib-capture: the printable target and its description; render → detect →
// calib-dlt and calib-tsai recovering the rendered camera within the uncertainty they report;
// video input (a small MJPG AVI written here by OpenCV); determinism over thread counts; and every
// bad input of the issue — a target that does not match the board, a video that cannot be opened,
// a manifest naming missing images or positions, duplicate images, empty and truncated PNG/JPEG
// files, images of different sizes, too few usable images — with exit code 2 (3 for too few
// usable images), one line naming the file and the fix, and no output left behind.
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <fstream>
#include <map>

#include "calibration_checks.h"
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-capture";

class CliCalibCapture : public CliTest {
 public:  // the bad-input cases below prepare their files through these
  using CliTest::Path;
  using CliTest::ReadJson;
  using CliTest::ReadText;
  using CliTest::WriteJson;
  using CliTest::WriteText;
  using CliTest::Synth;

  // Runs calib-capture; fails the test unless it succeeds.
  void Ok(const std::vector<std::string>& args) const {
    const CommandResult r = Run(kTool, args);
    ASSERT_EQ(r.exit_code, kOk) << r.err;
  }
  // in/board.target.json: a 9×6 chessboard of 40 mm squares.
  void Board(std::vector<std::string> extra = {}) const {
    std::vector<std::string> args = {"target", "--rows", "6", "--cols", "9", "--square-size", "40", "--dpi", "0", "-o", "in/board"};
    args.insert(args.end(), extra.begin(), extra.end());
    Ok(args);
  }
  // in/camera.truth.json: calib-synth's distorted 640×480 camera (fx 600, k1 −0.15, k2 0.05).
  void Camera() const { Synth("in/camera.json", DistortedVolumeArgs()); }
  // Renders in/board.target.json as a volume (5 planes, 100 mm apart) into `folder`.
  void RenderVolume(const std::string& folder, std::vector<std::string> extra = {}) const {
    std::vector<std::string> args = {"render", "in/board.target.json", "--camera", "in/camera.truth.json", "-o", folder, "--near", "0",
                                     "--far", "400", "--interval", "100", "--camera-distance", "700", "--tilt-deg", "15",
                                     "--blur-px", "0.8", "--noise", "2"};
    args.insert(args.end(), extra.begin(), extra.end());
    Ok(args);
  }
  void RenderViews(const std::string& folder, const std::string& target = "in/board.target.json", int views = 5) const {
    Ok({"render", target, "--camera", "in/camera.truth.json", "-o", folder, "--rig", "planar-views", "--views", std::to_string(views),
        "--distance", "900", "--blur-px", "0.8", "--noise", "2"});
  }
  void Copy(const std::string& from, const std::string& to) const { fs::copy_file(Path(from), Path(to), fs::copy_options::overwrite_existing); }
};

TEST_F(CliCalibCapture, TargetWritesTheDescriptionAndThePrintableFiles) {
  Ok({"target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "100", "-o", "out/board"});
  EXPECT_EQ(List("out"), (std::vector<std::string>{"board.png", "board.svg", "board.target.json"}));
  const Json t = ReadJson("out/board.target.json");
  EXPECT_EQ(t.at("format"), "vstcal/target@1");
  EXPECT_EQ(t.at("type"), "chessboard");
  EXPECT_EQ(t.at("square_size"), 25.0);
  EXPECT_EQ(t.at("margin"), 25.0);
  EXPECT_EQ(t.at("sheet").at("width"), 300.0);
  EXPECT_NE(ReadText("out/board.svg").find("width=\"300mm\" height=\"225mm\""), std::string::npos);
  const cv::Mat png = cv::imread(Path("out/board.png").string(), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(png.cols, 1182);  // ⌈300 mm / 0.254 mm⌉
  // ChArUco and AprilTag grids, without the PNG.
  Ok({"target", "--type", "charuco", "--rows", "5", "--cols", "7", "--square-size", "30", "--dpi", "0", "-o", "out/ch"});
  EXPECT_EQ(ReadJson("out/ch.target.json").at("marker_size"), 22.5);
  EXPECT_FALSE(ReadJson("out/ch.target.json").contains("legacy"));
  // OpenCV's legacy pattern (boards drawn before 4.6): an even number of square rows, the top-left square white.
  Ok({"target", "--type", "charuco", "--rows", "5", "--cols", "7", "--square-size", "30", "--legacy", "--dpi", "0", "-o", "out/legacy"});
  EXPECT_EQ(ReadJson("out/legacy.target.json").at("legacy"), true);
  EXPECT_NE(ReadJson("out/legacy.target.json").at("board_frame").get<std::string>().find("the top-left square is white"), std::string::npos);
  Ok({"target", "--type", "apriltag-grid", "--rows", "4", "--cols", "6", "--tag-size", "30", "--dpi", "0", "-o", "out/ag"});
  EXPECT_EQ(ReadJson("out/ag.target.json").at("tag_gap"), 7.5);
  EXPECT_FALSE(fs::exists(Path("out/ch.png")));
}

// Kalibr's target YAML (its wiki's april_6x6.yaml, scaled down) becomes an aprilgrid target in
// metres with Kalibr's layout; the board drawn, rendered through a camera and detected: every tag
// of every view with its Kalibr corner id, within 0.1 px of the rendered truth.
TEST_F(CliCalibCapture, KalibrsAprilgridIsReadDrawnAndDetected) {
  WriteText("in/april.yaml",
            "target_type: 'aprilgrid' #gridtype\ntagCols: 6\ntagRows: 4\ntagSize: 0.03\ntagSpacing: 0.3 #ratio of space between tags to tagSize\n");
  Ok({"target", "--kalibr", "in/april.yaml", "--dpi", "100", "-o", "in/kalibr"});
  const Json t = ReadJson("in/kalibr.target.json");
  EXPECT_EQ(t.at("type"), "aprilgrid");
  EXPECT_EQ(t.at("length_unit"), "m");
  EXPECT_EQ(t.at("rows"), 4);
  EXPECT_EQ(t.at("cols"), 6);
  EXPECT_EQ(t.at("tag_size"), 0.03);
  EXPECT_EQ(t.at("tag_spacing"), 0.3);
  EXPECT_FALSE(t.contains("family"));
  EXPECT_NEAR(t.at("margin").get<double>(), 0.009, 1e-15);  // the gap
  // The same board from flags.
  Ok({"target", "--type", "aprilgrid", "--rows", "4", "--cols", "6", "--tag-size", "0.03", "--length-unit", "m", "--dpi", "0",
      "-o", "out/flags"});
  Json a = ReadJson("out/flags.target.json"), b = t;
  a.erase("provenance");
  b.erase("provenance");
  EXPECT_EQ(a, b);
  Camera();
  Ok({"render", "in/kalibr.target.json", "--camera", "in/camera.truth.json", "-o", "in/views", "--rig", "planar-views", "--views", "4",
      "--distance", "0.45", "--blur-px", "0.8", "--noise", "2"});
  Ok({"detect", "in/kalibr.target.json", "in/views", "-o", "out/corners.json"});
  const Json corners = ReadJson("out/corners.json"), truth = ReadJson("in/views/truth.json");
  EXPECT_EQ(corners.at("capture").at("counts").at("found"), 4);
  ASSERT_EQ(corners.at("views").size(), 4u);
  // OpenCV's aruco (markerBorderBits 2), which vstcal starts from, decodes some of these 40 px tags
  // only (docs/experiments/corners.md#aprilgrid). Of the tags it decodes, a corner whose contour ran
  // on into the junction square (put one gap off) is dropped, not renumbered: at least 80 % of their
  // corners are kept (86–99 % here), and none is numbered or placed wrongly.
  cv::Ptr<cv::aruco::DetectorParameters> parameters = cv::aruco::DetectorParameters::create();
  parameters->markerBorderBits = 2;
  const cv::Ptr<cv::aruco::Dictionary> tags = cv::aruco::getPredefinedDictionary(cv::aruco::DICT_APRILTAG_36h11);
  for (size_t v = 0; v < 4; ++v) {
    std::map<std::vector<double>, std::pair<double, double>> by_point;
    for (const Json& p : truth["views"][v]["points"]) by_point[{p[0].get<double>(), p[1].get<double>()}] = {p[3], p[4]};
    std::vector<std::vector<cv::Point2f>> marker_corners;
    std::vector<int> ids;
    cv::aruco::detectMarkers(cv::imread(Path("in/views/view-0" + std::to_string(v) + ".png").string(), cv::IMREAD_GRAYSCALE), tags, marker_corners,
                             ids, parameters);
    EXPECT_GE(5 * corners["views"][v]["points"].size(), 4 * 4 * ids.size()) << v;
    for (const Json& p : corners["views"][v]["points"]) {
      const auto it = by_point.find({p[0].get<double>(), p[1].get<double>()});
      ASSERT_NE(it, by_point.end());
      EXPECT_LT(std::hypot(p[3].get<double>() - it->second.first, p[4].get<double>() - it->second.second), 0.1);
    }
  }
  // Read as vstcal's apriltag-grid, the images say what the board is.
  Ok({"target", "--type", "apriltag-grid", "--rows", "4", "--cols", "6", "--tag-size", "0.03", "--length-unit", "m", "--dpi", "0",
      "-o", "in/grid"});
  const CommandResult r = Run(kTool, {"detect", "in/grid.target.json", "in/views", "-o", "out/wrong.json"});
  EXPECT_TRUE(FailsWith(r, kTool, kBadInput, "in/grid.target.json: ", {"Kalibr's aprilgrid", "set the target's type to aprilgrid"}));
}

// The main job end to end: a volume rendered through a distorted camera, detected, and solved by
// calib-dlt --refine and by calib-tsai: every lens parameter within 5σ of the truth, σ from the
// covariance each tool writes (calibration_checks.h says why 5).
TEST_F(CliCalibCapture, RenderDetectCalibrateRecoversTheCamera) {
  Camera();
  Board();
  RenderVolume("in/volume");
  EXPECT_EQ(List("in/volume"), (std::vector<std::string>{"camera.truth.json", "manifest.json", "plane-00.png", "plane-01.png",
                                                         "plane-02.png", "plane-03.png", "plane-04.png", "truth.json"}));
  Ok({"detect", "in/board.target.json", "--manifest", "in/volume/manifest.json", "-o", "out/corners.json"});
  const Json corners = ReadJson("out/corners.json"), truth = ReadJson("in/volume/truth.json");
  EXPECT_EQ(corners.at("rig"), "volume");
  EXPECT_EQ(corners.at("capture").at("counts"), Json({{"images", 5}, {"found", 5}, {"not_found", 0}, {"rejected", 0}}));
  ASSERT_EQ(corners.at("views").size(), 5u);
  for (size_t v = 0; v < 5; ++v) {
    EXPECT_EQ(corners["views"][v]["name"], truth["views"][v]["name"]);
    EXPECT_EQ(corners["views"][v]["image"], "in/volume/" + truth["views"][v]["image"].get<std::string>());
    EXPECT_EQ(corners["views"][v]["plane_offset"], truth["views"][v]["plane_offset"]);
    ASSERT_EQ(corners["views"][v]["points"].size(), truth["views"][v]["points"].size());
    for (size_t k = 0; k < truth["views"][v]["points"].size(); ++k) {
      const Json& a = corners["views"][v]["points"][k];
      const Json& b = truth["views"][v]["points"][k];
      for (int i = 0; i < 3; ++i) EXPECT_EQ(a[i], b[i]);
      EXPECT_LT(std::hypot(a[3].get<double>() - b[3].get<double>(), a[4].get<double>() - b[4].get<double>()), 0.1);
    }
  }
  const std::vector<std::string> terms = {"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"};
  const Json camera_truth = ReadJson("in/volume/camera.truth.json");
  ASSERT_EQ(Run("calib-dlt", {"out/corners.json", "-o", "out/dlt.json", "--refine", "-q"}).exit_code, kOk);
  EXPECT_TRUE(WithinSigmas(ReadJson("out/dlt.json"), camera_truth, terms, 5));
  ASSERT_EQ(Run("calib-tsai", {"out/corners.json", "-o", "out/tsai.json", "-q"}).exit_code, kOk);
  EXPECT_TRUE(WithinSigmas(ReadJson("out/tsai.json"), camera_truth, terms, 5));
  EXPECT_LT(RotationDifferenceDeg(ReadJson("out/tsai.json").at("camera_from_world"), camera_truth.at("camera_from_world")), 0.05);
}

// Planar views from a folder, from a glob and from a list give the same views; the output does
// not depend on the thread count (only the provenance, which records the arguments, differs).
TEST_F(CliCalibCapture, PlanarViewsAreDeterministicWhateverTheThreads) {
  Camera();
  Board();
  RenderViews("in/views");
  Ok({"detect", "in/board.target.json", "in/views", "--threads", "1", "-o", "out/one.json"});
  Ok({"detect", "in/board.target.json", "in/views/view-*.png", "--threads", "2", "-o", "out/two.json"});
  Json one = ReadJson("out/one.json"), two = ReadJson("out/two.json");
  EXPECT_EQ(one.at("rig"), "planar-views");
  EXPECT_EQ(one.at("views").size(), 5u);
  one.erase("provenance");
  two.erase("provenance");
  EXPECT_EQ(one.dump(), two.dump());
  // Not a terminal: the summary and nothing else on stderr (no progress bar).
  const CommandResult r = Run(kTool, {"detect", "in/board.target.json", "in/views/view-00.png", "in/views/view-01.png",
                                      "in/views/view-02.png", "-o", "out/three.json"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err, "calib-capture: 3 images: 3 found, 0 not found, 0 rejected; 162 corners in 3 views (rig planar-views); wrote "
                   "out/three.json\n");
}

// Inputs are never overwritten (docs/reliability.md#inputs): an output naming an image or the
// target description read by this run is refused with exit code 2, and the file keeps its bytes.
// One command from images (issue 24): calib-tsai, under its other name calib-camera, given the
// board and the images solves exactly what detect then calib-tsai solve — the same camera file and
// the same corners file but for the provenance, which records the arguments — and writes them with
// the overlays and the report page; the summary accounts for every image.
TEST_F(CliCalibCapture, OneCommandFromImagesSolvesWhatTheSeparateStepsSolve) {
  Camera();
  Board();
  RenderViews("in/views");
  Ok({"detect", "in/board.target.json", "in/views", "-o", "out/corners.json"});
  ASSERT_EQ(Run("calib-tsai", {"out/corners.json", "-o", "out/steps.json", "-q"}).exit_code, kOk);
  const CommandResult r = Run("calib-camera", {"--target", "in/board.target.json", "in/views", "-o", "out/one.json", "--corners",
                                               "out/one.corners.json", "--html", "out/one.html", "--overlay", "out/overlays"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err.rfind("calib-camera: 5 images: 5 found, 0 not found, 0 rejected; ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("wrote out/one.html"), std::string::npos) << r.err;
  Json steps = ReadJson("out/steps.json"), one = ReadJson("out/one.json");
  EXPECT_EQ(one.at("provenance").at("tool"), "calib-camera");
  steps.erase("provenance");
  one.erase("provenance");
  EXPECT_EQ(one.dump(), steps.dump());
  Json corners = ReadJson("out/corners.json"), one_corners = ReadJson("out/one.corners.json");
  corners.erase("provenance");
  one_corners.erase("provenance");
  EXPECT_EQ(one_corners.dump(), corners.dump());
  EXPECT_EQ(List("out/overlays").size(), 5u);
  // The page is reproj-report's for this camera and these corners: one residual figure per view.
  ASSERT_EQ(Run("reproj-report", {"out/one.json", "out/one.corners.json", "-o", "out/report.json", "--html", "out/report.html"}).exit_code, kOk);
  const std::string page = ReadText("out/one.html"), reference = ReadText("out/report.html");
  EXPECT_NE(page.find("<html"), std::string::npos);
  for (const char* view : {"view-00", "view-04"}) {
    EXPECT_NE(page.find(view), std::string::npos) << view;
    EXPECT_NE(reference.find(view), std::string::npos) << view;
  }
  // Without --corners the corners stay in memory: the same camera, and only the camera written.
  ASSERT_EQ(Run("calib-tsai", {"--target", "in/board.target.json", "in/views", "-o", "out/mem.json", "-q"}).exit_code, kOk);
  Json mem = ReadJson("out/mem.json");
  mem.erase("provenance");
  EXPECT_EQ(mem.dump(), steps.dump());
}

// The same for a volume: calib-dlt --target with the render's manifest equals detect --manifest then calib-dlt.
TEST_F(CliCalibCapture, OneCommandFromAVolumesImages) {
  Camera();
  Board();
  RenderVolume("in/volume");
  Ok({"detect", "in/board.target.json", "--manifest", "in/volume/manifest.json", "-o", "out/corners.json"});
  ASSERT_EQ(Run("calib-dlt", {"out/corners.json", "-o", "out/steps.json", "--refine", "-q"}).exit_code, kOk);
  const CommandResult r =
      Run("calib-dlt", {"--target", "in/board.target.json", "--manifest", "in/volume/manifest.json", "-o", "out/one.json", "--refine"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_EQ(r.err.rfind("calib-dlt: 5 images: 5 found, 0 not found, 0 rejected; ", 0), 0u) << r.err;
  Json steps = ReadJson("out/steps.json"), one = ReadJson("out/one.json");
  steps.erase("provenance");
  one.erase("provenance");
  EXPECT_EQ(one.dump(), steps.dump());
}

// The input's rules: the image flags need --target, one correspondences file without it, planar
// images are no volume for DLT; a solve that fails writes no corners file either (all or nothing).
TEST_F(CliCalibCapture, OneCommandFromImagesRefusesWhatDoesNotFit) {
  Camera();
  Board();
  RenderViews("in/views");
  Ok({"detect", "in/board.target.json", "in/views", "-o", "in/corners.json"});
  EXPECT_TRUE(FailsWith(Run("calib-tsai", {"in/corners.json", "in/corners.json", "-o", "out/c.json"}), "calib-tsai", kBadInput, "",
                        {"2 inputs: give one correspondences file, or --target"}));
  EXPECT_TRUE(FailsWith(Run("calib-tsai", {"in/corners.json", "--corners", "out/k.json", "-o", "out/c.json"}), "calib-tsai", kBadInput,
                        "--corners: ", {"applies to images", "--target"}));
  EXPECT_TRUE(FailsWith(Run("calib-tsai", {"-o", "out/c.json"}), "calib-tsai", kBadInput, "INPUT: ", {"--target"}));
  EXPECT_TRUE(FailsWith(Run("calib-dlt", {"--target", "in/board.target.json", "in/views", "-o", "out/c.json", "--corners", "out/k.json"}),
                        "calib-dlt", kBadInput, "the corners found in the images: rig: ", {"give the images' plane offsets with --manifest"}));
  EXPECT_TRUE(FailsWith(Run("calib-camera", {"--target", "in/board.target.json", "in/views/view-00.png", "-o", "out/c.json", "--corners",
                                             "out/k.json"}),
                        "calib-camera", kDegenerate, "too few usable images: 1 image: 1 found", {"--min-views"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibCapture, OutputsNeverReplaceTheImagesOrTheTarget) {
  Camera();
  Board();
  RenderViews("in/views", "in/board.target.json", 3);
  const std::string image = ReadText("in/views/view-01.png"), target = ReadText("in/board.target.json");
  for (const std::string& victim : {std::string("in/views/view-01.png"), std::string("./in/board.target.json")}) {
    const CommandResult r = Run(kTool, {"detect", "in/board.target.json", "in/views", "--min-views", "2", "-o", victim});
    EXPECT_TRUE(FailsWith(r, kTool, kBadInput, victim + ": ", {"is an input of this run"})) << victim;
  }
  EXPECT_EQ(ReadText("in/views/view-01.png"), image);
  EXPECT_EQ(ReadText("in/board.target.json"), target);
  EXPECT_TRUE(OutDirEmpty());
}

// A board in inches, as docs/conventions.md allows every length unit (issue 24: refused): 1 in
// squares and margin: 12 × 9 in of sheet (10 × 7 squares and the margin around them).
TEST_F(CliCalibCapture, TargetInInches) {
  Ok({"target", "--rows", "6", "--cols", "9", "--square-size", "1", "--length-unit", "in", "--dpi", "0", "-o", "out/b"});
  const Json target = ReadJson("out/b.target.json");
  EXPECT_EQ(target.at("length_unit"), "in");
  EXPECT_NE(ReadText("out/b.svg").find("width=\"304.8mm\""), std::string::npos) << ReadText("out/b.svg").substr(0, 400);
}

// Overlays are named <view>.overlay.png: written beside the images they are drawn on, they replace
// none, and a later run over the folder or a glob leaves them out and says so (issue 24: they were
// taken for new views, each pose counted twice); one named on its own is refused.
TEST_F(CliCalibCapture, OverlaysAreNotTakenForViewsOnTheNextRun) {
  Camera();
  Board();
  RenderViews("in/views", "in/board.target.json", 3);
  const std::string image = ReadText("in/views/view-01.png");
  Ok({"detect", "in/board.target.json", "in/views", "--min-views", "2", "--overlay", "in/views", "-o", "out/first.json"});
  EXPECT_EQ(ReadText("in/views/view-01.png"), image);
  EXPECT_EQ(List("in/views"), (std::vector<std::string>{"camera.truth.json", "truth.json", "view-00.overlay.png", "view-00.png",
                                                       "view-01.overlay.png", "view-01.png", "view-02.overlay.png", "view-02.png"}));
  for (const std::string& images : {std::string("in/views"), std::string("in/views/*.png")}) {
    const CommandResult r = Run(kTool, {"detect", "in/board.target.json", images, "--min-views", "2", "-o", "out/again.json"});
    ASSERT_EQ(r.exit_code, kOk) << r.err;
    EXPECT_NE(r.err.find("3 images: 3 found"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("left out 3 overlays (*.overlay.png) of an earlier --overlay"), std::string::npos) << r.err;
    Json first = ReadJson("out/first.json"), again = ReadJson("out/again.json");
    first.erase("provenance");
    again.erase("provenance");
    EXPECT_EQ(first.dump(), again.dump()) << images;
  }
  EXPECT_TRUE(FailsWith(Run(kTool, {"detect", "in/board.target.json", "in/views/view-00.overlay.png", "-o", "out/c.json"}), kTool,
                        kBadInput, "in/views/view-00.overlay.png: is an overlay", {"give the image it was drawn on"}));
}

// A volume from file names: --offset-from-name reads each template position from its image's name.
TEST_F(CliCalibCapture, OffsetsFromFileNames) {
  Camera();
  Board();
  RenderVolume("in/volume");
  for (int k = 0; k < 5; ++k) Copy("in/volume/plane-0" + std::to_string(k) + ".png", "in/z" + std::to_string(100 * k) + "mm.png");
  Ok({"detect", "in/board.target.json", "in/z0mm.png", "in/z100mm.png", "in/z200mm.png", "in/z300mm.png", "in/z400mm.png",
      "--offset-from-name", "z([0-9.]+)mm", "-o", "out/corners.json"});
  const Json corners = ReadJson("out/corners.json");
  EXPECT_EQ(corners.at("rig"), "volume");
  EXPECT_EQ(corners["views"][2]["name"], "z200mm");
  EXPECT_EQ(corners["views"][2]["plane_offset"], 200.0);
  EXPECT_EQ(corners["views"][2]["points"][0][2], 200.0);
}

// Video: every k-th frame of a file OpenCV reads (an MJPG AVI written here from rendered views).
TEST_F(CliCalibCapture, VideoEveryKthFrame) {
  Camera();
  Board();
  RenderViews("in/views", "in/board.target.json", 6);
  cv::VideoWriter writer(Path("in/video.avi").string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(640, 480), false);
  ASSERT_TRUE(writer.isOpened());
  for (int k = 0; k < 6; ++k) writer.write(cv::imread(Path("in/views/view-0" + std::to_string(k) + ".png").string(), cv::IMREAD_GRAYSCALE));
  writer.release();
  Ok({"detect", "in/board.target.json", "--video", "in/video.avi", "--every", "2", "--min-views", "2", "-o", "out/corners.json"});
  const Json corners = ReadJson("out/corners.json");
  ASSERT_EQ(corners.at("capture").at("images").size(), 3u);
  EXPECT_EQ(corners["capture"]["images"][1]["image"], "in/video.avi#2");
  EXPECT_EQ(corners["views"][0]["name"], "frame-000000");
  EXPECT_EQ(corners["views"][1]["image"], "in/video.avi#2");
  // Each frame's time on the video's clock (10 frames a second): what calib-handeye pairs with the tracker.
  EXPECT_NEAR(corners["views"][0]["time"].get<double>(), 0.0, 1e-9);
  EXPECT_NEAR(corners["views"][1]["time"].get<double>(), 0.2, 1e-9);
  EXPECT_NEAR(corners["views"][2]["time"].get<double>(), 0.4, 1e-9);
}

// Issue 22: --times gives image files their times (EuRoC's order and nanoseconds here: "time,name"),
// what calib-handeye pairs with the tracker; the views keep them in the order found.
TEST_F(CliCalibCapture, ImageTimesFromAFile) {
  Camera();
  Board();
  RenderViews("in/views");
  std::string times = "#timestamp [ns],filename\n";
  for (int k = 0; k < 5; ++k) times += std::to_string(1403636579000000000LL + 50000000LL * k) + ",view-0" + std::to_string(k) + ".png\n";
  WriteText("in/times.csv", times);
  Ok({"detect", "in/board.target.json", "in/views", "--times", "in/times.csv", "--times-unit", "ns", "-o", "out/corners.json"});
  const Json views = ReadJson("out/corners.json").at("views");
  ASSERT_EQ(views.size(), 5u);
  for (size_t k = 0; k < views.size(); ++k) {
    EXPECT_EQ(views[k]["image"], "in/views/view-0" + std::to_string(k) + ".png");
    // 1.403636579e9 s: a double keeps it to 0.24 µs.
    EXPECT_NEAR(views[k]["time"].get<double>(), 1403636579.0 + 0.05 * static_cast<double>(k), 1e-6);
  }
}

// --skip-unreadable lists a broken image as rejected, with its reason, and goes on.
TEST_F(CliCalibCapture, SkipUnreadableListsTheImageAsRejected) {
  Camera();
  Board();
  RenderViews("in/views");
  WriteText("in/views/broken.png", ReadText("in/views/view-00.png").substr(0, 500));
  Ok({"detect", "in/board.target.json", "in/views", "--skip-unreadable", "-o", "out/corners.json"});
  const Json images = ReadJson("out/corners.json").at("capture").at("images");
  ASSERT_EQ(images.size(), 6u);
  EXPECT_EQ(images[0]["image"], "in/views/broken.png");
  EXPECT_EQ(images[0]["status"], "rejected");
  EXPECT_EQ(images[0]["reason"], "unreadable: truncated PNG (it does not end with the IEND chunk)");
}

// Issue 24: the docs' 6 × 9 board of 25 mm squares (300 × 225 mm) fits neither A4 nor Letter: a
// warning names A3; with --paper a4 the board gets 23.3 mm squares (landscape, paper_test's
// arithmetic); a board larger than A3 is named with its size.
TEST_F(CliCalibCapture, TargetFitsThePaperOrWarns) {
  CommandResult r = Run(kTool, {"target", "--rows", "6", "--cols", "9", "--square-size", "25", "--dpi", "0", "-o", "out/big"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("calib-capture: warning: the 300 × 225 mm sheet fits neither A4 nor Letter; it needs A3 (297 × 420 mm)"),
            std::string::npos)
      << r.err;
  r = Run(kTool, {"target", "--rows", "6", "--cols", "9", "--paper", "a4", "--dpi", "0", "-o", "out/a4"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("23.3 mm squares on a 279.6 × 209.7 mm sheet (fits A4 (210 × 297 mm) landscape)"), std::string::npos) << r.err;
  EXPECT_EQ(ReadJson("out/a4.target.json").at("square_size"), 23.3);
  EXPECT_EQ(ReadJson("out/a4.target.json").at("margin"), 23.3);
  r = Run(kTool, {"target", "--rows", "6", "--cols", "9", "--square-size", "20", "--dpi", "0", "-o", "out/small"});
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;  // 240 × 180 mm fits A4 landscape
  r = Run(kTool, {"target", "--rows", "6", "--cols", "9", "--square-size", "40", "--dpi", "0", "-o", "out/huge"});
  EXPECT_NE(r.err.find("it needs a sheet larger than A3: 480 × 360 mm"), std::string::npos) << r.err;
}

// The largest distance of a row of a 9 × 6 board's corners from its total-least-squares line, over
// every row, as OpenCV (the peer) finds the corners in `image`; -1 when it does not find the board.
double WorstRowBend(const cv::Mat& image) {
  std::vector<cv::Point2f> corners;
  if (!cv::findChessboardCorners(image, cv::Size(9, 6), corners, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE)) return -1;
  cv::cornerSubPix(image, corners, cv::Size(5, 5), cv::Size(-1, -1), cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 50, 1e-4));
  double worst = 0;
  for (int row = 0; row < 6; ++row) {
    const std::vector<cv::Point2f> line_points(corners.begin() + 9 * row, corners.begin() + 9 * row + 9);
    cv::Vec4f line;
    cv::fitLine(line_points, line, cv::DIST_L2, 0, 1e-6, 1e-6);
    for (const cv::Point2f& p : line_points) {
      worst = std::max(worst, std::abs(static_cast<double>(-line[1] * (p.x - line[2]) + line[0] * (p.y - line[3]))));
    }
  }
  return worst;
}

// Issue 24 item 4: calib-tsai --undistort writes each view's image undistorted through the solved
// camera. On noise-free renders through calib-synth's distorted camera (k1 −0.15, k2 0.05), each
// row of corners OpenCV finds in a written image lies within 0.1 px of a straight line, where the
// rendered image's rows bend by more than 0.5 px.
TEST_F(CliCalibCapture, UndistortedImagesHaveStraightRows) {
  Camera();
  Board();
  Ok({"render", "in/board.target.json", "--camera", "in/camera.truth.json", "-o", "in/views", "--rig", "planar-views", "--views", "6",
      "--distance", "900", "--blur-px", "0.8", "--noise", "0"});
  Ok({"detect", "in/board.target.json", "in/views", "-q", "-o", "in/corners.json"});
  const Json views = ReadJson("in/corners.json")["views"];
  ASSERT_GE(views.size(), 5u);
  const CommandResult r = Run("calib-tsai", {"in/corners.json", "-o", "out/cam.json", "--undistort", "out/und"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(r.err.find("wrote " + std::to_string(views.size()) + " undistorted images (<view>.undistorted.png) in out/und"),
            std::string::npos)
      << r.err;
  double bent = 0, straight = 0;
  for (const Json& v : views) {
    const std::string name = v["name"];
    const cv::Mat rendered = cv::imread(Path(v["image"]).string(), cv::IMREAD_GRAYSCALE);
    const cv::Mat undistorted = cv::imread(Path("out/und/" + name + ".undistorted.png").string(), cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(undistorted.empty()) << name;
    EXPECT_EQ(undistorted.size(), rendered.size());
    const double before = WorstRowBend(rendered), after = WorstRowBend(undistorted);
    ASSERT_GE(before, 0) << name;
    ASSERT_GE(after, 0) << name;
    bent = std::max(bent, before);
    straight = std::max(straight, after);
  }
  EXPECT_GT(bent, 0.5) << straight;  // 0.81 px at 900 mm
  EXPECT_LT(straight, 0.1) << bent;
  // Without images to undistort: refused, nothing written.
  Json corners = ReadJson("in/corners.json");
  for (Json& v : corners["views"]) v.erase("image");
  WriteJson("in/no-images.json", corners);
  EXPECT_TRUE(FailsWith(Run("calib-tsai", {"in/no-images.json", "-o", "out/c2.json", "--undistort", "out/und2"}), "calib-tsai", kBadInput,
                        "--undistort: in/no-images.json names no image", {"leave out --undistort"}));
  EXPECT_FALSE(fs::exists(Path("out/c2.json")));
}

// ---- bad input: exit code 2 (3 for too few usable images), one line, nothing written ----

struct BadCase {
  std::string name;
  std::function<void(CliCalibCapture*)> prepare;
  std::vector<std::string> args;
  int exit_code;
  std::string location;
  std::vector<std::string> phrases;
};
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

class CliCalibCaptureBad : public CliCalibCapture, public ::testing::WithParamInterface<BadCase> {};

// The common preparation: the camera, the 9×6 board and five planar views of it in in/views.
void Views(CliCalibCapture* t) {
  t->Camera();
  t->Board();
  t->RenderViews("in/views");
}

std::vector<BadCase> BadCases() {
  using T = CliCalibCapture;
  const auto views = Views;
  return {
      {"TargetTooFewRows", [](CliCalibCapture*) {}, {"target", "--rows", "1", "--cols", "9", "--square-size", "25", "-o", "out/b"}, kBadInput,
       "--rows: ", {"must be 2 to 1000 inner corners"}},
      {"TargetCharucoMarkerTooLarge", [](CliCalibCapture*) {},
       {"target", "--type", "charuco", "--rows", "5", "--cols", "7", "--square-size", "30", "--marker-size", "30", "-o", "out/b"}, kBadInput,
       "--marker-size: ", {"fills a square of 30", "give a marker_size < square_size"}},
      {"TargetChessboardWithFirstId", [](CliCalibCapture*) {},
       {"target", "--rows", "6", "--cols", "9", "--square-size", "25", "--first-id", "3", "-o", "out/b"}, kBadInput, "--first-id: ",
       {"a chessboard has no ids; remove it"}},
      {"TargetChessboardWithLegacy", [](CliCalibCapture*) {},
       {"target", "--rows", "5", "--cols", "7", "--square-size", "25", "--legacy", "-o", "out/b"}, kBadInput, "--legacy: ",
       {"only a ChArUco board has OpenCV's legacy pattern, not a chessboard; remove it"}},
      {"TargetGridWithSquareSize", [](CliCalibCapture*) {},
       {"target", "--type", "apriltag-grid", "--rows", "4", "--cols", "6", "--square-size", "30", "-o", "out/b"}, kBadInput,
       "--square-size: ", {"give --tag-size"}},
      // Issue 24: "--square-size: required" for a size given, but negative.
      {"TargetNegativeSquareSize", [](CliCalibCapture*) {}, {"target", "--rows", "6", "--cols", "9", "--square-size", "-1", "-o", "out/b"},
       kBadInput, "--square-size", {"expected a positive number, got \"-1\""}},
      // Issue 24: a square_size of 1e308 was an internal error (a sheet of infinite width), and with a
      // margin given, "a margin problem".
      {"TargetSquareSizeTooLarge", [](CliCalibCapture*) {},
       {"target", "--rows", "6", "--cols", "9", "--square-size", "1e308", "--margin", "25", "-o", "out/b"}, kBadInput, "--square-size: ",
       {"1e+308 makes a board beyond 1e308 mm wide, more than the 1e+09 mm vstcal computes with"}},
      // Issue 24: the image size of the camera file was refused without naming the file.
      {"RenderImagesTooLarge",
       [](CliCalibCapture* t) {
         t->Camera();
         t->Board();
         Json camera = static_cast<T*>(t)->ReadJson("in/camera.truth.json");
         camera["image_size"] = {20000, 20000};
         static_cast<T*>(t)->WriteJson("in/big.json", camera);
       },
       {"render", "in/board.target.json", "--camera", "in/big.json", "-o", "out/r"}, kBadInput, "in/big.json: image_size: ",
       {"more than 100 megapixels"}},
      // Issue 24: --paper with a size that does not fit: refused with the size that does.
      {"TargetDoesNotFitThePaper", [](CliCalibCapture*) {},
       {"target", "--rows", "6", "--cols", "9", "--square-size", "25", "--paper", "a4", "-o", "out/b"}, kBadInput, "--square-size: ",
       {"25 mm squares make a 300 × 225 mm sheet, larger than A4 (210 × 297 mm) either way",
        "at most 23.3 mm fits (landscape): give --square-size 23.3, or leave it out to fit the paper"}},
      {"TargetTagsDoNotFitTheLetter", [](CliCalibCapture*) {},
       {"target", "--type", "apriltag-grid", "--rows", "6", "--cols", "6", "--tag-size", "30", "--paper", "letter", "-o", "out/b"},
       kBadInput, "--tag-size: ", {"give --tag-size 27.8"}},
      {"KalibrCircleGrid", [](CliCalibCapture* t) { static_cast<T*>(t)->WriteText("in/c.yaml", "target_type: 'circlegrid'\ntargetCols: 6\n"); },
       {"target", "--kalibr", "in/c.yaml", "-o", "out/b"}, kBadInput, "in/c.yaml: target_type: ", {"vstcal has no circle grid"}},
      {"KalibrMissingSpacing",
       [](CliCalibCapture* t) { static_cast<T*>(t)->WriteText("in/a.yaml", "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\n"); },
       {"target", "--kalibr", "in/a.yaml", "-o", "out/b"}, kBadInput, "in/a.yaml: tagSpacing: ", {"add tagSpacing"}},
      {"KalibrWithRows",
       [](CliCalibCapture* t) {
         static_cast<T*>(t)->WriteText("in/a.yaml", "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.3\n");
       },
       {"target", "--kalibr", "in/a.yaml", "--rows", "5", "-o", "out/b"}, kBadInput, "--rows: ", {"the board comes from --kalibr"}},
      {"AprilgridSpacingTooSmall", [](CliCalibCapture*) {},
       {"target", "--type", "aprilgrid", "--rows", "6", "--cols", "6", "--tag-size", "30", "--tag-spacing", "0.02", "-o", "out/b"},
       kBadInput, "--tag-spacing: ", {"from 0.1 to 1 (Kalibr's tagSpacing)"}},
      {"TargetUnknownPaper", [](CliCalibCapture*) {}, {"target", "--rows", "6", "--cols", "9", "--paper", "a5", "-o", "out/b"}, kBadInput,
       "--paper: ", {"\"a5\" is not a paper size; give a4, letter, a3 or WxH in mm"}},
      {"TargetMarginFillsThePaper", [](CliCalibCapture*) {},
       {"target", "--rows", "6", "--cols", "9", "--margin", "60", "--paper", "100x100", "-o", "out/b"}, kBadInput, "--paper: ",
       {"leave no room for the board on 100 × 100 mm"}},
      {"TargetOutputFolderMissing", [](CliCalibCapture*) {},
       {"target", "--rows", "6", "--cols", "9", "--square-size", "20", "-o", "out/no/b"}, kBadInput, "out/no/b.target.json: ",
       {"cannot write: directory out/no does not exist; create it first"}},
      // One rule for every tool's output files (issue 24: detect created the folder): refused.
      {"DetectOutputFolderMissing", views, {"detect", "in/board.target.json", "in/views", "-o", "out/no/c.json"}, kBadInput,
       "out/no/c.json: ", {"cannot write: directory out/no does not exist; create it first"}},
      {"OverlayFolderParentMissing", views,
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json", "--overlay", "out/no/deeper"}, kBadInput,
       "out/no/deeper: ", {"cannot create: folder out/no does not exist; create it first"}},
      {"TargetFileMissing", views, {"detect", "in/missing.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/missing.json: ",
       {"no such file"}},
      {"TargetFileIsACamera", views, {"detect", "in/camera.truth.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/camera.truth.json: ",
       {"this is a \"vstcal/camera@1\" file, expected \"vstcal/target@1\""}},
      {"TargetWrongType",
       [](CliCalibCapture* t) {
         Views(t);
         Json target = static_cast<T*>(t)->ReadJson("in/board.target.json");
         target["type"] = "charuco";  // the board is a chessboard
         static_cast<T*>(t)->WriteJson("in/wrong.target.json", target);
       },
       {"detect", "in/wrong.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/wrong.target.json: ", {"marker_size: missing field"}},
      {"TargetDoesNotMatchTheBoard",
       [](CliCalibCapture* t) {
         Views(t);
         static_cast<T*>(t)->Ok({"target", "--rows", "6", "--cols", "8", "--square-size", "40", "--dpi", "0", "-o", "in/eight"});
       },
       {"detect", "in/eight.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/eight.target.json: ",
       {"no image shows the chessboard of 8×6 inner corners", "5 images: 0 found, 5 not found", "check the target file's type, rows and cols"}},
      {"CharucoRowsAndColsSwapped",
       [](CliCalibCapture* t) {
         static_cast<T*>(t)->Camera();
         static_cast<T*>(t)->Ok({"target", "--type", "charuco", "--rows", "5", "--cols", "7", "--square-size", "50", "--dpi", "0", "-o", "in/ch"});
         static_cast<T*>(t)->Ok({"target", "--type", "charuco", "--rows", "7", "--cols", "5", "--square-size", "50", "--dpi", "0", "-o", "in/swapped"});
         static_cast<T*>(t)->RenderViews("in/views", "in/ch.target.json");
       },
       {"detect", "in/swapped.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/swapped.target.json: ",
       {"no image shows the ChArUco board of 5×7", "5 rejected (5 layout mismatch)"}},
      // Issue 24: FFmpeg's own "moov atom not found" came before the one error line. An MP4 of
      // its ftyp box alone: no moov atom.
      {"VideoWithoutMoovAtom",
       [](CliCalibCapture* t) {
         Views(t);
         static_cast<T*>(t)->WriteText("in/video.mp4", std::string("\0\0\0\x18" "ftypisom\0\0\x02\0" "isomiso2", 24));
       },
       {"detect", "in/board.target.json", "--video", "in/video.mp4", "-o", "out/c.json"}, kBadInput, "in/video.mp4: ",
       {"cannot open as a video"}},
      // Issue 24: a sharp board rejected as blurred was advised to "check rows and cols".
      {"OnlyImageRejectedAsBlurred", views, {"detect", "in/board.target.json", "in/views/view-00.png", "--max-blur-px", "0.01", "-o", "out/c.json"},
       kBadInput, "in/board.target.json: no usable image of the chessboard",
       {"1 rejected (1 blurred)", "the board was found and rejected (in/views/view-00.png: blurred: ", "take sharper images"}},
      {"VideoCannotBeOpened", [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/video.avi", "not a video\n"); },
       {"detect", "in/board.target.json", "--video", "in/video.avi", "-o", "out/c.json"}, kBadInput, "in/video.avi: ",
       {"cannot open as a video", "MJPG AVI"}},
      {"VideoMissing", views, {"detect", "in/board.target.json", "--video", "in/none.avi", "-o", "out/c.json"}, kBadInput, "in/none.avi: ",
       {"no such file"}},
      {"OverlayWithVideo", views, {"detect", "in/board.target.json", "--video", "in/v.avi", "--overlay", "out/o", "-o", "out/c.json"}, kBadInput,
       "--overlay: ", {"does not apply to --video"}},
      {"ManifestNamesAMissingImage",
       [](CliCalibCapture* t) {
         static_cast<T*>(t)->Camera();
         static_cast<T*>(t)->Board();
         static_cast<T*>(t)->RenderVolume("in/volume");
         fs::remove(static_cast<T*>(t)->Path("in/volume/plane-03.png"));
       },
       {"detect", "in/board.target.json", "--manifest", "in/volume/manifest.json", "-o", "out/c.json"}, kBadInput,
       "in/volume/manifest.json: images[3].image: ", {"in/volume/plane-03.png: no such image file", "remove the entry"}},
      {"ManifestWithoutAPosition",
       [](CliCalibCapture* t) {
         Views(t);
         static_cast<T*>(t)->WriteText("in/views/m.json", R"({"format": "vstcal/volume-manifest@1", "length_unit": "mm", "images": [)"
                                                          R"({"image": "view-00.png", "plane_offset": 0}, {"image": "view-01.png"}]})");
       },
       {"detect", "in/board.target.json", "--manifest", "in/views/m.json", "-o", "out/c.json"}, kBadInput, "in/views/m.json: images[1].plane_offset: ",
       {"missing field"}},
      {"ManifestListsAnImageTwice",
       [](CliCalibCapture* t) {
         Views(t);
         static_cast<T*>(t)->WriteText("in/views/m.json", R"({"format": "vstcal/volume-manifest@1", "length_unit": "mm", "images": [)"
                                                          R"({"image": "view-00.png", "plane_offset": 0}, {"image": "./view-00.png", "plane_offset": 100}]})");
       },
       {"detect", "in/board.target.json", "--manifest", "in/views/m.json", "-o", "out/c.json"}, kBadInput, "in/views/m.json: images[1].image: ",
       {"listed twice"}},
      {"ImageListedTwice", views, {"detect", "in/board.target.json", "in/views/view-00.png", "in/views/view-00.png", "-o", "out/c.json"},
       kBadInput, "in/views/view-00.png: ", {"listed twice", "list each image once"}},
      {"DuplicateImageContent", [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->Copy("in/views/view-01.png", "in/views/view-09.png"); },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/view-09.png: ",
       {"the same image as in/views/view-01.png", "remove the copy"}},
      {"ZeroBytePng", [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/views/empty.png", ""); },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/empty.png: ",
       {"the file is empty (0 bytes)", "--skip-unreadable"}},
      {"TruncatedPng",
       [](CliCalibCapture* t) {
         Views(t);
         static_cast<T*>(t)->WriteText("in/views/cut.png", static_cast<T*>(t)->ReadText("in/views/view-00.png").substr(0, 2000));
       },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/cut.png: ",
       {"truncated PNG (it does not end with the IEND chunk)", "copy the image again"}},
      {"TruncatedJpeg",
       [](CliCalibCapture* t) {
         Views(t);
         std::vector<uint8_t> jpeg;
         cv::imencode(".jpg", cv::imread(static_cast<T*>(t)->Path("in/views/view-00.png").string()), jpeg);
         static_cast<T*>(t)->WriteText("in/views/cut.jpg", std::string(jpeg.begin(), jpeg.begin() + jpeg.size() / 2));
       },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/cut.jpg: ", {"truncated JPEG"}},
      {"ZeroByteJpeg", [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/views/empty.jpg", ""); },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/empty.jpg: ", {"the file is empty"}},
      {"NotAnImage", [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/views/notes.png", "hello\n"); },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/notes.png: ", {"not an image OpenCV can decode"}},
      {"ImagesOfDifferentSizes",
       [](CliCalibCapture* t) {
         Views(t);
         cv::Mat small;
         cv::imwrite(static_cast<T*>(t)->Path("in/views/view-09.png").string(), cv::Mat(240, 320, CV_8U, cv::Scalar(128)));
       },
       {"detect", "in/board.target.json", "in/views", "-o", "out/c.json"}, kBadInput, "in/views/view-09.png: ",
       {"320×240 pixels, but in/views/view-00.png has 640×480"}},
      {"TooFewUsableImages", views, {"detect", "in/board.target.json", "in/views/view-00.png", "in/views/view-01.png", "-o", "out/c.json"},
       kDegenerate, "", {"too few usable images: 2 images: 2 found", "at least 3 (--min-views)"}},
      {"VolumeAtOnePosition", views,
       {"detect", "in/board.target.json", "in/views", "--offset-from-name", "(0)", "-o", "out/c.json"}, kDegenerate, "",
       {"at plane_offset 0", "at least two template positions"}},
      {"OffsetPatternDoesNotMatch", views,
       {"detect", "in/board.target.json", "in/views", "--offset-from-name", "z([0-9]+)", "-o", "out/c.json"}, kBadInput, "--offset-from-name: ",
       {"\"view-00.png\" does not match \"z([0-9]+)\""}},
      {"TimesFileMissesAnImage",
       [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/times.txt", "view-00.png 0.1\nview-01.png 0.2\n"); },
       {"detect", "in/board.target.json", "in/views", "--times", "in/times.txt", "-o", "out/c.json"}, kBadInput, "in/times.txt: ",
       {"no line for the image \"view-02.png\"", "give every image its time"}},
      {"TimesFileNamesNoImage",
       [](CliCalibCapture* t) { Views(t), static_cast<T*>(t)->WriteText("in/times.txt", "# camera clock\nview-00.png 0.1\nvew-01.png 0.2\n"); },
       {"detect", "in/board.target.json", "in/views", "--times", "in/times.txt", "-o", "out/c.json"}, kBadInput, "in/times.txt: line 3: ",
       {"\"vew-01.png\" nor \"0.2\" is the file name of an image given"}},
      {"TimesWithAVideo", views,
       {"detect", "in/board.target.json", "--video", "in/views/view-00.png", "--times", "in/times.txt", "-o", "out/c.json"}, kBadInput,
       "--times: ", {"a video's frames have theirs"}},
      {"NoImages", views, {"detect", "in/board.target.json", "-o", "out/c.json"}, kBadInput, "", {"no images: give"}},
      {"GlobMatchesNothing", views, {"detect", "in/board.target.json", "in/views/*.tif", "-o", "out/c.json"}, kBadInput, "in/views/*.tif: ",
       {"no file matches"}},
      {"OutputIsAnInput", views, {"detect", "in/board.target.json", "in/views", "-o", "in/board.target.json"}, kBadInput,
       "in/board.target.json: ", {"is an input of this run"}},
      {"RenderFlagOfTheOtherRig", views,
       {"render", "in/board.target.json", "--camera", "in/camera.truth.json", "-o", "out/r", "--rig", "planar-views", "--near", "10"}, kBadInput,
       "--near: ", {"applies to --rig volume only"}},
      {"RenderLightingOutOfRange", views,
       {"render", "in/board.target.json", "--camera", "in/camera.truth.json", "-o", "out/r", "--lighting", "1"}, kBadInput, "--lighting: ",
       {"[0, 1)"}},
      {"RenderTooManyMegapixels",
       [](CliCalibCapture* t) {
         t->Board();
         t->Synth("in/big.json", Override(DefaultSynthArgs(), "--image-size", "4000x3000"));
       },
       {"render", "in/board.target.json", "--camera", "in/big.truth.json", "-o", "out/r", "--rig", "planar-views", "--views", "100"},
       kBadInput, "--views: ", {"100 images of 4000×3000 are 1200 megapixels in all, more than 1000"}},
      {"RenderTooManyPlanes", views,
       {"render", "in/board.target.json", "--camera", "in/camera.truth.json", "-o", "out/r", "--interval", "0.1"}, kBadInput, "--interval: ",
       {"more than 1000 template positions"}},
  };
}

TEST_P(CliCalibCaptureBad, FailsCleanly) {
  const BadCase& c = GetParam();
  c.prepare(this);
  if (HasFatalFailure()) return;
  const CommandResult r = Run(kTool, c.args);
  EXPECT_TRUE(FailsWith(r, kTool, c.exit_code, c.location, c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Cases, CliCalibCaptureBad, ::testing::ValuesIn(BadCases()),
                         [](const ::testing::TestParamInfo<BadCase>& case_info) { return case_info.param.name; });

}  // namespace
}  // namespace vstcal::cli_test

namespace vstcal::cli_test {
namespace {

using CliCodecsPlugin = CliTest;

// OpenCV's codecs are a plugin loaded on first use (image/codecs.h, docs/conventions.md#image-codecs):
// the PNG of a target is encoded through it, and a plugin that does not load is one line naming it
// and VSTCAL_CODECS_PLUGIN, exit 1 (an installation fault), with nothing written.
TEST_F(CliCodecsPlugin, PngThroughThePluginAndOneLineWhenItIsMissing) {
  const std::vector<std::string> args = {"target", "--rows", "5", "--cols", "7", "--square-size", "30", "--dpi", "40", "-o", "out/board"};
  const CommandResult ok = Run("calib-capture", args);
  ASSERT_EQ(ok.exit_code, kOk) << ok.err;
  const std::string png = ReadText("out/board.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  fs::remove_all(Path("out"));
  fs::create_directories(Path("out"));

  ::setenv("VSTCAL_CODECS_PLUGIN", "/nonexistent/libvstcal_codecs.so", 1);
  const CommandResult missing = Run("calib-capture", args);
  ::unsetenv("VSTCAL_CODECS_PLUGIN");
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  EXPECT_NE(missing.err.find("/nonexistent/libvstcal_codecs.so"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("VSTCAL_CODECS_PLUGIN"), std::string::npos) << missing.err;
  // Not a bug of vstcal's: the line says how to fix it, and does not ask for a report.
  EXPECT_EQ(missing.err.rfind("calib-capture: error: the image codecs plugin", 0), 0u) << missing.err;
  EXPECT_EQ(missing.err.find("please report"), std::string::npos) << missing.err;
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
