// ROS camera_info YAML, as ROS's camera_calibration writes it and camera_info_manager reads it
// (the calibration fields of sensor_msgs/CameraInfo): image_width, image_height, camera_name,
// camera_matrix (K), distortion_model, distortion_coefficients (D), rectification_matrix (R) and
// projection_matrix (P), each matrix as {rows, cols, data}. docs/formats.md#ros-camera-info.
//
// distortion_model: "plumb_bob" (5: k1, k2, t1, t2, k3) is vstcal's "radial-tangential",
// "rational_polynomial" (8: k1, k2, t1, t2, k3, k4, k5, k6) its "rational", "equidistant" (4:
// image_geometry's cv::fisheye k1, k2, k3, k4) its "kannala-brandt". The file holds no lengths
// except a stereo right camera's P[0][3] = −fx'·B, B in metres (ROS's unit).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/scene/calibrated_camera.h"

namespace vstcal {

// A camera_info file's content: the raw camera (name = camera_name, may be empty) and the
// rectification of a stereo camera (R = I and P = [K | 0] for a single camera).
struct RosCameraInfo {
  CalibratedCamera camera;
  Eigen::Matrix3d rectification = Eigen::Matrix3d::Identity();
  Matrix34d projection = Matrix34d::Zero();
};

// Reads and validates; throws InputError "<file>: <field>: <what>; <fix>". Every field but
// camera_name is required. `length_unit` is recorded in the camera (the file has no lengths).
RosCameraInfo RosCameraInfoFromText(const std::string& text, const std::string& name, LengthUnit length_unit);
// The camera of a camera_info file, method "ros". A rectification (R ≠ I or P ≠ [K | 0]) is not
// kept, and a note says so: camera@1 holds the raw camera.
ImportedCamera ReadRosCameraInfo(const std::filesystem::path& path, LengthUnit length_unit);
ImportedCamera ImportRosCameraInfo(const RosCameraInfo& info, const std::string& name);

// The file's text: numbers in their shortest exact form, the provenance in a comment. Refuses
// skew (RefuseSkew: ROS's image_geometry works through OpenCV, which ignores it). A camera
// without distortion is written as plumb_bob with five zeros (ROS has no name for none).
ExportedCamera RosCameraInfoText(const RosCameraInfo& info, std::string_view source, const Provenance& provenance);
// A single camera: R = I, P = [K | 0] (sensor_msgs/CameraInfo's rule for a monocular camera).
ExportedCamera RosCameraInfoText(const CalibratedCamera& camera, std::string_view source, const Provenance& provenance);

}  // namespace vstcal
