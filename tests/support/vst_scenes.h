// Simple VST rigs for err-sim tests and benchmarks.
#pragma once

#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/json/json_writer.h"

namespace vstcal::testing {

// A parallel orthostereo rig: two pinhole cameras (1280×720, fx = fy = `focal`, principal point
// at the image centre) with axes along the hmd's, centres at (∓baseline/2, 0, 0) in the hmd frame,
// eyes at the camera centres (ipd = baseline), a collimated display (virtual image at infinity).
// The hmd sits 2 m behind the world origin looking
// along world +z (hmd_from_tracker · tracker_from_world = translation (0, 0, 2000) mm with a
// non-trivial tracker in between); the virtual world and the object frame are rotated and
// shifted away from the world so that every frame of the chain is exercised. Test points are
// given in the world frame. Lengths in mm.
ChainGeometry ParallelRig(std::vector<Eigen::Vector3d> points_in_world, double focal = 700.0,
                                  double baseline = 63.0);

// The hmd frame's origin expressed in the world frame of ParallelRig: a point at hmd (x, y, z) is
// at world (x, y, z − 2000).
Eigen::Vector3d WorldFromHmdPoint(const Eigen::Vector3d& point_in_hmd);

// A vst-chain@1 document of a parallel orthostereo rig (pinhole 1280×720, fx = fy = `focal`,
// baseline and ipd 63 mm, a collimated display) with the hmd at the world origin and every frame the
// identity but the cameras' ±31.5 mm: a test point on the cyclopean axis at `depth` ("axis") and one
// off it ("aside", (200, −100, 1200)); `sources` its error sources and, when not null, `joint` its
// joint_covariance. Lengths in mm, 1,000 samples, seed 5.
OrderedJson ParallelRigChain(const OrderedJson& sources, double focal, double depth, const OrderedJson& joint = nullptr);
// A pose of the chain's frames: no rotation, translation (tx, ty, tz); a normal distribution of σ.
OrderedJson ChainPose(double tx, double ty, double tz);
OrderedJson ChainNormal(double sigma);

// Expects a run of `model`'s scenarios (3,000 samples, seed 3) on one thread and on two threads
// split into two merged shards to give every statistic of every output to the bit.
void ExpectTheSameBitsWhateverThreadsAndShards(const ChainModel& model);

}  // namespace vstcal::testing
