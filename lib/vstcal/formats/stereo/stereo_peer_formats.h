// A stereo rig written for OpenCV and for mrcal (docs/formats.md#stereo-export).
//
// OpenCV: one FileStorage YAML with the names of OpenCV's stereo sample (samples/cpp/stereo_calib.cpp)
// and of stereoCalibrate's outputs: M1, D1, M2, D2 (left and right K and distortion), R, T
// (right_from_left: x_right = R x_left + T), E = [T]× R and F = M2⁻ᵀ E M1⁻¹ scaled to F[2][2] = 1
// (x_rightᵀ F x_left = 0 for undistorted pixels), and with a rectification R1, R2, P1, P2, Q and
// the valid rectangles. mrcal: two .cameramodel files whose extrinsics share one reference frame,
// the left camera (the left's rt_cam_ref is zero, the right's is right_from_left).
#pragma once

#include <optional>
#include <string_view>
#include <utility>

#include "vstcal/formats/camera/mrcal_cameramodel.h"
#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

// The YAML text. Refuses (InputError naming `source`) a camera with skew, and cameras of different
// image sizes (OpenCV's stereo functions take one size; the file has one image_width and
// image_height). Notes say what the format does not hold (names, covariance, fit).
ExportedCamera OpenCvStereoYamlText(const StereoRig& rig, std::string_view source, const Provenance& provenance);

// The left and right .cameramodel texts (MrcalCameramodelText's rules for each camera).
std::pair<ExportedCamera, ExportedCamera> MrcalStereoTexts(const StereoRig& rig, std::string_view source,
                                                          const MrcalWriteOptions& options, const Provenance& provenance);

}  // namespace vstcal
