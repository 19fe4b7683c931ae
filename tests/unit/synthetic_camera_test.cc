// calib-synth's camera and truth, as library calls: K from the field of view (closed form), the
// skew angle (seed 001 Eq. 5), every lens model by its coefficient count, and the refusals.
#include <gtest/gtest.h>

#include <cmath>

#include "support/error_of.h"
#include "vstcal/core/option_name.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

TEST(SyntheticCamera, KFromFieldOfViewAndSkewAngle) {
  SyntheticCameraSpec spec;
  spec.image_size = ImageSize{1280, 720};
  spec.hfov_deg = 90;
  spec.skew_deg = 80;
  const Eigen::Matrix3d K = MakeSyntheticCamera(spec).K();
  // 90° across the whole width: fx = (W/2) / tan 45° = 640 exactly; s = −fx cot θ.
  EXPECT_DOUBLE_EQ(K(0, 0), 640.0);
  EXPECT_DOUBLE_EQ(K(1, 1), 640.0);
  EXPECT_NEAR(K(0, 1), -640.0 / std::tan(80.0 * kPi / 180.0), 1e-12);
  EXPECT_DOUBLE_EQ(K(0, 2), 639.5);  // (W − 1)/2
  EXPECT_DOUBLE_EQ(K(1, 2), 359.5);
}

TEST(SyntheticCamera, LensModelByCoefficientCount) {
  SyntheticCameraSpec spec;
  spec.image_size = ImageSize{640, 480};
  spec.fx = 500;
  EXPECT_EQ(LensModelName(MakeSyntheticCamera(spec).model), "none");
  spec.distortion = {-0.1, 0.01, 0, 0, 0.001};
  EXPECT_EQ(LensModelName(MakeSyntheticCamera(spec).model), "radial-tangential");
  spec.distortion = {0.1, 0.01, 0, 0, 0.001, 0.2, 0.02, 0.002};
  const Camera rational = MakeSyntheticCamera(spec);
  EXPECT_EQ(LensModelName(rational.model), "rational");
  EXPECT_EQ(std::vector<double>(rational.distortion().begin(), rational.distortion().end()), spec.distortion);
  spec.distortion = {0.1, 0.2};
  EXPECT_THROW(MakeSyntheticCamera(spec), InputError);
}

TEST(SyntheticCamera, RefusesImpossibleAndOutOfScaleValues) {
  SyntheticCameraSpec spec;
  spec.image_size = ImageSize{640, 480};
  EXPECT_THROW(MakeSyntheticCamera(spec), InputError);  // neither fx nor hfov
  spec.fx = 1e300;
  const std::string e = testing::ErrorOf([&] { MakeSyntheticCamera(spec); });
  EXPECT_NE(e.find(VSTCAL_OPT("fx") ": 1e+300 px is beyond ±1e+09"), std::string::npos) << e;
  spec.fx = 500;
  spec.cx = NAN;
  EXPECT_THROW(MakeSyntheticCamera(spec), InputError);
}

TEST(SyntheticCamera, VolumeTruthHoldsThePoseAndTheFit) {
  SyntheticCameraSpec camera_spec;
  camera_spec.image_size = ImageSize{640, 480};
  camera_spec.fx = 600;
  const Camera camera = MakeSyntheticCamera(camera_spec);
  VolumeSpec spec;
  spec.grid_cols = 5;
  spec.grid_rows = 4;
  spec.far = 400;
  spec.camera_distance = 1500;
  spec.camera_name = "left";
  const SyntheticVolume volume = SynthesizeVolume(camera, spec, {});
  const CalibratedCamera truth = VolumeTruthCamera(camera, spec, volume);
  EXPECT_EQ(truth.method, "synthetic");
  EXPECT_EQ(truth.name, "left");
  EXPECT_EQ(truth.camera_from_world->R, volume.camera_from_world.R);
  ASSERT_TRUE(truth.fit.has_value());
  EXPECT_EQ(truth.fit->overall.n_points, 60u);
  EXPECT_LT(truth.fit->overall.rms_px, 1e-9);  // no noise: the true camera fits exactly
}

}  // namespace
}  // namespace vstcal
