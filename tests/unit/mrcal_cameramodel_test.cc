// mrcal .cameramodel: exact round trips for every lens model, and libmrcal as the peer (its reader
// takes what we write and mrcal_project gives the same pixels; we read what its writer writes).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "support/error_of.h"
#include "support/interop_cameras.h"
#include "support/mrcal.h"
#include "support/scenes.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"

namespace vstcal {
namespace {

using testing::ErrorOf;
using testing::InteropCameras;
using testing::PointsInFront;

const Provenance kProvenance{"mrcal_cameramodel_test", {"--flag"}, std::nullopt};

std::string WriteText(const CalibratedCamera& c, const MrcalWriteOptions& options = {}) {
  return MrcalCameramodelText(c, "cam.json", options, kProvenance).text;
}

ImportedCamera ReadText(const std::string& text, std::optional<LengthUnit> unit = std::nullopt) {
  return MrcalCameramodelFromText(text, "cam.cameramodel", unit);
}

struct MrcalModelDeleter {
  void operator()(mrcal_cameramodel_t* m) const { mrcal_free_cameramodel(&m); }
};
using MrcalModel = std::unique_ptr<mrcal_cameramodel_t, MrcalModelDeleter>;

MrcalModel MrcalRead(const std::string& text) {
  return MrcalModel(mrcal_read_cameramodel_string(text.c_str(), static_cast<int>(text.size())));
}

TEST(MrcalCameramodel, RoundTripIsExactForEveryModel) {
  for (const bool with_pose : {false, true}) {
    for (const CalibratedCamera& c : InteropCameras(with_pose)) {
      const std::string name(LensModelName(c.camera.model));
      const ImportedCamera back = ReadText(WriteText(c));
      EXPECT_EQ(LensModelName(back.camera.camera.model), name);
      EXPECT_EQ(back.camera.camera.params, c.camera.params) << name;  // bit for bit, 1e-12 included
      EXPECT_EQ(back.camera.camera.image_size, c.camera.image_size);
      EXPECT_EQ(back.camera.length_unit, c.length_unit);
      EXPECT_EQ(back.camera.method, "mrcal");
      EXPECT_TRUE(back.notes.empty());
      ASSERT_EQ(back.camera.camera_from_world.has_value(), with_pose);
      if (with_pose) {
        EXPECT_EQ(back.camera.camera_from_world->t, c.camera_from_world->t);  // copied
        // Through a rotation vector and back: equal to rounding.
        EXPECT_LT((back.camera.camera_from_world->R - c.camera_from_world->R).cwiseAbs().maxCoeff(), 1e-15);
      }
    }
  }
}

// "radial-tangential" with k3 = 0 exactly is mrcal's OPENCV4; other models take their own size.
TEST(MrcalCameramodel, WritesTheShortestExactLensModel) {
  const std::vector<CalibratedCamera> cameras = InteropCameras();
  const char* expected[] = {"LENSMODEL_PINHOLE", "LENSMODEL_OPENCV5", "LENSMODEL_OPENCV4", "LENSMODEL_OPENCV8"};
  for (size_t i = 0; i < cameras.size(); ++i) {
    EXPECT_NE(WriteText(cameras[i]).find(std::string("'lensmodel': '") + expected[i] + "'"), std::string::npos) << i;
  }
}

// libmrcal's own reader takes our file: same numbers bit for bit, and mrcal_project of world
// points through its rt_cam_ref gives our pixels. This is an acceptance criterion of issue 3.
TEST(MrcalCameramodel, LibmrcalReadsWhatWeWriteAndProjectsTheSame) {
  for (const CalibratedCamera& c : InteropCameras()) {
    const std::string name(LensModelName(c.camera.model));
    const std::string text = WriteText(c);
    const MrcalModel m = MrcalRead(text);
    ASSERT_NE(m, nullptr) << "libmrcal refused:\n" << text;
    const int n = mrcal_lensmodel_num_params(&m->lensmodel);
    const Eigen::Matrix3d K = c.camera.K();
    EXPECT_EQ(m->intrinsics[0], K(0, 0));
    EXPECT_EQ(m->intrinsics[1], K(1, 1));
    EXPECT_EQ(m->intrinsics[2], K(0, 2));
    EXPECT_EQ(m->intrinsics[3], K(1, 2));
    for (int i = 4; i < n; ++i) {
      const double ours = i - 4 < static_cast<int>(c.camera.distortion().size()) ? c.camera.distortion()[i - 4] : 0.0;
      EXPECT_EQ(m->intrinsics[i], ours) << name << " coefficient " << i - 4;
    }
    EXPECT_EQ(m->imagersize[0], 1280u);
    EXPECT_EQ(m->imagersize[1], 720u);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(m->rt_cam_ref[3 + i], c.camera_from_world->t(i));

    // 0.3 to 4.3 m in front (mm), at the scale of the 3 m translation: points much nearer than
    // the world origin would measure the rounding of R x + t, not the projections.
    std::vector<Eigen::Vector3d> points_in_camera = PointsInFront(1000, 31);
    for (Eigen::Vector3d& x : points_in_camera) x *= 1000;
    std::vector<mrcal_point3_t> p(points_in_camera.size());
    std::vector<Eigen::Vector3d> points_in_world;
    for (size_t i = 0; i < p.size(); ++i) {
      points_in_world.push_back(c.camera_from_world->inverse() * points_in_camera[i]);
      mrcal_transform_point_rt(p[i].xyz, nullptr, nullptr, m->rt_cam_ref, points_in_world[i].data());
    }
    std::vector<mrcal_point2_t> q(p.size());
    ASSERT_TRUE(
        mrcal_project(q.data(), nullptr, nullptr, p.data(), static_cast<int>(p.size()), &m->lensmodel, m->intrinsics));
    double worst = 0;
    for (size_t i = 0; i < p.size(); ++i) {
      const Eigen::Vector2d ours = *c.camera.Project(*c.camera_from_world * points_in_world[i]);
      worst = std::max(worst, (ours - Eigen::Vector2d(q[i].x, q[i].y)).norm());
    }
    EXPECT_LT(worst, 1e-9) << name;
  }
}

// A camera the refinement solved with the rational model (--distortion k1,k2,p1,p2,k4 on planar
// views) is written as LENSMODEL_OPENCV8 and libmrcal projects through it what we project.
TEST(MrcalCameramodel, RefinedRationalCameraProjectsTheSameThroughLibmrcal) {
  Eigen::Matrix3d K;
  K << 600.5, 0, 643.2, 0, 599.8, 358.1, 0, 0, 1;
  const double d[8] = {-0.02, 0.01, 0.0006, -0.0003, 0, 0.16, 0, 0};
  PlanarViewsSpec spec;
  spec.num_views = 12;
  spec.noise_px = 0.2;
  const SyntheticViews data = SynthesizePlanarViews(Camera::FromK(K, ImageSize{1280, 720}, RationalModel{}, d), spec);
  CalibrationOptions options;
  options.refinement.free_distortion = {"k1", "k2", "p1", "p2", "k4"};
  const CalibrationResult r = Calibrate(data.correspondences, options);
  ASSERT_EQ(r.exit_code, ExitCode::kOk) << r.message;
  ASSERT_EQ(LensModelName(r.camera.camera.model), "rational");
  const std::string text = WriteText(r.camera);
  EXPECT_NE(text.find("'lensmodel': 'LENSMODEL_OPENCV8'"), std::string::npos);
  const MrcalModel m = MrcalRead(text);
  ASSERT_NE(m, nullptr) << text;
  std::vector<Eigen::Vector3d> points = PointsInFront(1000, 32);
  std::vector<mrcal_point3_t> p(points.size());
  for (size_t i = 0; i < p.size(); ++i) {
    for (int k = 0; k < 3; ++k) p[i].xyz[k] = points[i](k);
  }
  std::vector<mrcal_point2_t> q(p.size());
  ASSERT_TRUE(mrcal_project(q.data(), nullptr, nullptr, p.data(), static_cast<int>(p.size()), &m->lensmodel, m->intrinsics));
  double worst = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    worst = std::max(worst, (*r.camera.camera.Project(points[i]) - Eigen::Vector2d(q[i].x, q[i].y)).norm());
  }
  EXPECT_LT(worst, 1e-9);
}

// libmrcal's writer prints "%f": 1e-12 becomes 0. We read its file, and must read exactly what
// libmrcal's own reader reads from it.
TEST(MrcalCameramodel, ReadsFilesLibmrcalWrites) {
  for (const CalibratedCamera& c : InteropCameras()) {
    const MrcalModel ours = MrcalRead(WriteText(c));
    ASSERT_NE(ours, nullptr);
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("vstcal-mrcal-" + std::to_string(::getpid()) + ".cameramodel");
    ASSERT_TRUE(mrcal_write_cameramodel_file(path.c_str(), ours.get()));
    std::stringstream text;
    text << std::ifstream(path).rdbuf();
    std::filesystem::remove(path);

    const MrcalModel theirs = MrcalRead(text.str());
    ASSERT_NE(theirs, nullptr);
    const ImportedCamera in = ReadText(text.str());
    const Camera& cam = in.camera.camera;
    EXPECT_EQ(cam.params[0], theirs->intrinsics[0]);
    EXPECT_EQ(cam.params[1], theirs->intrinsics[1]);
    EXPECT_EQ(cam.params[2], theirs->intrinsics[2]);
    EXPECT_EQ(cam.params[3], theirs->intrinsics[3]);
    const int n = mrcal_lensmodel_num_params(&theirs->lensmodel);
    for (int i = 4; i < n; ++i) EXPECT_EQ(cam.distortion()[i - 4], theirs->intrinsics[i]) << i;
    // What "%f" costs: up to 5e-7 in every number.
    for (size_t i = 0; i < c.camera.params.size(); ++i) EXPECT_NEAR(cam.params[i], c.camera.params[i], 5e-7) << i;
    ASSERT_TRUE(in.camera.camera_from_world.has_value());
    for (int i = 0; i < 3; ++i) EXPECT_EQ(in.camera.camera_from_world->t(i), theirs->rt_cam_ref[3 + i]);
  }
}

TEST(MrcalCameramodel, LensModelOnRequest) {
  const CalibratedCamera rt_k3_zero = InteropCameras()[2];
  for (const char* model : {"LENSMODEL_OPENCV4", "LENSMODEL_OPENCV5", "LENSMODEL_OPENCV8"}) {
    const std::string text = WriteText(rt_k3_zero, {model, std::nullopt, std::nullopt});
    EXPECT_NE(text.find(std::string("'lensmodel': '") + model + "'"), std::string::npos);
    const Camera back = ReadText(text).camera.camera;
    // The coefficients are the same numbers, padded with zeros in a larger model.
    for (size_t i = 0; i < rt_k3_zero.camera.distortion().size(); ++i) {
      EXPECT_EQ(back.distortion()[i], rt_k3_zero.camera.distortion()[i]);
    }
  }
  const std::string e = ErrorOf([&] { WriteText(InteropCameras()[1], {"LENSMODEL_OPENCV4", std::nullopt, std::nullopt}); });
  EXPECT_NE(e.find("cam.json: distortion.k3: LENSMODEL_OPENCV4 has no k3, and this camera's is 3e-05; write "
                   "LENSMODEL_OPENCV5, which holds it"),
            std::string::npos)
      << e;
  const std::string r = ErrorOf([&] { WriteText(InteropCameras()[3], {"LENSMODEL_OPENCV5", std::nullopt, std::nullopt}); });
  EXPECT_NE(r.find("cam.json: distortion.k4: LENSMODEL_OPENCV5 has no k4"), std::string::npos) << r;
}

TEST(MrcalCameramodel, RefusesSkew) {
  CalibratedCamera c = InteropCameras()[3];
  c.camera.params[4] = -0.25;
  EXPECT_NE(ErrorOf([&] {
              WriteText(c);
            }).find("cam.json: K[0][1]: the camera has skew -0.25 px, and mrcal has no skew term"),
            std::string::npos);
}

// mrcal 2.2 has no Kannala–Brandt model (its header lists none): a fisheye is refused in one line
// that says so and names the nearest model, fitted rather than converted.
TEST(MrcalCameramodel, RefusesAFisheyeNamingTheNearestModel) {
  CalibratedCamera c = InteropCameras()[3];
  const double d[4] = {0.02, -0.004, 0.001, -0.0002};
  c.camera = Camera::FromK(c.camera.K(), c.camera.image_size, KannalaBrandtModel{}, d);
  const std::string e = ErrorOf([&] { WriteText(c); });
  EXPECT_EQ(e.rfind("cam.json: model: \"kannala-brandt\" (cv::fisheye's model) has no equivalent in mrcal 2.2, which has "
                    "no Kannala–Brandt model; calibrate the same corners with mrcal-calibrate-cameras --lensmodel "
                    "LENSMODEL_SPLINED_STEREOGRAPHIC",
                    0),
            0u)
      << e;
  EXPECT_EQ(e.find('\n'), std::string::npos);
}

// mrcal files carry no unit: the translation is written in the camera's unit unless asked
// otherwise, and the unit goes in 'vstcal_length_unit', which libmrcal skips.
TEST(MrcalCameramodel, LengthUnits) {
  CalibratedCamera c = InteropCameras()[1];
  c.length_unit = LengthUnit::kMetre;
  c.camera_from_world->t = Eigen::Vector3d(0.25, -0.5, 2.0);
  const std::string in_metres = WriteText(c);
  EXPECT_NE(in_metres.find("'vstcal_length_unit': 'm',"), std::string::npos);
  EXPECT_EQ(ReadText(in_metres).camera.length_unit, LengthUnit::kMetre);
  ASSERT_NE(MrcalRead(in_metres), nullptr);

  const std::string in_mm = WriteText(c, {std::nullopt, LengthUnit::kMillimetre, std::nullopt});
  const ImportedCamera back = ReadText(in_mm);
  EXPECT_EQ(back.camera.length_unit, LengthUnit::kMillimetre);
  EXPECT_EQ(back.camera.camera_from_world->t, Eigen::Vector3d(250, -500, 2000));
  EXPECT_EQ(MrcalRead(in_mm)->rt_cam_ref[5], 2000.0);

  // A unit given for a file that records another one is a contradiction, not a conversion.
  const std::string e = ErrorOf([&] { ReadText(in_mm, LengthUnit::kMetre); });
  EXPECT_NE(e.find("cam.cameramodel: vstcal_length_unit: the file's lengths are in mm, but m was given"),
            std::string::npos)
      << e;

  // Without the key (a file from mrcal itself) the unit is the one given, else mm with a note.
  std::string bare = in_mm;
  bare.erase(bare.find("    'vstcal_length_unit'"));
  bare += "}\n";
  EXPECT_EQ(ReadText(bare, LengthUnit::kCentimetre).camera.length_unit, LengthUnit::kCentimetre);
  const ImportedCamera assumed = ReadText(bare);
  EXPECT_EQ(assumed.camera.length_unit, LengthUnit::kMillimetre);
  ASSERT_EQ(assumed.notes.size(), 1u);
  EXPECT_NE(assumed.notes[0].find("the translation is taken to be in mm"), std::string::npos) << assumed.notes[0];
}

// A file as mrcal's Python tools write it: comments, trailing commas, keys vstcal ignores (a
// bytes literal, a list of lists, an int).
TEST(MrcalCameramodel, ReadsMrcalPythonStyle) {
  const std::string text = R"(# generated on 2026-11-21 with   mrcal-calibrate-cameras --corners-cache corners.vnl
{
    'lensmodel':  'LENSMODEL_OPENCV8',

    # intrinsics are fx,fy,cx,cy,distortion0,distortion1,....
    'intrinsics': [ 1761.181055, 1761.250444, 1965.706996, 1087.518797, -0.01266096516, 0.03590794372, -0.0002547045941, 0.0005275929652, 0.01968883397, 0.01482863541, -0.0562239888, 0.0500223357,],

    'valid_intrinsics_region': [
    [ 0, 0 ],
    [ 10.5, 20 ],
],

    # extrinsics are rt_fromref
    'extrinsics': [ 0, 0, 0, -0, -0, -0,],

    'imagersize': [ 4000, 2200,],

    'icam_intrinsics': 0,

    'optimization_inputs': b'c$Vr6Ut~l+0{',
}
)";
  const ImportedCamera in = ReadText(text);
  const Camera& cam = in.camera.camera;
  EXPECT_EQ(LensModelName(cam.model), "rational");
  EXPECT_EQ(cam.params[0], 1761.181055);
  EXPECT_EQ(cam.params[4], 0.0);  // mrcal has no skew
  EXPECT_EQ(cam.distortion()[7], 0.0500223357);
  EXPECT_EQ(cam.image_size, (ImageSize{4000, 2200}));
  EXPECT_FALSE(in.camera.camera_from_world.has_value());  // the reference camera
  ASSERT_NE(MrcalRead(text), nullptr);                    // the peer agrees it is valid
}

TEST(MrcalCameramodel, RefusesOtherLensModelsByName) {
  for (const char* model : {"LENSMODEL_CAHVOR", "LENSMODEL_OPENCV12",
                            "LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=30_Ny=18_fov_x_deg=150"}) {
    const std::string text = std::string("{'lensmodel': '") + model + "', 'intrinsics': [1, 1, 0, 0], " +
                             "'extrinsics': [0, 0, 0, 0, 0, 0], 'imagersize': [10, 10]}";
    const std::string e = ErrorOf([&] { ReadText(text); });
    EXPECT_NE(e.find(std::string("cam.cameramodel: lensmodel: '") + model + "' is not a lens model vstcal reads"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("mrcal-convert-lensmodel"), std::string::npos) << e;
  }
}

// Found by libFuzzer (tests/fuzz/corpus/cameramodel/overflowing-rotation): a rotation vector
// whose sum of squares overflows was refused with a message that printed its length, ∞, through
// the writer's number formatting, which refuses non-finite numbers: an internal error, not exit 2.
TEST(MrcalCameramodel, RefusesARotationVectorBeyondRange) {
  const std::string text =
      "{'lensmodel': 'LENSMODEL_PINHOLE', 'intrinsics': [400, 400, 320, 240], "
      "'extrinsics': [0, 3.8e179, 0, 0, 0, 1000], 'imagersize': [640, 480]}";
  EXPECT_EQ(ErrorOf([&] { ReadText(text); }),
            "cam.cameramodel: extrinsics: the rotation vector's length, its angle, is 3.8e+179 rad; give the rotation "
            "with an angle of at most 1000000.0 rad (mrcal writes it in [0, π])");
}

}  // namespace
}  // namespace vstcal
