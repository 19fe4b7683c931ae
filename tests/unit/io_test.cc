// Readers and writers: exact round trips, and the library-level checks that are not about a
// single malformed field (those are covered by tests/cli).
#include <gtest/gtest.h>

#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal {
namespace {

CalibratedCamera SampleCamera() {
  Eigen::Matrix3d K;
  K << 1234.5678901234567, -0.123456789, 640.1, 0, 1230.000000001, 359.9, 0, 0, 1;
  const double d[5] = {-0.1, 0.01, 1e-9, -2.5e-12, 3e-5};  // tiny values must survive
  CalibratedCamera c;
  c.name = "left";
  c.camera = Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, d);
  c.method = "dlt";
  c.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(10.5, -20.25, 3000.125));
  return c;
}

Provenance TestProvenance() { return Provenance{"io_test", {"--flag", "value"}, 7}; }

TEST(CameraIo, RoundTripIsExact) {
  const CalibratedCamera c = SampleCamera();
  const std::string text = DumpJson(CameraToJson(c, TestProvenance()));
  const CalibratedCamera back = CameraFromJson(JsonDocument::Parse(text, "mem.json"));
  EXPECT_EQ(back.camera.params, c.camera.params);
  EXPECT_EQ(LensModelName(back.camera.model), "radial-tangential");
  EXPECT_EQ(back.camera.image_size, c.camera.image_size);
  EXPECT_EQ(back.name, "left");
  EXPECT_EQ(back.method, "dlt");
  // R is a rotation to rounding: kept bit for bit (a SVD would move its last bits on every read).
  EXPECT_EQ(back.camera_from_world->R, c.camera_from_world->R);
  EXPECT_EQ(back.camera_from_world->t, c.camera_from_world->t);
  // Written again, the file is the same bytes, P included (kept as read, already scaled).
  EXPECT_EQ(DumpJson(CameraToJson(back, TestProvenance())), text);
}

TEST(CameraIo, WritesProvenanceAndEq5Intrinsics) {
  const OrderedJson j = CameraToJson(SampleCamera(), TestProvenance());
  EXPECT_EQ(j["format"], "vstcal/camera@1");
  EXPECT_EQ(j["provenance"]["tool"], "io_test");
  EXPECT_EQ(j["provenance"]["seed"], 7);
  EXPECT_EQ(j["provenance"]["args"][1], "value");
  EXPECT_EQ(j.items().begin().key(), "format");
  std::string last;
  for (const auto& item : j.items()) last = item.key();
  EXPECT_EQ(last, "provenance");
  const double theta = j["intrinsics"]["skew_angle_deg"];
  EXPECT_NEAR(theta, RadToDeg(std::atan2(1234.5678901234567, 0.123456789)), 1e-12);
  EXPECT_NEAR(j["P"][2][0].get<double>() * j["P"][2][0].get<double>() + j["P"][2][1].get<double>() * j["P"][2][1].get<double>() +
                  j["P"][2][2].get<double>() * j["P"][2][2].get<double>(),
              1.0, 1e-15);
}

TEST(CameraIo, RedundantFieldsMustAgreeWithK) {
  OrderedJson j = CameraToJson(SampleCamera(), TestProvenance());
  j["intrinsics"]["fu"] = 1300.0;
  try {
    CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cam.json: intrinsics: disagrees with K"), std::string::npos) << e.what();
  }
  j = CameraToJson(SampleCamera(), TestProvenance());
  j["P"][0][3] = j["P"][0][3].get<double>() * (1 + 1e-5);
  EXPECT_THROW(CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json")), InputError);
  j = CameraToJson(SampleCamera(), TestProvenance());
  j["camera_from_world"]["R"][0][0] = 2.0;
  EXPECT_THROW(CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json")), InputError);
  j = CameraToJson(SampleCamera(), TestProvenance());
  j["distortion"]["model"] = "fisheye";
  try {
    CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("\"none\", \"radial-tangential\""), std::string::npos) << e.what();
  }
}

// P's sign is free; its 3×3 block is checked at its own scale; without a pose its intrinsic part
// must still match K.
TEST(CameraIo, ProjectionMatrixChecks) {
  OrderedJson j = CameraToJson(SampleCamera(), TestProvenance());
  for (auto& row : j["P"]) {
    for (auto& v : row) v = -v.get<double>();
  }
  const CalibratedCamera negated = CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json"));
  EXPECT_GT(negated.P->leftCols<3>().determinant(), 0);
  j = CameraToJson(SampleCamera(), TestProvenance());
  j["P"][0][0] = j["P"][0][0].get<double>() + 0.5;  // 0.5 px in K R: tiny next to the translation column
  EXPECT_THROW(CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json")), InputError);
  j = CameraToJson(SampleCamera(), TestProvenance());
  j.erase("camera_from_world");
  EXPECT_NO_THROW(CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json")));
  j["K"][0][0] = 1300.0;
  j.erase("intrinsics");
  try {
    CameraFromJson(JsonDocument::Parse(j.dump(), "cam.json"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cam.json: P: its intrinsic part disagrees with K"), std::string::npos) << e.what();
  }
}

TEST(CorrespondencesIo, RoundTripIsExact) {
  VolumeSpec spec;
  spec.noise_px = 0.3;
  spec.camera_name = "right";
  Eigen::Matrix3d K;
  K << 1500, 0, 639.5, 0, 1500, 511.5, 0, 0, 1;
  const auto v = SynthesizeVolume(Camera::FromK(K, ImageSize{1280, 1024}), spec, Seed000TestPoints(spec));
  const std::string text = DumpJson(CorrespondencesToJson(v.correspondences, TestProvenance()));
  const Correspondences back = CorrespondencesFromJson(JsonDocument::Parse(text, "c.json"));
  EXPECT_EQ(back.camera, "right");
  ASSERT_EQ(back.views.size(), v.correspondences.views.size());
  for (size_t i = 0; i < back.views.size(); ++i) {
    EXPECT_EQ(back.views[i].name, v.correspondences.views[i].name);
    EXPECT_EQ(back.views[i].plane_offset, v.correspondences.views[i].plane_offset);
    ASSERT_EQ(back.views[i].observations.size(), v.correspondences.views[i].observations.size());
    for (size_t k = 0; k < back.views[i].observations.size(); ++k) {
      EXPECT_EQ(back.views[i].observations[k].point, v.correspondences.views[i].observations[k].point);
      EXPECT_EQ(back.views[i].observations[k].pixel, v.correspondences.views[i].observations[k].pixel);
    }
  }
  ASSERT_EQ(back.test_points.size(), 5u);
  EXPECT_EQ(back.test_points[3].pixel, v.correspondences.test_points[3].pixel);
  EXPECT_EQ(DumpJson(CorrespondencesToJson(back, TestProvenance())), text);
}

// Weights are a sixth number, written only when not 1, read back exactly; inches are a unit.
TEST(CorrespondencesIo, WeightsAndInchesRoundTrip) {
  VolumeSpec spec;
  spec.length_unit = LengthUnit::kInch;
  spec.spacing = 4;
  spec.far = 80;
  spec.interval = 8;
  spec.camera_distance = 80;
  Eigen::Matrix3d K;
  K << 1500, 0, 639.5, 0, 1500, 511.5, 0, 0, 1;
  Correspondences c = SynthesizeVolume(Camera::FromK(K, ImageSize{1280, 1024}), spec, {}).correspondences;
  c.views[0].observations[0].weight = 0.25;
  c.views[1].observations[3].weight = 1.0 / 3.0;
  const std::string text = DumpJson(CorrespondencesToJson(c, TestProvenance()));
  EXPECT_NE(text.find("\"length_unit\": \"in\""), std::string::npos);
  const Correspondences back = CorrespondencesFromJson(JsonDocument::Parse(text, "c.json"));
  EXPECT_EQ(back.length_unit, LengthUnit::kInch);
  EXPECT_EQ(back.views[0].observations[0].weight, 0.25);
  EXPECT_EQ(back.views[1].observations[3].weight, 1.0 / 3.0);
  EXPECT_EQ(back.views[0].observations[1].weight, 1.0);
  EXPECT_EQ(DumpJson(CorrespondencesToJson(back, TestProvenance())), text);
  EXPECT_EQ(MetresPer(LengthUnit::kInch), 0.0254);
}

// A planar-views camera's covariance, with one pose block per view, reads back as written.
TEST(CameraIo, PoseBlocksRoundTrip) {
  CalibratedCamera c = SampleCamera();
  c.camera_from_world.reset();
  c.views = {{"a", Rigid3d::FromRotvec(Eigen::Vector3d(0.1, 0, 0), Eigen::Vector3d(1, 2, 600)), 0.2},
             {"b", Rigid3d::FromRotvec(Eigen::Vector3d(0, 0.2, 0), Eigen::Vector3d(-1, 2, 700)), 0.3}};
  ParameterCovariance cov;
  cov.parameters = {"fx", "fy"};
  cov.matrix = (Eigen::Matrix2d() << 4.0, 1.0, 1.0, 3.0).finished();
  for (int v = 0; v < 2; ++v) {
    PoseCovariance p;
    p.pose = "views[" + std::to_string(v) + "].camera_from_board";
    p.matrix = Matrix6d::Identity() * (1e-6 * (v + 1));
    p.with_parameters = Matrix6Xd::Constant(6, 2, 1e-5 * (v + 1));
    cov.poses.push_back(p);
  }
  c.covariance = cov;
  const std::string text = DumpJson(CameraToJson(c, TestProvenance()));
  const CalibratedCamera back = CameraFromJson(JsonDocument::Parse(text, "mem.json"));
  ASSERT_TRUE(back.covariance.has_value());
  EXPECT_EQ(back.covariance->parameters, cov.parameters);
  EXPECT_EQ(back.covariance->matrix, cov.matrix);
  ASSERT_EQ(back.covariance->poses.size(), 2u);
  for (int v = 0; v < 2; ++v) {
    EXPECT_EQ(back.covariance->poses[v].pose, cov.poses[v].pose);
    EXPECT_EQ(back.covariance->poses[v].matrix, cov.poses[v].matrix);
    EXPECT_EQ(back.covariance->poses[v].with_parameters, cov.poses[v].with_parameters);
  }
}

}  // namespace
}  // namespace vstcal
