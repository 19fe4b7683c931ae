// Sub-pixel refinement of chessboard corners by point symmetry (docs/math/corners.md).
//
// Around a corner, four squares meet along two straight edges (lines stay lines under a pinhole
// projection), so the image of the corner's neighbourhood is point-symmetric about the corner:
// I(c + p) = I(c − p) for every offset p that stays inside the four squares, whatever the
// perspective, the blur (any point-symmetric PSF, the pixel's box included) or the contrast.
// The refinement finds c by Gauss–Newton on
//     E(c) = Σ_p w(p) · (L(c + p) − L(c − p))²,
// L the bilinear interpolant of the image, p over half a disc of integer offsets of radius R
// (each pair once; R the window's whole pixels, 2 … 8), w a Gaussian taper of σ = R/2. Bilinear interpolation's leading error,
// ½·f(1 − f)·I'', is the same at c + p and c − p (f and 1 − f are mirrored, I'' is even under
// the point reflection), so it cancels: the estimate has no interpolation bias to first order.
// No model of the blur or of the edges is fitted, which is why it is cheap (≈ 5 µs a corner).
#pragma once

#include <optional>

#include <Eigen/Core>

#include "vstcal/image/image.h"

namespace vstcal {

struct SymmetryRefinement {
  Eigen::Vector2d corner;  // refined position, px
  int iterations = 0;
};

// Refines `start` with a window of radius `radius` px (≥ 2; keep it below the distance to the
// next corner minus the blur). nullopt when the window leaves the image, Gauss–Newton diverges
// (a step larger than the radius) or the problem is singular (a flat patch).
std::optional<SymmetryRefinement> RefineCornerBySymmetry(const GrayImage& image, const Eigen::Vector2d& start, double radius);

// The optical blur of a straight edge between two points on it, px: the Gaussian σ whose 10 %–90 %
// rise (2.563 σ) matches the grey profile across the edge at the segment's midpoint, sampled
// every ¼ px over ±`reach` px, less the spread the pixel (box, 1/12 px²) and the bilinear
// sampling (1/6 px²) add. nullopt when the profile does not rise by at least 16 grey levels or
// leaves the image.
std::optional<double> EdgeBlur(const GrayImage& image, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double reach);

}  // namespace vstcal

namespace vstcal {

// How far the image around c is from point symmetry: the weighted RMS of L(c + p) − L(c − p)
// over the refinement's window, divided by the window's grey range (max − min). About 0 at an
// X-junction with little noise, about 0.5 or more elsewhere. nullopt when the window leaves the
// image or is flat.
std::optional<double> Asymmetry(const GrayImage& image, const Eigen::Vector2d& c, double radius);

}  // namespace vstcal
