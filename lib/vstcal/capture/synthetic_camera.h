// The camera calib-synth simulates, built from what one knows of a lens: the image size, a focal
// length or the horizontal field of view, the principal point, the angle between the pixel axes
// (seed 001 Eq. 5: s = −fx·cot θ) and Brown–Conrady coefficients in OpenCV's order.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/camera/camera.h"

namespace vstcal {

struct SyntheticCameraSpec {
  ImageSize image_size;             // px, each side 1 … limits::kMaxImageSide
  std::optional<double> fx;         // K[0][0], px; exactly one of fx and hfov_deg
  std::optional<double> hfov_deg;   // field of view across the whole width, (0, 180) degrees
  std::optional<double> fy;         // K[1][1], px (default fx)
  std::optional<double> cx, cy;     // principal point, px (default the image centre ((W − 1)/2, (H − 1)/2))
  double skew_deg = 90;             // θ in (0, 180); 90 = no skew
  std::vector<double> distortion;   // OpenCV's order: none, 5 (radial-tangential) or 8 (rational)
};

// K = [[fx, −fx·cot θ, cx], [0, fy, cy], [0, 0, 1]] with fx from the field of view when asked:
// fx = (W/2) / tan(hfov/2) (FocalFromHorizontalFov). Throws InputError naming calib-synth's flag
// (--image-size, --fx, --hfov-deg, --fy, --cx, --cy, --skew-deg, --distortion) for an impossible
// or non-finite value, or a focal length or principal point beyond limits::kMaxSyntheticScale.
Camera MakeSyntheticCamera(const SyntheticCameraSpec& spec);

// A ground-truth camera as calib-synth writes it: `camera`, named `name`, in `unit`, with method
// "synthetic"; the pose (or the board poses) and the fit are added by VolumeTruthCamera and
// PlanarViewsTruthCamera.
CalibratedCamera SyntheticTruth(const Camera& camera, const std::string& name, LengthUnit unit);

}  // namespace vstcal
