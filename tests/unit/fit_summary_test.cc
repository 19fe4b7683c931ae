// lib/vstcal/report/fit_summary: a summary line is never cut, however long its numbers (issue 24:
// a camera centre of 1e200, printed in full with %.2f, was cut at 512 bytes).
#include <gtest/gtest.h>

#include <cstdio>

#include "vstcal/report/fit_summary.h"

namespace vstcal {
namespace {

TEST(FitSummary, ACameraCentreOf1e200IsPrintedWhole) {
  CalibratedCamera camera;
  Eigen::Matrix3d K;
  K << 600, 0, 320, 0, 600, 240, 0, 0, 1;
  camera.camera = Camera::FromK(K, {640, 480});
  camera.camera_from_world = Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-1e200, -2e200, -3e200)};
  const std::string text = FitSummaryText(camera);
  // The expected line, printed here on its own: the centre is −t.
  const int n = std::snprintf(nullptr, 0, "  camera centre in world: (%.2f, %.2f, %.2f) mm\n", 1e200, 2e200, 3e200);
  std::string line(static_cast<size_t>(n), '\0');
  std::snprintf(line.data(), line.size() + 1, "  camera centre in world: (%.2f, %.2f, %.2f) mm\n", 1e200, 2e200, 3e200);
  EXPECT_GT(line.size(), 600u);
  EXPECT_NE(text.find(line), std::string::npos) << text;
}

}  // namespace
}  // namespace vstcal
