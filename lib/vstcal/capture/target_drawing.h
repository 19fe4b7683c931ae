// Printable files of a target: an SVG at exact physical size and a PNG at a given resolution,
// both drawn from the target's one Pattern (target_pattern.h).
#pragma once

#include <string>

#include "vstcal/image/image.h"
#include "vstcal/capture/target.h"

namespace vstcal {

// An SVG whose width and height are the sheet's size in millimetres, with a viewBox in
// millimetres: printed at 100 % (no "fit to page"), every square has its stated size. A scale bar
// (group id "scale-bar", its length in data-length-mm, ticked every tenth) in the bottom margin
// lets a ruler check the print.
std::string TargetSvg(const Target& target);

// The sheet rasterised at `dpi` pixels per inch, each pixel's grey the exact fraction of its area
// that is white (255 white … 0 black). The pixel pitch is exactly 25.4 mm / dpi; the image is
// rounded up to whole pixels (white beyond the sheet). Throws InputError naming --dpi when the
// image would exceed 200 megapixels.
GrayImage RasterizeTarget(const Target& target, double dpi);

// PNG bytes of a grey image, with a pHYs chunk stating `dpi` so that printers and viewers know its
// physical size (0: no pHYs).
std::string EncodePng(const GrayImage& image, double dpi = 0);

}  // namespace vstcal
