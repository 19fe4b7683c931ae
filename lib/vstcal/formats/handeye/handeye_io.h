// vstcal/handeye@1 (docs/formats.md#handeye): what calib-handeye measured — hmd_from_camera,
// tracker_from_board, the time offset, their joint covariance with named parameters, the fit, the
// closed-form start — for err-sim's chain and for the user.
#pragma once

#include "vstcal/core/units.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/tracker_noise.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

OrderedJson HandEyeToJson(const HandEyeSolution& solution, LengthUnit length_unit, const Provenance& provenance);

// The same as OpenCV FileStorage YAML, for a user's OpenCV code: R_cam2gripper / t_cam2gripper
// (hmd_from_camera, OpenCV's calibrateHandEye names), R_target2base / t_target2base
// (tracker_from_board), time_offset, each with its matrix and the length unit in a comment.
std::string HandEyeOpenCvYaml(const HandEyeSolution& solution, LengthUnit length_unit, const Provenance& provenance);

// vstcal/tracker-noise@1 (docs/formats.md#tracker-noise): calib-handeye noise's estimate.
OrderedJson TrackerNoiseToJson(const TrackerNoise& noise, LengthUnit length_unit, const Provenance& provenance);

}  // namespace vstcal
