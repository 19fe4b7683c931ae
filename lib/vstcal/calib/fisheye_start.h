// A planar-views start for a fisheye (a ray lens model, "kannala-brandt"): Zhang's closed form
// assumes a pinhole, and a wide fisheye's corners are where a pinhole is worst (its homographies
// bend: the focal length comes out far too large past ~60° off the axis), while a narrow lens's
// corners are where the fisheye's own guess is worst. docs/math/fisheye.md#start.
#pragma once

#include <string>

#include "vstcal/calib/zhang.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

struct FisheyeStart {
  ZhangResult start;   // camera: a "kannala-brandt" camera (K and k1…k4), one pose per view
  std::string chosen;  // which candidate won (empty when none succeeded: `start` is then the pinhole's)
  double cost = 0;     // its sum of squared reprojection errors, px²
};

// The start chosen from the data among three candidates, each a K and one pose per view:
//  - Zhang redone on pinhole-equivalent corners from OpenCV's fisheye guess, f = max(W, H)/π at
//    the image centre: each round maps every corner through the current K to the pixel a pinhole
//    with that K would see for the equidistant fisheye's ray (θ = θd = |K⁻¹ pixel|: pixel' =
//    K·(tan θd/θd)·x_d), leaving out corners with θd ≥ 75°, where tan grows without bound, and
//    solves Zhang again, until K moves by less than 1e-9 relative (at most 50 rounds); the true K of
//    equidistant data is a fixed point;
//  - the same rounds from `pinhole`'s K (Zhang on the raw corners);
//  - `pinhole` itself (a narrow lens: its homographies are straight).
// Each candidate's k1…k4 are fitted by linear least squares with its K and poses fixed (θd − θ is
// linear in them), and the candidate, with those k's or with k = 0, whose reprojection cost through
// the Kannala–Brandt projection is lowest is the start. If no candidate succeeded, `pinhole`.
FisheyeStart ChooseFisheyeStart(const Correspondences& c, const ZhangResult& pinhole);

}  // namespace vstcal
