// OpenCV's distortion vector ↔ vstcal's lens models: chosen by coefficient count alone.
#include <gtest/gtest.h>

#include "vstcal/camera/opencv_distortion.h"

namespace vstcal {
namespace {

Camera WithDistortion(AnyLensModel model, std::vector<double> d) {
  Eigen::Matrix3d K;
  K << 800, 0, 320, 0, 800, 240, 0, 0, 1;
  return Camera::FromK(K, ImageSize{640, 480}, model, d);
}

TEST(OpenCvDistortion, ModelForEachOpenCvLength) {
  EXPECT_EQ(LensModelName(*LensModelForOpenCvLength(0)), "none");
  EXPECT_EQ(LensModelName(*LensModelForOpenCvLength(4)), "radial-tangential");
  EXPECT_EQ(LensModelName(*LensModelForOpenCvLength(5)), "radial-tangential");
  EXPECT_EQ(LensModelName(*LensModelForOpenCvLength(8)), "rational");
  for (const int n : {12, 14, 1, 3, 6, 7, 9, -1}) EXPECT_FALSE(LensModelForOpenCvLength(n).has_value()) << n;
}

TEST(OpenCvDistortion, FourCoefficientsMeanK3IsZero) {
  const double d[4] = {-0.1, 0.01, 1e-3, -2e-3};
  const Camera c = CameraFromOpenCv(Eigen::Matrix3d::Identity(), ImageSize{10, 10}, d);
  EXPECT_EQ(LensModelName(c.model), "radial-tangential");
  EXPECT_EQ(std::vector<double>(c.distortion().begin(), c.distortion().end()),
            (std::vector<double>{-0.1, 0.01, 1e-3, -2e-3, 0.0}));
}

TEST(OpenCvDistortion, ShortestLengthKeepsTheModel) {
  EXPECT_EQ(ShortestOpenCvLength(WithDistortion(PinholeModel{}, {})), 0);
  EXPECT_EQ(ShortestOpenCvLength(WithDistortion(RadialTangentialModel{}, {-0.1, 0.01, 0, 0, 0})), 4);
  EXPECT_EQ(ShortestOpenCvLength(WithDistortion(RadialTangentialModel{}, {-0.1, 0.01, 0, 0, 1e-300})), 5);
  // A rational camera whose denominator is 1 still goes out as 8 coefficients: 4 or 5 would read
  // back as "radial-tangential".
  EXPECT_EQ(ShortestOpenCvLength(WithDistortion(RationalModel{}, {0, 0, 0, 0, 0, 0, 0, 0})), 8);
}

TEST(OpenCvDistortion, PaddingAndTheCoefficientsThatDoNotFit) {
  const Camera rt = WithDistortion(RadialTangentialModel{}, {-0.1, 0.01, 2e-3, 0, 0.005});
  EXPECT_EQ(OpenCvDistortion(rt, 8), (std::vector<double>{-0.1, 0.01, 2e-3, 0, 0.005, 0, 0, 0}));
  EXPECT_EQ(OpenCvDistortion(rt, 5), (std::vector<double>{-0.1, 0.01, 2e-3, 0, 0.005}));
  EXPECT_EQ(FirstCoefficientBeyond(rt, 4), 4);  // k3
  EXPECT_FALSE(FirstCoefficientBeyond(rt, 5).has_value());
  const Camera rational = WithDistortion(RationalModel{}, {0.4, -0.08, 0, 0, 0, 0, -1e-12, 0});
  EXPECT_EQ(FirstCoefficientBeyond(rational, 5), 6);  // k5
  EXPECT_EQ(OpenCvDistortion(WithDistortion(PinholeModel{}, {}), 4), (std::vector<double>{0, 0, 0, 0}));
}

}  // namespace
}  // namespace vstcal
