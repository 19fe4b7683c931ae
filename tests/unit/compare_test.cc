// CompareCameras against closed forms.
#include <gtest/gtest.h>

#include "vstcal/calib/compare.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

CalibratedCamera Posed(double cx) {
  Eigen::Matrix3d K;
  K << 1000, 0, cx, 0, 1000, 360, 0, 0, 1;
  CalibratedCamera c;
  c.camera = Camera::FromK(K, ImageSize{1280, 720});
  c.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(0.1, 0.2, -0.1), Eigen::Vector3d(5, -10, 2500));
  return c;
}

TEST(CompareCameras, IdenticalCamerasAgreeEverywhere) {
  const CameraComparison c = CompareCameras(Posed(640), Posed(640));
  EXPECT_EQ(c.n_points, 81u);
  EXPECT_LT(c.max_px, 1e-9);
  EXPECT_NEAR(*c.rotation_deg, 0, 1e-12);
  EXPECT_NEAR(*c.centre_distance, 0, 1e-9);
  EXPECT_DOUBLE_EQ(c.depth, 2500);  // the world origin's depth
}

// A principal point moved by 1.5 px shifts every pixel by exactly 1.5 px.
TEST(CompareCameras, PrincipalPointShiftIsAUniformPixelShift) {
  const CameraComparison c = CompareCameras(Posed(640), Posed(641.5), 1800.0);
  EXPECT_NEAR(c.rms_px, 1.5, 1e-9);
  EXPECT_NEAR(c.max_px, 1.5, 1e-9);
  EXPECT_DOUBLE_EQ(c.K_difference(0, 2), 1.5);
  EXPECT_DOUBLE_EQ(c.depth, 1800);
}

// A camera centre moved by Δ sideways shows as f·Δ/z pixels at depth z.
TEST(CompareCameras, TranslationParallaxIsFocalTimesShiftOverDepth) {
  CalibratedCamera b = Posed(640);
  b.camera_from_world->t.x() += 3.0;  // camera-frame shift of 3 mm
  const CameraComparison c = CompareCameras(Posed(640), b, 1500.0);
  EXPECT_NEAR(c.rms_px, 1000 * 3.0 / 1500, 1e-9);
  EXPECT_NEAR(*c.centre_distance, 3.0, 1e-9);
}

TEST(CompareCameras, RefusesDifferentSensors) {
  CalibratedCamera b = Posed(640);
  b.camera.image_size.width = 640;
  EXPECT_THROW(CompareCameras(Posed(640), b), InputError);
  b = Posed(640);
  b.length_unit = LengthUnit::kMetre;
  EXPECT_THROW(CompareCameras(Posed(640), b), InputError);
}

}  // namespace
}  // namespace vstcal
