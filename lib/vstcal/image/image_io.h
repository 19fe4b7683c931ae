// Reading the images a capture is made of: the bytes, checks that tell a user what is wrong with
// a file (empty, truncated, too large, not an image), and decoding to 8-bit grey (colour images
// are converted with OpenCV's weights 0.299 R + 0.587 G + 0.114 B).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>

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

// The width and height a PNG's or JPEG's header states, read from the file's first 256 KiB
// without decoding (nullopt for other formats, unreadable files and headers not in that reach):
// lets a capture refuse images of mixed sizes before it searches any of them.
std::optional<std::pair<int, int>> ReadImageHeaderSize(const std::filesystem::path& path);

// Writes nothing; PNG bytes of a grey image are capture/target_drawing.h's EncodePng.

}  // namespace vstcal
