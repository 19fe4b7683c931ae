// lib/vstcal/geometry/convex_hull: the hull against its half-spaces worked out by hand
// (docs/math/report-statistics.md#hull).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vstcal/geometry/convex_hull.h"

namespace vstcal {
namespace {

// The unit tetrahedron's hull is x, y, z ≥ 0 and x + y + z ≤ 1: its bounding box is the unit cube,
// so points of the cube beyond the slanted face tell a hull from a box.
std::vector<Eigen::Vector3d> Tetrahedron() {
  std::vector<Eigen::Vector3d> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  p.push_back({0.1, 0.1, 0.1});  // inner points do not change the hull
  p.push_back({0.5, 0.25, 0.25});  // on the slanted face
  return p;
}

TEST(ConvexHull, TetrahedronAgainstItsHalfSpaces) {
  const auto outcome = ConvexHull3::Of(Tetrahedron());
  ASSERT_TRUE(outcome.hull) << outcome.why;
  const ConvexHull3& hull = *outcome.hull;
  EXPECT_EQ(hull.num_vertices(), 4u);
  EXPECT_EQ(hull.num_facets(), 4u);
  EXPECT_TRUE(hull.Contains({0.2, 0.2, 0.2}));
  EXPECT_TRUE(hull.Contains({1.0 / 3, 1.0 / 3, 1.0 / 3}));  // on the slanted face: bounds included
  EXPECT_TRUE(hull.Contains({0, 0, 0}));                    // a vertex
  EXPECT_TRUE(hull.Contains({0.5, 0, 0}));                  // an edge
  EXPECT_FALSE(hull.Contains({0.4, 0.4, 0.4}));             // inside the bounding box, outside the hull
  EXPECT_NEAR(hull.SignedDistance({0.4, 0.4, 0.4}), 0.2 / std::sqrt(3.0), 1e-12);  // (x + y + z − 1)/√3
  EXPECT_NEAR(hull.SignedDistance({-0.5, 0.2, 0.2}), 0.5, 1e-12);                  // beyond x = 0
  EXPECT_NEAR(hull.SignedDistance({0.1, 0.2, 0.3}), -0.1, 1e-12);  // nearest face x = 0
}

TEST(ConvexHull, CubeGridWithCoplanarFacesIsTheCube) {
  // A 3×3×3 grid, as a calibration volume of three planes gives: many coplanar points per face.
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) p.push_back({100.0 * i, 100.0 * j, 200.0 * k});
  const auto outcome = ConvexHull3::Of(p);
  ASSERT_TRUE(outcome.hull) << outcome.why;
  EXPECT_EQ(outcome.hull->num_vertices(), 8u);
  EXPECT_TRUE(outcome.hull->Contains({200, 200, 400}));  // a corner
  EXPECT_TRUE(outcome.hull->Contains({100, 0, 250}));    // on a face
  EXPECT_FALSE(outcome.hull->Contains({100, 100, 400.001}));
  EXPECT_NEAR(outcome.hull->SignedDistance({100, 100, 450}), 50, 1e-9);
}

TEST(ConvexHull, NoVolumeIsAStatusNotAnError) {
  const std::vector<Eigen::Vector3d> plane = {{0, 0, 5}, {1, 0, 5}, {0, 1, 5}, {1, 1, 5}, {0.5, 0.2, 5}};
  const auto flat = ConvexHull3::Of(plane);
  EXPECT_FALSE(flat.hull);
  EXPECT_NE(flat.why.find("one plane"), std::string::npos) << flat.why;
  const std::vector<Eigen::Vector3d> three = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_NE(ConvexHull3::Of(three).why.find("fewer than 4"), std::string::npos);
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  EXPECT_NE(ConvexHull3::Of(line).why.find("one line"), std::string::npos);
}

// The same cube grid in any length unit, 1e-150 to 1e200 times (issue 24: 1e100 and 1e-150 gave
// "no hull", and at 1e200 the bounding box's diagonal overflowed, so that every point was inside):
// the same hull, and the same decisions and distances at the scaled points.
TEST(ConvexHull, TheSameHullInAnyLengthUnit) {
  for (const double scale : {1e-150, 1e-30, 1.0, 1e30, 1e100, 1e200}) {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k) p.push_back(scale * Eigen::Vector3d(100.0 * i, 100.0 * j, 200.0 * k));
    const auto outcome = ConvexHull3::Of(p);
    ASSERT_TRUE(outcome.hull) << scale << ": " << outcome.why;
    EXPECT_EQ(outcome.hull->num_vertices(), 8u) << scale;
    EXPECT_EQ(outcome.hull->num_facets(), 6u) << scale;
    EXPECT_TRUE(outcome.hull->Contains(scale * Eigen::Vector3d(200, 200, 400))) << scale;
    EXPECT_TRUE(outcome.hull->Contains(scale * Eigen::Vector3d(100, 0, 250))) << scale;
    EXPECT_FALSE(outcome.hull->Contains(scale * Eigen::Vector3d(100, 100, 400.001))) << scale;
    EXPECT_FALSE(outcome.hull->Contains(scale * Eigen::Vector3d(-640, 0, 200))) << scale;
    EXPECT_NEAR(outcome.hull->SignedDistance(scale * Eigen::Vector3d(100, 100, 450)) / scale, 50, 1e-9) << scale;
    EXPECT_FALSE(outcome.hull->Contains({1e308, 0, 0})) << scale;  // far outside, whatever the unit
  }
}

}  // namespace
}  // namespace vstcal
