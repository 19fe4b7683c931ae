// vstcal/stereo@1 reader and writer (docs/formats.md#stereo).
#pragma once

#include <filesystem>

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/scene/stereo_rig.h"

namespace vstcal {

// Reads and validates a rig; throws InputError "<file>: <field>: <what>; <fix>". Beyond types:
// left and right are camera@1 objects holding intrinsics only, in the rig's length unit;
// right_from_left's R a rotation to 1e-6 and its cameras apart; baseline = |t| to 1e-6 relative;
// a covariance over exactly the six tangents of right_from_left (checked as a camera's); a
// rectification whose rotations align the two cameras and put the baseline on one image axis,
// whose P and Q agree with them (docs/formats.md#stereo lists every rule).
StereoRig ReadStereoRig(const std::filesystem::path& path);
StereoRig StereoRigFromJson(const JsonDocument& doc);
// Whether the document says it is a vstcal/stereo@1 file (its "format"), for tools that take a rig
// or a camera in one place.
bool IsStereoRigDocument(const JsonDocument& doc);

// A covariance {"parameters", "matrix"} over exactly the six tangents of right_from_left
// (RelativePoseTangentNames, any order; ω radians, ρ length unit), checked as a camera's: the
// stereo@1 field, and a vst-chain's camera_extrinsic.right.covariance.
ParameterCovariance ReadRelativePoseCovariance(const JsonNode& node);

// A joint covariance {"parameters", "matrix"} of a rig's errors: "left.<lens parameter>" and
// "right.<lens parameter>" of each camera's lens model (fx, fy, cx, cy, s, distortion terms) and
// right_from_left's tangents (RelativePoseTangentNames), each at most once, any subset and order;
// the matrix checked as a camera's (square, symmetric, PSD). The stereo@1 field (whose blocks must
// also be the marginals beside it) and a vst-chain's inline joint_covariance.
ParameterCovariance ReadJointCovariance(const JsonNode& node, const AnyLensModel& left, const AnyLensModel& right);

// The stereo@1 object: a file written, read and written again is the same bytes.
OrderedJson StereoRigToJson(const StereoRig& rig, const Provenance& provenance);

}  // namespace vstcal
