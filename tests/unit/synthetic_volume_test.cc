// Synthetic calibration volumes: geometry of the pose, noise statistics and keying, test points.
#include <gtest/gtest.h>

#include "vstcal/scene/fit.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

Camera TestCamera() {
  Eigen::Matrix3d K;
  K << 1500, 0, 639.5, 0, 1500, 511.5, 0, 0, 1;
  return Camera::FromK(K, ImageSize{1280, 1024});
}

TEST(SyntheticVolume, PoseAtZeroTiltSitsOnTheAxisAtCameraDistance) {
  VolumeSpec spec;  // near 0, far 2000, camera distance 2000
  const Rigid3d camera_from_world = VolumeCameraPose(spec);
  const Eigen::Vector3d centre = camera_from_world.inverse().t;
  EXPECT_LT((centre - Eigen::Vector3d(0, 0, -2000)).norm(), 1e-9);
  EXPECT_LT((camera_from_world.R - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(SyntheticVolume, TiltedCameraLooksAtTheVolumeCentre) {
  VolumeSpec spec;
  spec.tilt_deg = 20;
  spec.tilt_direction_deg = 30;
  spec.roll_deg = 0;
  const Rigid3d camera_from_world = VolumeCameraPose(spec);
  const Eigen::Vector3d in_camera = camera_from_world * Eigen::Vector3d(0, 0, 1000);
  EXPECT_LT(in_camera.head<2>().norm(), 1e-9);  // on the optical axis
  EXPECT_NEAR(in_camera.z(), 3000, 1e-9);       // radius = distance + half depth
  // Without roll the image x axis is horizontal in the template plane (no world-Y component).
  EXPECT_NEAR(camera_from_world.R.row(0).dot(Eigen::Vector3d::UnitY()), 0, 1e-15);
  // The optical axis makes the tilt angle with the template normal.
  EXPECT_NEAR(std::acos(camera_from_world.R.row(2).dot(Eigen::Vector3d::UnitZ())), DegToRad(20), 1e-12);
  spec.roll_deg = 10;
  const Rigid3d rolled = VolumeCameraPose(spec);
  EXPECT_NEAR(AngleBetween(rolled.R, camera_from_world.R), DegToRad(10), 1e-12);
}

TEST(SyntheticVolume, NoiseFreePixelsAreExactProjections) {
  VolumeSpec spec;
  const Camera camera = TestCamera();
  const SyntheticVolume v = SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
  ASSERT_EQ(v.correspondences.views.size(), 11u);  // 0, 200, …, 2000
  EXPECT_EQ(*v.correspondences.views[3].plane_offset, 600.0);
  for (const View& view : v.correspondences.views) {
    for (const Observation& o : view.observations) {
      EXPECT_EQ(o.pixel, *camera.Project(v.camera_from_world * o.point));
      EXPECT_EQ(o.point.z(), *view.plane_offset);
    }
  }
  // At 2 m the 1.2 m × 0.8 m template fills about half the image: every corner is visible.
  EXPECT_EQ(NumObservations(v.correspondences), 11u * 13 * 9);
}

TEST(SyntheticVolume, NoiseHasTheRequestedSigmaAndIsKeyedByGridIndex) {
  VolumeSpec spec;
  spec.noise_px = 0.7;
  spec.seed = 31;
  const Camera camera = TestCamera();
  const SyntheticVolume v = SynthesizeVolume(camera, spec, {});
  double sum = 0, sum2 = 0;
  size_t n = 0;
  for (const View& view : v.correspondences.views) {
    for (const Observation& o : view.observations) {
      const Eigen::Vector2d e = o.pixel - *camera.Project(v.camera_from_world * o.point);
      sum += e.x() + e.y();
      sum2 += e.squaredNorm();
      n += 2;
    }
  }
  const double sd = std::sqrt(sum2 / n);
  EXPECT_LT(std::abs(sum / n), 5 * 0.7 / std::sqrt(n));
  EXPECT_NEAR(sd, 0.7, 5 * 0.7 / std::sqrt(2.0 * n));
  // Corner (i, j) of plane k draws Normal2(j·cols + i, 0) from stream k.
  const Observation& o = v.correspondences.views[2].observations[14];  // row 1, column 1
  const auto z = CounterRng(31, 2).Normal2(1 * 13 + 1, 0);
  const Eigen::Vector2d expected = *camera.Project(v.camera_from_world * o.point) + 0.7 * Eigen::Vector2d(z[0], z[1]);
  EXPECT_EQ(o.pixel, expected);
}

TEST(SyntheticVolume, DeterministicPerSeed) {
  VolumeSpec spec;
  spec.noise_px = 0.2;
  const Camera camera = TestCamera();
  const auto a = SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
  const auto b = SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
  spec.seed = 2;
  const auto c = SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
  EXPECT_EQ(a.correspondences.views[5].observations[7].pixel, b.correspondences.views[5].observations[7].pixel);
  EXPECT_NE(a.correspondences.views[5].observations[7].pixel, c.correspondences.views[5].observations[7].pixel);
  EXPECT_EQ(a.correspondences.test_points[0].pixel, b.correspondences.test_points[0].pixel);
}

// Seed 000 Fig. 4: "Left" 44 cm and "Right" 16 cm outside the template, Middle 1–3 inside.
TEST(SyntheticVolume, Seed000TestPointsStraddleTheVolume) {
  VolumeSpec spec;
  const Camera camera = TestCamera();
  const SyntheticVolume v = SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
  const Fit fit = ComputeVolumeFit(camera, v.camera_from_world, v.correspondences);
  ASSERT_EQ(fit.test_points.size(), 5u);
  EXPECT_EQ(fit.test_points[0].name, "Left");
  EXPECT_NEAR(fit.test_points[0].point_in_world.x(), -600 - 440, 1e-12);
  EXPECT_NEAR(fit.test_points[1].point_in_world.x(), 600 + 160, 1e-12);
  EXPECT_EQ(fit.test_points[0].inside_volume, std::optional<bool>(false));
  EXPECT_EQ(fit.test_points[1].inside_volume, std::optional<bool>(false));
  for (int i = 2; i < 5; ++i) EXPECT_EQ(fit.test_points[i].inside_volume, std::optional<bool>(true)) << fit.test_points[i].name;
  for (const auto& t : fit.test_points) EXPECT_NEAR(*t.error_px(), 0.0, 1e-9);
  spec.length_unit = LengthUnit::kMetre;  // offsets follow the unit
  EXPECT_NEAR(Seed000TestPoints(spec)[1].point_in_world.x(), 600 + 0.16, 1e-12);
}

TEST(SyntheticVolume, RejectsImpossibleSpecs) {
  const Camera camera = TestCamera();
  auto expect_error = [&](VolumeSpec spec, const std::string& flag) {
    try {
      SynthesizeVolume(camera, spec, Seed000TestPoints(spec));
      ADD_FAILURE() << "no error for " << flag;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
    }
  };
  VolumeSpec s;
  s.spacing = 0;
  expect_error(s, VSTCAL_OPT("spacing"));
  s = {};
  s.interval = -1;
  expect_error(s, VSTCAL_OPT("interval"));
  s = {};
  s.far = -5;
  expect_error(s, VSTCAL_OPT("far"));
  s = {};
  s.noise_px = -0.1;
  expect_error(s, VSTCAL_OPT("noise"));
  s = {};
  s.camera_distance = 0;
  expect_error(s, VSTCAL_OPT("camera_distance"));
  s = {};
  s.grid_cols = 41;  // a 4 m wide template
  s.camera_distance = 10;
  s.tilt_deg = 75;  // on a 1010 mm sphere the camera sits between the planes, beside the axis
  expect_error(s, VSTCAL_OPT("camera_distance"));
  s = {};
  s.grid_cols = 1;
  expect_error(s, VSTCAL_OPT("grid"));
}

TEST(Fit, ResidualStatistics) {
  const std::vector<Eigen::Vector2d> r = {{3, 4}, {0, 0}, {NAN, NAN}, {1, 0}};
  const ResidualStats s = Summarize(r);
  EXPECT_EQ(s.n_points, 3u);
  EXPECT_DOUBLE_EQ(s.max_px, 5.0);
  EXPECT_DOUBLE_EQ(s.rms_px, std::sqrt(26.0 / 3));
}

}  // namespace
}  // namespace vstcal
