// calib/fit: a volume calibration's test points are inside or outside the convex hull of its
// calibration points (docs/math/report-statistics.md#hull), not their bounding box; and what a
// camera file says when the points span no volume (docs/formats.md#camera, `fit`).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "vstcal/scene/fit.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/formats/camera/camera_io.h"

namespace vstcal {
namespace {

// fx = fy = 1000 px, the principal point at the image centre.
Camera CameraLookingAlongWorldZ() {
  SyntheticCameraSpec spec;
  spec.image_size = {1280, 720};
  spec.fx = 1000.0;
  return MakeSyntheticCamera(spec);
}

// The camera 1.5 m in front of the volume's centre, looking along world +z.
Rigid3d CameraFromWorld() { return Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(-100, -100, 1500)}; }

// A template of nx × 3 corners at z, x from 0 in steps of 100 mm, y ∈ {0, 100, 200}, with exact pixels.
View Template(const std::string& name, int nx, double z) {
  const Camera camera = CameraLookingAlongWorldZ();
  View view;
  view.name = name;
  for (int i = 0; i < nx; ++i) {
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d p(100.0 * i, 100.0 * j, z);
      view.observations.push_back({p, *camera.Project(CameraFromWorld() * p)});
    }
  }
  return view;
}

Fit FitWithTestPoints(std::vector<View> views, const std::vector<Eigen::Vector3d>& tests) {
  Correspondences c;
  c.image_size = ImageSize{1280, 720};
  c.views = std::move(views);
  for (size_t k = 0; k < tests.size(); ++k) c.test_points.push_back({"T" + std::to_string(k), tests[k], std::nullopt});
  return ComputeVolumeFit(CameraLookingAlongWorldZ(), CameraFromWorld(), c);
}

// Two template positions, the far one narrower (a template cut short, or half of it out of view):
// 3 × 3 corners over x, y ∈ [0, 200] at z = 0, 2 × 3 over x ∈ [0, 100] at z = 200. The bounding box
// is the cube [0, 200]³; the hull is the prism bounded by x = 0, y = 0, y = 200, z = 0, z = 200 and
// the slanted face through the edges x = 200, z = 0 and x = 100, z = 200: x + z/2 ≤ 200.
// - (180, 100, 150): in the box; x + z/2 = 255 > 200, so outside, 55/√(1 + 1/4) ≈ 49.19 mm beyond
//   the slanted face. The bounding box called it inside.
// - (100, 100, 100): x + z/2 = 150 ≤ 200 and strictly inside every other face: inside.
// - (150, 100, 100): x + z/2 = 200, on the slanted face: inside (bounds included).
// - (100, 100, 250): beyond z = 200, outside box and hull alike.
TEST(FitVolume, TestPointInTheBoxButOutsideTheHullIsOutside) {
  const Fit fit = FitWithTestPoints({Template("near", 3, 0), Template("far", 2, 200)},
                                    {{180, 100, 150}, {100, 100, 100}, {150, 100, 100}, {100, 100, 250}});
  ASSERT_TRUE(fit.volume && fit.volume->hull) << (fit.volume ? fit.volume->status : "no volume");
  EXPECT_EQ(fit.volume->status, "ok");
  EXPECT_EQ(fit.volume->vertices, 8u);  // the prism's corners; the grid's other corners lie on edges
  EXPECT_EQ(fit.volume->facets, 6u);    // coplanar facets merged into the prism's six faces
  EXPECT_NEAR(fit.volume->hull->SignedDistance({180, 100, 150}), 55 / std::sqrt(1.25), 1e-9);
  ASSERT_EQ(fit.test_points.size(), 4u);
  EXPECT_EQ(fit.test_points[0].inside_volume, std::optional<bool>(false));
  EXPECT_EQ(fit.test_points[1].inside_volume, std::optional<bool>(true));
  EXPECT_EQ(fit.test_points[2].inside_volume, std::optional<bool>(true));
  EXPECT_EQ(fit.test_points[3].inside_volume, std::optional<bool>(false));

  const OrderedJson j = FitToJson(fit);
  EXPECT_EQ(j.at("volume").at("hull"), "ok");
  EXPECT_EQ(j.at("volume").at("vertices"), 8);
  EXPECT_EQ(j.at("test_points").at(0).at("inside_volume"), false);
  EXPECT_EQ(j.at("test_points").at(1).at("inside_volume"), true);
}

// One template position is a volume rig whose points lie on one plane: no hull, so a test point is
// neither inside nor outside, in front of the plane or on it; the file says why.
TEST(FitVolume, OnePlaneHasNoHullAndNoSide) {
  const Fit fit = FitWithTestPoints({Template("only", 3, 0)}, {{100, 100, 100}, {100, 100, 0}});
  ASSERT_TRUE(fit.volume);
  EXPECT_FALSE(fit.volume->hull);
  EXPECT_EQ(fit.volume->status, "the points lie on one plane: they span no volume");
  ASSERT_EQ(fit.test_points.size(), 2u);
  EXPECT_EQ(fit.test_points[0].inside_volume, std::nullopt);
  EXPECT_EQ(fit.test_points[1].inside_volume, std::nullopt);
  EXPECT_STREQ(VolumeSideName(fit.test_points[0].inside_volume), "no hull");

  const OrderedJson j = FitToJson(fit);
  EXPECT_EQ(j.at("volume").at("hull"), "the points lie on one plane: they span no volume");
  EXPECT_EQ(j.at("volume").at("vertices"), 0);
  EXPECT_EQ(j.at("volume").at("facets"), 0);
  EXPECT_TRUE(j.at("test_points").at(0).at("inside_volume").is_null());
  EXPECT_TRUE(j.at("test_points").at(1).at("inside_volume").is_null());
}

// Planar views have no world frame and no test points: no volume is written.
TEST(FitVolume, PlanarViewsWriteNoVolume) {
  Correspondences c;
  c.image_size = ImageSize{1280, 720};
  c.rig = Rig::kPlanarViews;
  c.views = {Template("board", 3, 0)};
  const std::vector<Rigid3d> poses = {CameraFromWorld()};
  const Fit fit = ComputeViewsFit(CameraLookingAlongWorldZ(), poses, c);
  EXPECT_FALSE(fit.volume);
  EXPECT_FALSE(FitToJson(fit).contains("volume"));
}

}  // namespace
}  // namespace vstcal
