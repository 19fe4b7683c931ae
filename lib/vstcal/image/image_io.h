// Reading the images a capture is made of: the bytes, checks that tell a user what is wrong with
// a file (empty, truncated, too large, not an image), and decoding to 8-bit grey (colour images
// are converted with OpenCV's weights 0.299 R + 0.587 G + 0.114 B).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "vstcal/image/image.h"

namespace vstcal {

inline constexpr double kMaxImageMegapixels = 100;

struct LoadedImage {
  GrayImage image;
  std::string problem;  // empty when the image was read; else why not, e.g. "truncated PNG (no IEND chunk)"
  uint64_t digest = 0;  // FNV-1a of the file's bytes: identical files have equal digests
};

// Never throws for what the file holds: a missing, empty, truncated, oversized (more than
// kMaxImageMegapixels) or undecodable file comes back with `problem` set (one phrase, no file
// name). PNG must end with its IEND chunk and JPEG with its EOI marker; their sizes are read from
// the header before anything is decoded.
LoadedImage LoadImageFile(const std::filesystem::path& path);
LoadedImage DecodeImage(const std::string& bytes);

// Writes nothing; PNG bytes of a grey image are capture/target_drawing.h's EncodePng.

}  // namespace vstcal
