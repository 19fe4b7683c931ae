// OpenCV FileStorage YAML, as OpenCV's calibration sample (samples/cpp/calibration.cpp) writes a
// camera: image_width, image_height, camera_matrix (3×3 !!opencv-matrix) and
// distortion_coefficients (N×1 or 1×N, N = 4, 5 or 8). docs/formats.md#opencv-yaml.
//
// cv::FileStorage parses and prints the text: OpenCV is the peer, so what it accepts is what
// OpenCV users have. It prints doubles with 17 significant digits, so a camera survives the
// round trip bit for bit. The format holds intrinsics only: no pose, no length unit.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "vstcal/formats/camera/peer_formats.h"

namespace vstcal {

// Reads and validates a file; throws InputError "<file>: <field>: <what>; <fix>". N = 4 gives
// "radial-tangential" with k3 = 0, 5 "radial-tangential", 8 "rational"; no distortion_coefficients
// (or an empty matrix) gives "none". N = 12 and 14 (thin prism, tilted sensor) are refused. A
// camera_matrix with K[0][1] ≠ 0 is kept, with a note (OpenCV itself ignores that entry).
// `distortion_model: fisheye` (the only value it may have) marks cv::fisheye's k1, k2, k3, k4:
// exactly 4 coefficients, read as "kannala-brandt". Without it 4 coefficients are
// calibrateCamera's k1, k2, p1, p2, with a note saying so.
// `length_unit` is recorded in the camera: the file has no lengths. method is "opencv".
ImportedCamera ReadOpenCvYaml(const std::filesystem::path& path, LengthUnit length_unit);
ImportedCamera OpenCvYamlFromText(const std::string& text, const std::string& name, LengthUnit length_unit);

// The file's text, through cv::FileStorage. Refuses a camera with skew (RefuseSkew; `source`
// names the camera in the message). The distortion is written with the model's own count (5 or
// 8); "none" writes no distortion_coefficients; "kannala-brandt" writes its 4 and
// distortion_model: fisheye. The provenance goes in a comment. A pose cannot
// be written: a note says so.
ExportedCamera OpenCvYamlText(const CalibratedCamera& camera, std::string_view source, const Provenance& provenance);

}  // namespace vstcal
