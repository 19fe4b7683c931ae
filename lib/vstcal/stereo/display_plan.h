// Stereo display planning (seed 000 §3, Eq. 3–6, derived again in docs/math/stereo.md#display):
// parallel cameras a baseline b apart, focal length f px, show their images to the two eyes. A
// point at depth z appears in the two images with crossed disparity d(z) = f·b/z (Eq. 3): with
// the images shown as captured, everything is in front of the zero-parallax plane, which is at
// infinity. Translating the images apart by t = d(z0) = f·b/z0 px (the left image's content to the
// left by t/2, the right one's to the right) puts depth z0 at zero parallax; the screen parallax
// (right image minus left image, positive = uncrossed = behind the screen) becomes
// p(z) = t − d(z) = f·b·(1/z0 − 1/z) (Eq. 4). Cropping both images to the display width A after
// the translation needs a capture width A′ = A + t (Eq. 5–6; with θ the horizontal field of view
// across A′, A′ = A / (1 − b/(2·tan(θ/2)·z0))).
//
// What a viewer with interpupillary distance I perceives (seed 001 §4.6: IPD ≠ baseline):
//  - "hmd": each eye sees its image through its own display at the camera's field of view (the
//    display model of err-sim, docs/math/vst-chain.md#perceived): Z = I·f/(d(z) − t), so without
//    translation Z = (I/b)·z, and with it every depth beyond z0 diverges.
//  - "screen": one screen of width S at distance D shows both images (the A px across S):
//    Z = I·D/(I − p·S/A), diverging where the uncrossed parallax p·S/A reaches I.
// Lengths in one unit throughout; depths along the cameras' (and the viewer's) optical axis.
#pragma once

#include <optional>
#include <string_view>
#include <vector>
#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class Viewer { kNone, kHmd, kScreen };
inline constexpr EnumNames<Viewer, 3> kViewerNames = {{{Viewer::kNone, "none"}, {Viewer::kHmd, "hmd"}, {Viewer::kScreen, "screen"}}};
std::string_view ViewerName(Viewer viewer);  // "none", "hmd", "screen"

struct DisplayPlanInput {
  double baseline = 0;                 // b, length unit, > 0
  std::optional<double> z0;            // zero-parallax depth; none: no translation (zero parallax at infinity)
  int display_width = 0;               // A, px
  // The capture's horizontal focal length in px, or its horizontal field of view across the captured
  // width (seed 000's θ, radians): exactly one of the two.
  std::optional<double> focal_px;
  std::optional<double> hfov_rad;
  std::optional<int> capture_width;    // the camera's A′, to check against the need
  std::vector<double> depths;          // where to tabulate, length unit, > 0
  Viewer viewer = Viewer::kNone;
  double ipd = 0;                      // I, length unit (viewer ≠ none)
  double screen_width = 0;             // S, length unit (screen viewer)
  double viewing_distance = 0;         // D, length unit (screen viewer)
};

struct DepthRow {
  double depth = 0;
  double disparity_px = 0;  // d(z) = f·b/z, crossed, as captured
  double parallax_px = 0;   // p(z) = t − d(z) on the display, positive = uncrossed = behind the screen
  int side = 0;             // −1 in front of the screen (crossed), 0 on it, +1 behind
  std::optional<double> perceived_depth;  // viewer ≠ none; nullopt where the eyes' rays diverge
};

struct DisplayPlan {
  double focal_px = 0;             // f used
  double translation_px = 0;       // t = f·b/z0 (0 without z0)
  double capture_width_needed = 0;  // A + t, px (not rounded)
  std::optional<int> capture_margin_px;  // capture_width − ⌈A + t⌉ when capture_width is given (< 0: too narrow)
  // Depths beyond which the viewer's rays diverge (no fusion): hmd with translation z0; screen
  // where p·S/A = I. nullopt when no depth diverges (or no viewer).
  std::optional<double> diverges_beyond;
  std::vector<DepthRow> rows;
};

// Throws InputError for inputs outside their domain (non-positive lengths, hfov outside (0°, 180°),
// both or neither of focal_px and hfov_rad, a viewer without its sizes, and a z0 nearer than
// b/(2·tan(θ/2)), where Eq. 6 has no solution: the translation would exceed the capture).
DisplayPlan PlanDisplay(const DisplayPlanInput& input);

// The formulas PlanDisplay tabulates. Eq. 3: d = f·b/z.
double CrossedDisparityPx(double focal_px, double baseline, double depth);
// Z = I·f/(d − t); nullopt where d ≤ t (the rays are parallel or diverge).
std::optional<double> PerceivedDepthHmd(double ipd, double focal_px, double disparity_px, double translation_px);
// Z = I·D/(I − P), P the uncrossed screen parallax in length units; nullopt where P ≥ I.
std::optional<double> PerceivedDepthScreen(double ipd, double viewing_distance, double screen_parallax);

}  // namespace vstcal
