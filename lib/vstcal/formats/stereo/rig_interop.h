// A stereo rig in ROS's and Kalibr's files (docs/formats.md#ros-camera-info,
// docs/formats.md#kalibr-camchain): a Kalibr chain of two cameras is a rig both ways; ROS gets a
// left and a right camera_info with the rig's rectification. Both peers measure lengths in metres.
#pragma once

#include <string_view>
#include <utility>
#include <vector>

#include "vstcal/formats/camera/kalibr_camchain.h"
#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

// The rig of a camchain of exactly two cameras (cam0 left, cam1 right, right_from_left =
// cam1's T_cn_cnm1), in metres, method "kalibr". Throws InputError naming `name` for a chain of
// another length (a stereo@1 rig holds two cameras) and for a baseline of 0. `notes` (may be null)
// get the rostopics, which stereo@1 does not hold.
StereoRig RigFromKalibr(const std::vector<KalibrCamera>& cameras, const std::string& name,
                        std::vector<std::string>* notes = nullptr);
// The camchain of a rig: T_cn_cnm1 = right_from_left with t in metres (exact for a rig in m).
// Notes say what it does not hold (names, covariance, fit, rectification).
ExportedCamera KalibrCamchainText(const StereoRig& rig, std::string_view source, const Provenance& provenance);

// The left and right camera_info of a rig: R = R1, R2 and P = P1, P2 of the rig's rectification,
// or of Rectify(rig, {}) (OpenCV's defaults) when it has none; P's last column in metres
// (the right camera's P[0][3] = −fx'·B, B in metres, as ROS's image_geometry reads it).
std::pair<ExportedCamera, ExportedCamera> RosStereoTexts(const StereoRig& rig, std::string_view source,
                                                         const Provenance& provenance);

}  // namespace vstcal
