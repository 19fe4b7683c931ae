// Round trips are fixed points (docs/reliability.md#round-trips): a file read and written again,
// then read and written once more, gives the same bytes on the second pass, for camera@1 (with
// views and covariance), OpenCV YAML and mrcal .cameramodel, over many poses, every lens model,
// P at any scale and sign, and rotations written with few digits.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "support/interop_cameras.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/camera/opencv_yaml.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

const Provenance kRoundTripProvenance{"round_trip_test", {"--flag"}, std::nullopt};

// Camera k of a deterministic family: every lens model, a rotation anywhere on SO(3) (angles up
// to π), translations from 1e-3 to 1e4.
CalibratedCamera FamilyCamera(int k) {
  const CounterRng rng(2024, static_cast<uint32_t>(k));
  const auto a = rng.Uniform2(0, 0), b = rng.Uniform2(0, 1), c = rng.Uniform2(0, 2);
  CalibratedCamera cam = testing::InteropCameras(true)[static_cast<size_t>(k) % 4];
  const Eigen::Vector3d axis = Eigen::Vector3d(a[0] - 0.5, a[1] - 0.5, b[0] - 0.5).normalized();
  const double scale = std::pow(10.0, -3 + 7 * c[0]);
  cam.camera_from_world = Rigid3d::FromRotvec(axis * kPi * b[1], scale * Eigen::Vector3d(c[1] - 0.5, 0.3, 1.0));
  return cam;
}

std::string CameraText(const CalibratedCamera& c) { return DumpJson(CameraToJson(c, kRoundTripProvenance)); }
std::string CameraPass(const std::string& text) {
  return CameraText(CameraFromJson(JsonDocument::Parse(text, "cam.json")));
}

TEST(RoundTrip, CameraFileIsAFixedPointAfterOnePass) {
  for (int k = 0; k < 200; ++k) {
    CalibratedCamera c = FamilyCamera(k);
    // A DLT's own P, at an arbitrary scale and sign (read back scaled to a unit third row).
    if (k % 3 == 0) c.P = ProjectionMatrix(c.camera.K(), *c.camera_from_world) * (k % 2 ? -37.25 : 1e-3);
    // R written with 9 digits, as a hand-made file may have it (re-orthonormalized on read).
    if (k % 5 == 0) c.camera_from_world->R = (c.camera_from_world->R * 1e9).array().round() / 1e9;
    const std::string first = CameraPass(CameraText(c));
    EXPECT_EQ(CameraPass(first), first) << "camera " << k;
  }
}

TEST(RoundTrip, CameraFileWrittenByAToolIsReadAndWrittenIdentically) {
  // A camera as a tool writes it: R from a rotation vector, P = K[R|t] scaled (never re-read).
  for (int k = 0; k < 200; ++k) {
    const std::string text = CameraText(FamilyCamera(k));
    EXPECT_EQ(CameraPass(text), text) << "camera " << k;
  }
}

TEST(RoundTrip, PlanarViewsCameraWithCovariance) {
  CalibratedCamera c = FamilyCamera(1);
  c.camera_from_world.reset();
  for (int v = 0; v < 5; ++v) c.views.push_back({"view-" + std::to_string(v), FamilyCamera(10 + v).camera_from_world.value(), 0.1 * v});
  ParameterCovariance cov;
  cov.parameters = {"fx", "k1", "views[4].camera_from_board.tz"};
  cov.matrix = Eigen::Matrix3d{{0.25, 1e-3, -0.1}, {1e-3, 1e-5, 0}, {-0.1, 0, 4.0}};
  c.covariance = cov;
  const std::string first = CameraPass(CameraText(c));
  EXPECT_EQ(CameraPass(first), first);
}

TEST(RoundTrip, MrcalFileIsAFixedPointAfterOnePass) {
  auto pass = [](const std::string& text) {
    const ImportedCamera in = MrcalCameramodelFromText(text, "cam.cameramodel", std::nullopt);
    return MrcalCameramodelText(in.camera, "cam.cameramodel", {std::nullopt, std::nullopt, in.rotation_vector},
                                    kRoundTripProvenance)
        .text;
  };
  for (int k = 0; k < 400; ++k) {
    // Written from a camera@1's R, then read and written: the rotation vector is kept exactly.
    const std::string written = MrcalCameramodelText(FamilyCamera(k), "cam.json", {}, kRoundTripProvenance).text;
    EXPECT_EQ(pass(written), written) << "camera " << k;
  }
}

TEST(RoundTrip, OpenCvYamlIsAFixedPoint) {
  for (int k = 0; k < 8; ++k) {
    CalibratedCamera c = FamilyCamera(k);
    c.camera_from_world.reset();
    const std::string written = OpenCvYamlText(c, "cam.json", kRoundTripProvenance).text;
    const ImportedCamera in = OpenCvYamlFromText(written, "cam.yaml", LengthUnit::kMillimetre);
    EXPECT_EQ(OpenCvYamlText(in.camera, "cam.yaml", kRoundTripProvenance).text, written) << "camera " << k;
  }
}

}  // namespace
}  // namespace vstcal
