// Kalibr's camchain.yaml (kalibr_calibrate_cameras' output; the Kalibr wiki's "YAML formats"): one
// map per camera, cam0, cam1, …, each with camera_model, intrinsics [fu, fv, pu, pv],
// distortion_model, distortion_coeffs, resolution [w, h], optionally rostopic and cam_overlaps,
// and for camN (N ≥ 1) T_cn_cnm1, the 4×4 transform from cam(N−1)'s frame to camN's, in metres.
// docs/formats.md#kalibr-camchain.
//
// camera_model "pinhole" only (omni, eucm, ds have no vstcal model). distortion_model "radtan"
// (k1, k2, r1, r2) is vstcal's "radial-tangential" with k3 = 0, "none" (no coefficients) its
// "none"; "equidistant" (k1…k4) its "kannala-brandt"; "fov" has no vstcal lens model and is
// refused by name.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/scene/calibrated_camera.h"

namespace vstcal {

struct KalibrCamera {
  CalibratedCamera camera;                  // length_unit m, method "kalibr", no name
  std::optional<Rigid3d> cam_from_previous;  // T_cn_cnm1 (cam1 and later), metres
  std::string rostopic;                     // empty when absent
};

// Reads and validates every camera; throws InputError "<file>: <field>: <what>; <fix>". The keys
// cam0 … cam(N−1) must be consecutive; other top-level keys and per-camera keys other than the
// ones above (T_cam_imu, timeshift_cam_imu, …) are ignored, and `notes` name them. R of T_cn_cnm1
// must be a rotation to 1e-6 (kept bit for bit when it is one to 1e-12, else the nearest one).
std::vector<KalibrCamera> KalibrCamchainFromText(const std::string& text, const std::string& name,
                                                 std::vector<std::string>* notes);

// The text of a chain of cameras (the first's cam_from_previous is ignored), with the provenance in
// a comment. Refuses skew, a radial-tangential k3 ≠ 0 and the rational model (radtan has four
// coefficients), naming `source`. A camera's pose and name are not written (notes say so).
ExportedCamera KalibrCamchainText(const std::vector<KalibrCamera>& cameras, std::string_view source,
                                  const Provenance& provenance);

}  // namespace vstcal
