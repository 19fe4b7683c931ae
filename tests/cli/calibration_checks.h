// What the CLI tests of the calibration tools (calib-tsai, calib-dlt --refine) share: their
// synthetic input, and checks that a camera@1 file's "covariance" block is well formed and that
// its parameters agree with a calib-synth truth within a multiple of the σ the same file reports.
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "cli_fixture.h"

namespace vstcal::cli_test {

// calib-synth flags for a distorted 640×480 camera (fx 600, k1 −0.15, k2 0.05) 0.9 m in front of
// a 9×7 grid (60 mm) at five depths 0…400 mm, tilted 15°, with 0.5 px noise and no test points:
// 315 points spread over most of the image.
std::vector<std::string> DistortedVolumeArgs();
inline constexpr double kVolumeNoisePx = 0.5;

// The camera of DistortedVolumeArgs() and a 9×7 board (30 mm) at 8 poses about 0.5 m away, rig
// "planar-views".
std::vector<std::string> PlanarArgs();

// A lens parameter of a camera@1 file by its covariance name: fx, fy, cx, cy, s from K, the
// distortion coefficients by name (0 when the file's model does not have the term).
double LensParameter(const Json& camera, const std::string& name);

// Index of `name` in camera["covariance"]["parameters"], or nullopt.
std::optional<size_t> CovarianceIndex(const Json& camera, const std::string& name);

// √Σᵢᵢ of a named parameter; fails the test (and returns NaN) when the covariance lacks it.
double Sigma(const Json& camera, const std::string& name);

// "covariance" has unique parameter names, an n×n matrix that is exactly symmetric with a
// positive diagonal and correlations within [−1, 1].
::testing::AssertionResult CovarianceIsWellFormed(const Json& camera);

// |estimate − truth| < k·σ for each named lens parameter, σ from the estimate's covariance.
// With an unbiased estimator and a correct covariance, |error|/σ is standard normal: k = 5 fails
// a correct solver with probability 6e-7 per parameter, while a wrong σ or a biased estimate by
// more than a few σ fails it.
::testing::AssertionResult WithinSigmas(const Json& estimate, const Json& truth, const std::vector<std::string>& names,
                                        double k);

// The rotation angle (degrees) between two camera_from_world (or camera_from_board) blocks.
double RotationDifferenceDeg(const Json& a, const Json& b);

}  // namespace vstcal::cli_test
