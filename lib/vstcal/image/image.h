// An 8-bit grey image as the capture module passes it around: row-major, pixel (u, v) at
// v·width + u, its centre at (u, v) in vstcal's pixel convention (docs/conventions.md: (0, 0) is
// the centre of the top-left pixel). No OpenCV type appears in the module's headers.
#pragma once

#include <cstdint>
#include <vector>

namespace vstcal {

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // width · height grey levels

  GrayImage() = default;
  GrayImage(int w, int h, uint8_t fill = 0) : width(w), height(h), pixels(static_cast<size_t>(w) * h, fill) {}
  uint8_t at(int u, int v) const { return pixels[static_cast<size_t>(v) * width + u]; }
  uint8_t& at(int u, int v) { return pixels[static_cast<size_t>(v) * width + u]; }
  bool empty() const { return pixels.empty(); }
};

}  // namespace vstcal
