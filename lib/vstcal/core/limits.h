// The documented maxima of every input and every size flag (docs/reliability.md#limits). Beyond
// one, a reader or a tool refuses with a one-line message (exit code 2) before it allocates or
// loops in proportion to the value, so that no input can exhaust the machine. Declared once here;
// the docs quote these numbers.
#pragma once

#include <cstddef>

namespace vstcal::limits {

// Bytes of one input file (JSON, OpenCV YAML, mrcal .cameramodel): room for a correspondences
// file of kMaxPoints as the writer lays it out (about 135 bytes a point) twice over.
inline constexpr size_t kMaxInputFileBytes = size_t{256} << 20;  // 256 MiB

// Bytes of an OpenCV YAML file: cv::FileStorage holds every value as a node of its own (tens of
// bytes each); a camera file takes a few kilobytes, with per-view extrinsics and image points a
// few megabytes.
inline constexpr size_t kMaxOpenCvYamlBytes = size_t{16} << 20;  // 16 MiB

// Nesting depth of a JSON document, of an OpenCV YAML file (estimated from its indentation,
// block indicators and brackets, which bound the depth from above) and of a .cameramodel
// literal. The formats need 6 levels at most; parsers recurse, and 50,000 levels overflow the stack.
inline constexpr int kMaxNesting = 64;

// Values (numbers, strings, arrays, objects, ...) in one JSON document: bounds the parsed tree,
// whose memory is ~16–80 bytes a value whatever the text.
inline constexpr size_t kMaxJsonValues = size_t{16} << 20;  // 16,777,216
// Values in one .cameramodel literal (its parse tree takes ~120 bytes a value).
inline constexpr size_t kMaxLiteralValues = size_t{1} << 20;  // 1,048,576

// An image side in pixels (image_size, image_width/height, imagersize, --image-size).
inline constexpr int kMaxImageSide = 1'000'000;

// Calibration points in one correspondences file (all views), and views in one file or run.
inline constexpr size_t kMaxPoints = 1'000'000;
inline constexpr size_t kMaxViews = 10'000;
// Cells of a projection-uncertainty grid (--grid-size COLSxROWS): each costs one Jacobian
// and one 2×2 eigen decomposition, and 80 bytes of output.
inline constexpr size_t kMaxGridCells = 1'000'000;

// Lengths (in the length unit) and focal lengths (px) of a synthetic scene (calib-synth): within
// ±1e9, K·[R | t] and the squares the solvers form stay far from overflow.
inline constexpr double kMaxSyntheticScale = 1e9;

}  // namespace vstcal::limits
