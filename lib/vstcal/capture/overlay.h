// A picture of what detect found: the image in grey with every corner circled and its id written,
// the board's X axis (corner 0 → its row neighbour) in red and Y axis in green, so a user sees at
// a glance that the numbering runs the same way in every view.
#pragma once

#include <string>

#include "vstcal/capture/detect.h"
#include "vstcal/image/image.h"
#include "vstcal/capture/target.h"

namespace vstcal {

// PNG bytes (colour) of the overlay.
std::string OverlayPng(const GrayImage& image, const Target& target, const Detection& detection);

}  // namespace vstcal
