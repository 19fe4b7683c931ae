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
// candidates), most of them under kMinPxPerCell pixels a marker cell.
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

// The blur σ, px at full resolution, of the sharpest tenth of the image's strongest edges, and how
// many edges were measured; nullopt when fewer than 20 (a flat image). Edges are chosen in the
// reduced search image (search_image.h) and measured at full resolution, profiles reaching ±reach_px.
struct EdgeSharpness {
  double sigma_px = 0;
  int edges = 0;
};
std::optional<EdgeSharpness> SharpestEdgeBlur(const GrayImage& image, double reach_px);

// What to add to a not-found reason, or empty: "the markers look too small: …; move closer …"
// when the undecoded candidates are small (blur cannot be read where edges are a pixel or two
// apart), else "the image looks blurred: …; refocus …" (a blurred marker does not decode either).
// `undecoded_sides_px`: sides of the candidates a marker finder could not decode (empty for the
// chessboard); `cells`: cells across a marker, black border included; `what`: "marker" or "tag".
std::string MissHint(const GrayImage& image, const DetectorOptions& options, std::vector<double> undecoded_sides_px, int cells,
                     std::string_view what);

}  // namespace vstcal
