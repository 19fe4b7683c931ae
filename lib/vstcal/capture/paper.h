// Paper sizes and fitting a target to a sheet of paper (docs/tools/calib-capture.md#paper).
//
// A target's sheet (its pattern and white margin, target.h's SheetExtent) is affine in its size s
// (the square side, or the tag side): with the defaults of calib-capture target the margin is one
// square (or the tag gap, a quarter tag), so the sheet is a multiple of s; a margin, tag gap or
// marker given as a length stays fixed. Fitting solves the two inequalities of each orientation
// for s, keeps the orientation with the larger s (portrait on a tie) and rounds s down to a
// printable step (0.1 mm, 0.01 cm, 0.0001 m, 0.001 in).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "vstcal/capture/target.h"

namespace vstcal {

// A sheet of paper, portrait: width ≤ height, in millimetres.
struct Paper {
  std::string name;  // "A4", "Letter", "A3", or "210 × 297 mm" for a custom size
  double width_mm = 0;
  double height_mm = 0;
};

// A4 (210 × 297), Letter (215.9 × 279.4), A3 (297 × 420): the sizes the warning names, smallest first.
std::span<const Paper> StandardPapers();

// "a4", "letter", "a3" (any case) or "WxH" in millimetres (e.g. "250x350"); nullopt when the text
// is none of these or a size is not a positive finite number.
std::optional<Paper> PaperFromName(std::string_view text);

// True when a sheet of w × h mm fits on `paper` in either orientation.
bool SheetFitsPaper(double w_mm, double h_mm, const Paper& paper);

// The smallest of StandardPapers() a sheet of w × h mm fits on; nullopt when larger than A3.
std::optional<Paper> SmallestStandardPaper(double w_mm, double h_mm);

// Lengths of a target given outright; an unset one follows the size as calib-capture's defaults
// do: margin = one square (chessboard, charuco) or the tag gap (aprilgrid: tag_spacing × tag
// size); tag gap = tag size / 4; marker = 0.75 × square size.
struct TargetLengths {
  std::optional<double> margin, tag_gap, marker_size;
};

// `target` with its size (square_size, or tag_size for an apriltag-grid or aprilgrid) set to `size` and the
// unset lengths derived from it.
Target WithSize(Target target, double size, const TargetLengths& given);

struct PaperFit {
  double size = 0;          // the largest printable square (tag) size, in the target's unit
  bool landscape = false;   // the paper turned: its long side across the sheet (along X)
  double sheet_width_mm = 0, sheet_height_mm = 0;  // the sheet at that size
};
// The largest size whose sheet fits on `paper` (see above); nullopt when no positive size fits
// (the lengths given outright already fill the paper).
std::optional<PaperFit> FitToPaper(const Target& target, const TargetLengths& given, const Paper& paper);

}  // namespace vstcal
