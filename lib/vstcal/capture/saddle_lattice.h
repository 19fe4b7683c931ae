// A chessboard too small in the image for OpenCV's finders still shows its corners: X-junctions,
// where the image is a saddle, side by side along the squares' edges. Finding a lattice of them
// tells "the board is there, but too small" (miss_diagnosis.h) from "no board" (issue 25 item 4):
// the chessboard finders report no candidates of their own. Internal to the capture module.
//
// The saddles are the local maxima of −det H, H the Hessian of the image smoothed at σ 1 px: at
// an X-junction of contrast C blurred over σ_t the image is C·(a·x)(b·x)/(π σ_t²) near its centre (a,
// b the normals of its two edges: erf(z) ≈ 2z/√π), a saddle whose zero lines are the edges. Two
// saddles are linked as neighbouring corners of one board when the line between them runs along a
// zero line of each (an edge), the squares on its two sides differ (one black, one white), the
// middle of the line is the grey between them, and the saddles' polarity across the line is
// opposite (the squares' colours swap from one corner to the next). Noise, texture or a marker's
// bits link a few saddles by chance; a board links dozens.
#pragma once

#include <optional>

#include "vstcal/image/image.h"

namespace vstcal {

struct SaddleLattice {
  int corners = 0;         // saddles in the largest connected lattice (inner corners; a board's outer ones may join)
  double spacing_px = 0;   // median distance between linked saddles, px at full resolution
  int search_factor = 1;   // the reduction of the image searched (search_image.h)
};

// The largest lattice of linked saddles whose links are at most `max_link_px` (full-resolution px)
// in the image reduced for the search, or nullopt when none reaches kMinLatticeCorners.
inline constexpr int kMinLatticeCorners = 12;
std::optional<SaddleLattice> FindSaddleLattice(const GrayImage& image, double max_link_px);

}  // namespace vstcal
