// vstcal/handeye@1 (docs/formats.md#handeye): what calib-handeye measured — hmd_from_camera,
// tracker_from_board, the time offset, their joint covariance with named parameters, the fit, the
// closed-form start — for err-sim's chain and for the user.
#pragma once

#include <optional>

#include "vstcal/core/units.h"
#include "vstcal/handeye/bootstrap.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/handeye/tracker_noise.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// A rig's solve (docs/math/handeye.md#rig): the stereo@1 file whose right_from_left was held, the
// right camera's corners file and how its views were paired with the left camera's.
struct HandEyeRigFile {
  std::string file, right_corners, pairing;
};

// `rig`: written as the file's "rig" (with right_from_left and the right camera's counts).
// `bootstrap`: written as the file's "bootstrap", beside the first-order `covariance` (which stays
// what readers take).
OrderedJson HandEyeToJson(const HandEyeSolution& solution, LengthUnit length_unit, const Provenance& provenance,
                          const HandEyeRigFile* rig = nullptr, const HandEyeBootstrap* bootstrap = nullptr);

// The same as OpenCV FileStorage YAML, for a user's OpenCV code: R_cam2gripper / t_cam2gripper
// (hmd_from_camera, OpenCV's calibrateHandEye names), R_target2base / t_target2base
// (tracker_from_board), time_offset, each with its matrix and the length unit in a comment.
std::string HandEyeOpenCvYaml(const HandEyeSolution& solution, LengthUnit length_unit, const Provenance& provenance);

// vstcal/tracker-noise@1 (docs/formats.md#tracker-noise): calib-handeye noise's estimate.
OrderedJson TrackerNoiseToJson(const TrackerNoise& noise, LengthUnit length_unit, const Provenance& provenance);

// A handeye@1 file as err-sim's chain reads it: length unit, X, Z, δ and, when the file has one,
// the covariance (`covariance` empty and `names` empty for a truth written by calib-synth).
// InputError naming the file and field for a malformed file.
struct HandEyeMeasurement {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  HandEyeSolution solution;  // hmd_from_camera, tracker_from_board, time_offset, covariance, names
  // The file's `bootstrap.time_offset_sigma_s` (calib-handeye solve --bootstrap), when it has one:
  // δ's σ where the first-order one is off with few views (docs/math/handeye.md#delta-bootstrap).
  std::optional<double> bootstrap_time_offset_sigma;
};
HandEyeMeasurement HandEyeFromJson(const JsonDocument& doc);

// A tracker-noise@1 file: the length unit and the estimate (mean pose, σ's and their intervals).
struct TrackerNoiseMeasurement {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  TrackerNoise noise;
};
TrackerNoiseMeasurement TrackerNoiseFromJson(const JsonDocument& doc);

}  // namespace vstcal
