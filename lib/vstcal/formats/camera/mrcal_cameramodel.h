// mrcal's .cameramodel text format (docs/formats.md#mrcal): a Python dict with 'lensmodel',
// 'intrinsics' = [fx, fy, cx, cy, distortion...], 'extrinsics' = rt_cam_ref and 'imagersize'.
//
// vstcal reads and writes LENSMODEL_PINHOLE and LENSMODEL_OPENCV4/5/8 (docs/conventions.md#
// distortion). The writer is vstcal's own: libmrcal 2.2's writer prints "%f", which turns a
// coefficient of 1e-7 into 0; this one prints every double in its shortest exact form.
//
// rt_cam_ref is (r, t) with x_cam = R(r)·x_ref + t (mrcal's T_AB maps B to A): it is
// camera_from_world with a rotation vector in radians. All-zero extrinsics, mrcal's "this camera
// is the reference", mean no pose. mrcal files carry no length unit: the writer adds a
// 'vstcal_length_unit' key (mrcal ignores unknown keys) and the reader honours it.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "vstcal/formats/camera/peer_formats.h"

namespace vstcal {

// The mrcal lens-model names vstcal reads and writes, with their OpenCV distortion length.
struct MrcalLensModel {
  std::string_view name;  // "LENSMODEL_OPENCV5"
  int opencv_length;      // 0 for LENSMODEL_PINHOLE
};
inline constexpr MrcalLensModel kMrcalLensModels[] = {
    {"LENSMODEL_PINHOLE", 0}, {"LENSMODEL_OPENCV4", 4}, {"LENSMODEL_OPENCV5", 5}, {"LENSMODEL_OPENCV8", 8}};

// Reads and validates a file; throws InputError "<file>: <field>: <what>; <fix>" (or
// "<file>: line L, column C: ..." for bad syntax). The unit of the translation is `length_unit`
// when given (it must agree with a 'vstcal_length_unit' key), else the file's
// 'vstcal_length_unit', else mm: a note says so when the translation is not zero. method is "mrcal".
ImportedCamera ReadMrcalCameramodel(const std::filesystem::path& path, std::optional<LengthUnit> length_unit);
ImportedCamera MrcalCameramodelFromText(std::string_view text, const std::string& name,
                                        std::optional<LengthUnit> length_unit);

struct MrcalWriteOptions {
  // One of kMrcalLensModels. Default: LENSMODEL_PINHOLE for "none", and otherwise the shortest
  // OpenCV model that reads back as the camera's own (OPENCV4 for "radial-tangential" with
  // k3 = 0 exactly, OPENCV5 otherwise, OPENCV8 for "rational").
  std::optional<std::string> lensmodel;
  // Unit of the written translation (converted from the camera's); default: the camera's.
  std::optional<LengthUnit> length_unit;
  // The rotation vector the pose was read with (ImportedCamera::rotation_vector): written as it is
  // while it still gives the camera's R exactly, so that a file read and written again keeps its
  // bits; otherwise the rotation vector of R.
  std::optional<Eigen::Vector3d> rotation_vector;
};

// The file's text. Refuses (InputError naming `source`) a camera with skew, and a lens model
// that would drop a non-zero coefficient (LENSMODEL_OPENCV4 for k3 ≠ 0). The provenance goes in
// a comment.
ExportedCamera MrcalCameramodelText(const CalibratedCamera& camera, std::string_view source,
                                    const MrcalWriteOptions& options, const Provenance& provenance);

}  // namespace vstcal
