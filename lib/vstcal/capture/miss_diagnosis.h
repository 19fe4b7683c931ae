// Why a target was not found, where the image can tell (issue 25): the image is too blurred, or
// the board's markers are too small — so that a not-found reason names the right fix (refocus, or
// move closer) instead of the target file's rows and cols. Internal to the capture module.
//
// Blurred: the blur σ of the image's sharpest edges — the same measure (EdgeBlur,
// corner_refinement.h: the Gaussian σ of the 10 %–90 % rise across an edge, net of the pixel and
// the sampling) that rejects a found view as blurred — above the detector's max_blur_px. Measured
// across up to kEdgesMeasured of the image's strongest edges, one per cell of a coarse grid; the
// sharpest tenth decides: a sharp image has sharp edges somewhere, a defocused one has none.
// Too small: OpenCV's marker finder saw quadrilaterals it could not decode (its rejected
// candidates), most of them under kMinPxPerCell pixels a marker cell; or, for a chessboard (whose
// finders report no candidates), a lattice of chessboard corners (saddle_lattice.h) whose squares
// are smaller than the finders read (kMinSquareSearchPx in the image they searched).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/capture/detect.h"

namespace vstcal {

// Pixels a marker cell needs to decode: OpenCV samples each cell's middle after removing the
// perspective; below about 2 px a cell, blur and the pixel grid mix neighbouring cells. (At 3 px a
// chessboard's 40 px squares, read as Kalibr's 10-cell tags, were called too small.)
inline constexpr double kMinPxPerCell = 2;

// Pixels a chessboard square needs in the image the finders search (search_image.h): on 640×480
// renders tilted up to 35° (blur σ 0.5–1 px, noise σ 2) OpenCV's classic-then-sector-based search
// found 0 of 8 views of 5 px squares, 7 of 8 at 6 px and 8 of 8 at 7 px.
inline constexpr double kMinSquareSearchPx = 7;

// The blur σ, px at full resolution, of the sharpest tenth of the image's strongest edges, and how
// many edges were measured; nullopt when fewer than 20 (a flat image). Edges are chosen in the
// reduced search image (search_image.h) and measured at full resolution, profiles reaching ±reach_px.
struct EdgeSharpness {
  double sigma_px = 0;
  int edges = 0;
};
std::optional<EdgeSharpness> SharpestEdgeBlur(const GrayImage& image, double reach_px);

// "the <what>s look too small: …; move the camera closer …" when at least 4 candidates a marker
// finder could not decode have a median side under kMinPxPerCell × `cells`, else empty.
// `undecoded_sides_px`: their sides, px; `cells`: cells across a marker, black border included;
// `what`: "marker" or "tag".
std::string TooSmallMarkers(std::vector<double> undecoded_sides_px, int cells, std::string_view what);

// "the squares look too small: …; move the camera closer …" when the image shows a lattice of
// chessboard corners whose squares are under kMinSquareSearchPx in the image the finders searched
// (reduced by `search_factor`), else empty.
std::string TooSmallSquares(const GrayImage& image, int search_factor);

// What to add to a not-found reason, or empty: `too_small` (one of the above) where given — checked
// first, since blur cannot be read where edges are a pixel or two apart — else "the image looks
// blurred: …; refocus …" (a blurred marker does not decode either).
std::string MissHint(const GrayImage& image, const DetectorOptions& options, std::string too_small);

}  // namespace vstcal
