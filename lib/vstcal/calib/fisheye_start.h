// A planar-views start for a fisheye (a ray lens model, "kannala-brandt"): Zhang's closed form
// assumes a pinhole, and a wide fisheye's corners are where a pinhole is worst (its homographies
// bend: the focal length comes out far too large past ~60° off the axis). docs/math/fisheye.md#start.
#pragma once

#include "vstcal/calib/zhang.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal {

// Zhang's start redone on pinhole-equivalent corners: each round maps every corner through the
// current K to the pixel a pinhole with that K would see for the equidistant fisheye's ray
// (θ = θd = |K⁻¹ pixel|: pixel' = K·(tan θd/θd)·x_d), leaving out corners with θd ≥ 75°, where tan
// grows without bound, and solves Zhang again, until K moves by less than 1e-9 relative (at most
// 50 rounds). The true K of equidistant data is a fixed point, so the start's error is what
// k1…k4 add. The first round's K is OpenCV's fisheye guess, f = max(W, H)/π at the image centre
// (Zhang's K from the raw corners can be tens of % off, too far for the linearized corners to be
// consistent: Zhang then refuses them); if those rounds fail, `pinhole`'s K (Zhang on the raw
// corners). Returns the last round that succeeded, `pinhole` if none did.
ZhangResult EquidistantZhangStart(const Correspondences& c, const ZhangResult& pinhole);

}  // namespace vstcal
