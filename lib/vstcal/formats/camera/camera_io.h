// vstcal/camera@1 reader and writer (docs/formats.md#camera).
#pragma once

#include <filesystem>
#include <optional>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {

// Reads and validates a camera file. K is authoritative; `intrinsics` and `P`, when present, must
// agree with it (relative 1e-6; P's 3×3 block and last column each against their own scale, up
// to P's free sign); R must be a rotation to 1e-6 (it is then re-orthonormalized).
CalibratedCamera ReadCamera(const std::filesystem::path& path);
CalibratedCamera CameraFromJson(const JsonDocument& doc);
// A camera@1 object inside another file (a stereo@1 rig's "left"); fields are reported under the
// node's path ("left.K").
CalibratedCamera CameraFromNode(const JsonNode& node);

// The camera@1 object. The members of `extra` (e.g. a solver's diagnostics) are inserted before
// the closing provenance.
OrderedJson CameraToJson(const CalibratedCamera& camera, const Provenance& provenance,
                         const OrderedJson& extra = OrderedJson::object());
OrderedJson FitToJson(const Fit& fit);
// `{hull, vertices, facets}`: "ok" or why the calibration points have no convex hull, and its size
// (0 without one). The camera file's `fit.volume` and the reports' `volume` alike.
OrderedJson MeasuredVolumeToJson(const MeasuredVolume& volume);

// Why K cannot be a camera matrix (upper triangular, K[2][2] = 1, fx > 0, fy > 0), or nullopt.
// Every format's reader applies it, so that K is refused in the same words everywhere.
std::optional<FieldProblem> CameraMatrixProblem(const Eigen::Matrix3d& K);

// Why a pose cannot go with K, or nullopt: P = K [R | t] overflows a double (a translation near
// 1e308 / fx), so the camera could not be written back. Every format's reader applies it.
std::optional<FieldProblem> PoseProblem(const Eigen::Matrix3d& K, const Rigid3d& camera_from_world);

// The "distortion" object alone, and a Camera (K, distortion, image size) from a JSON object that
// has image_size, K and distortion (used by other formats that embed a camera).
OrderedJson DistortionToJson(const Camera& camera);
Camera ReadCameraIntrinsics(const JsonNode& node);

// The poses a camera file has, which a covariance's pose tangents may name.
struct CovariancePoses {
  bool camera_from_world = false;
  size_t num_views = 0;
};

// A "covariance" object {"parameters": [names], "matrix": [[…]]}: names are `camera`'s lens
// parameters or pose tangents ("camera_from_world.rx", "views[2].camera_from_board.tz"), each once
// and, given `poses`, each tangent of a pose the file has (without `poses`, for an inline camera
// that has no poses, any well-formed tangent name is accepted: its readers ignore them); the
// matrix square, symmetric to 1e-9 relative, with a non-negative diagonal and positive
// semi-definite (smallest eigenvalue ≥ −1e-9 × the largest |eigenvalue|).
ParameterCovariance ReadCovariance(const JsonNode& node, const Camera& camera, const std::optional<CovariancePoses>& poses);
// The "matrix" of a covariance object whose parameter `names` are already checked: as many rows
// of as many finite numbers, symmetric, non-negative diagonal, positive semi-definite (the rules
// above), for every format that writes a covariance.
ParameterCovariance ReadCovarianceMatrix(const JsonNode& node, std::vector<std::string> names);

}  // namespace vstcal
