// A planar-views start for a fisheye (a ray lens model, "kannala-brandt"): Zhang's closed form
// assumes a pinhole, and a wide fisheye's corners are where a pinhole is worst (its homographies
// bend: the focal length comes out far too large past ~60° off the axis), while a narrow lens's
// corners are where the fisheye's own guess is worst. docs/math/fisheye.md#start.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "vstcal/calib/zhang.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

// One candidate start as it was judged: with k = 0 or with its k1…k4 fitted.
struct FisheyeStartCandidate {
  std::string name;                // e.g. "equidistant rounds from the fisheye guess"
  bool ok = false;                 // false: its rounds or Zhang failed, nothing to judge
  bool coefficients_fitted = false;
  double cost = 0;                 // sum of squared reprojection errors, px² (when ok)
};

// Which candidate became the start, and how each fared: the decision a camera file records
// (`fisheye_start`, docs/formats.md#camera-fisheye-start).
struct FisheyeStartDecision {
  std::string chosen;                // the winner's name (empty when none succeeded: the pinhole's start is used)
  bool coefficients_fitted = false;  // the winner's k1…k4 fitted (else 0)
  double cost = 0;                   // its sum of squared reprojection errors, px²
  size_t num_points = 0;             // the corners every cost sums over
  std::vector<FisheyeStartCandidate> candidates;  // every one judged, in the order below

  // A cost as the RMS of the residual lengths over every corner, px: √(cost / N).
  double RmsPx(double sum_of_squares) const {
    return num_points ? std::sqrt(sum_of_squares / static_cast<double>(num_points)) : 0.0;
  }
};

struct FisheyeStart {
  ZhangResult start;  // camera: a "kannala-brandt" camera (K and k1…k4), one pose per view
  FisheyeStartDecision decision;
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
