// 3-D ↔ 2-D correspondences: the content of a vstcal/correspondences@1 file (docs/formats.md).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"

namespace vstcal {

enum class Rig {
  kVolume,       // all points in one world frame, one camera pose; DLT applies
  kPlanarViews,  // each view in its own board frame (Z = 0), one pose per view
};

// The fewest points a planar view needs to count: a homography has 8 degrees of freedom, and the
// 6th point is the first to check them (calib/zhang.h; synthetic views are made with at least this).
inline constexpr size_t kMinPointsPerPlanarView = 6;

// One measured point: `point` in the rig's frame (world for a volume, board for planar views,
// in the file's length unit), the pixel where it was detected, and its weight: the point's pixel
// noise is σ/√weight, σ that of a weight-1 point, so it counts in a fit as `weight` points of
// weight 1 (docs/formats.md#weights; mrcal's decimation level ℓ is weight 1/4^ℓ).
struct Observation {
  Eigen::Vector3d point;
  Eigen::Vector2d pixel;
  double weight = 1.0;  // > 0
};

struct View {
  std::string name;
  std::string image;                  // source image, may be empty
  std::optional<double> plane_offset;  // template offset along its normal, length unit
  std::vector<Observation> observations;
  std::optional<double> time;          // when the image was taken, s on the camera's clock (hand-eye)
};

// A point never used in a solve: it measures registration error (seed 000 §4.2).
struct TestPoint {
  std::string name;
  Eigen::Vector3d point_in_world;
  std::optional<Eigen::Vector2d> pixel;  // where it was detected, when measured
};

struct Correspondences {
  std::string camera;  // e.g. "left"
  ImageSize image_size;
  LengthUnit length_unit = LengthUnit::kMillimetre;
  Rig rig = Rig::kVolume;
  std::vector<View> views;
  std::vector<TestPoint> test_points;
};

size_t NumObservations(const Correspondences& c);

// A power of two by which solvers scale world coordinates far from 1 before summing or squaring
// them: 2^−e with e = ilogb of the largest |point − origin|, when that is beyond 1e±100 (the
// coordinates of a file scaled by 1e±300); 1 otherwise, so that ordinary data are solved exactly
// as given. Scaling by a power of two is exact: a solver undoes it on its lengths at the end.
double WorldCoordinateScale(std::span<const Observation> observations, const Eigen::Vector3d& origin);
// All observations of all views in order, for solvers of a single pose.
std::vector<Observation> AllObservations(const Correspondences& c);

}  // namespace vstcal
