// A tracker's log for hand-eye calibration (docs/formats.md#poses): vstcal/poses@1 (JSON) or the
// TUM trajectory text format robotics tools write ("timestamp tx ty tz qx qy qz qw" a line, '#'
// comments), each report the body's pose in the tracker's frame, tracker_from_hmd.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "vstcal/core/units.h"
#include "vstcal/handeye/refine.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

struct PoseLog {
  LengthUnit length_unit = LengthUnit::kMetre;
  std::vector<TrackedPose> poses;  // strictly increasing in time
};

// At most this many reports (a 1 kHz tracker for 16 minutes).
inline constexpr size_t kMaxPoseReports = 1'000'000;

// A .json file is poses@1; anything else is TUM text, whose translations are in `tum_unit` (TUM's
// own is the metre). Throws InputError naming the file and the line or field: a malformed line, a
// non-finite number, a quaternion whose norm is not 1 to 1e-3, times not strictly increasing,
// fewer than 2 reports, more than kMaxPoseReports.
PoseLog ReadPoseLog(const std::filesystem::path& path, LengthUnit tum_unit = LengthUnit::kMetre);
PoseLog PoseLogFromTum(const std::string& text, const std::string& name, LengthUnit unit);
PoseLog PoseLogFromJson(const JsonDocument& doc);
OrderedJson PoseLogToJson(const PoseLog& log, const Provenance& provenance);
// TUM text in the log's own unit, %.17g: read back with that unit, the same numbers.
std::string PoseLogToTum(const PoseLog& log);

// The log with its translations in `unit`.
PoseLog InUnit(PoseLog log, LengthUnit unit);

}  // namespace vstcal
