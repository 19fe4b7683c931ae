#include "vstcal/formats/handeye/pose_log_io.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

constexpr const char* kFormat = "vstcal/poses@1";

// |q| must be 1 to this: a log whose quaternions are not unit was written wrongly, and normalising
// it silently would hide that.
constexpr double kUnitTolerance = 1e-3;

[[noreturn]] void FailLine(const std::string& name, size_t line, const std::string& reason, const std::string& fix) {
  throw InputError(name + ": line " + std::to_string(line) + ": " + reason + "; " + fix);
}

// Why the last report cannot follow the one before it (times must increase strictly), or empty.
std::string OrderProblem(const std::vector<TrackedPose>& poses) {
  if (poses.size() < 2 || poses.back().time > poses[poses.size() - 2].time) return {};
  return "time " + MessageNumber(poses.back().time) + " s is not after the report before it (" + MessageNumber(poses[poses.size() - 2].time) + " s)";
}

constexpr const char* kOrderFix = "sort the log by time and drop duplicate reports";

}  // namespace

PoseLog PoseLogFromTum(const std::string& text, const std::string& name, LengthUnit unit) {
  PoseLog log;
  log.length_unit = unit;
  std::istringstream in(text);
  std::string line;
  size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::istringstream fields(line);
    double v[8];
    for (int i = 0; i < 8; ++i) {
      std::string word;
      if (!(fields >> word)) {
        FailLine(name, number, std::to_string(i) + " numbers where a TUM pose has 8 (timestamp tx ty tz qx qy qz qw)",
                 "write one pose a line, or comment the line out with #");
      }
      errno = 0;
      char* end = nullptr;
      v[i] = std::strtod(word.c_str(), &end);
      if (end == word.c_str() || *end != '\0' || errno == ERANGE || !std::isfinite(v[i])) {
        std::string reason = "\"";  // appended, not concatenated: GCC 12's -Wrestrict misfires on the temporaries
        reason.append(word, 0, 40);
        reason += "\" is not a finite number";
        FailLine(name, number, reason, "fix the line");
      }
    }
    std::string extra;
    if (fields >> extra) FailLine(name, number, "more than 8 numbers", "a TUM pose is timestamp tx ty tz qx qy qz qw");
    const double norm = std::sqrt(v[4] * v[4] + v[5] * v[5] + v[6] * v[6] + v[7] * v[7]);
    if (!(std::abs(norm - 1) <= kUnitTolerance)) {
      FailLine(name, number, "the quaternion's norm is " + MessageNumber(norm) + ", not 1", "write unit quaternions (qx qy qz qw)");
    }
    if (log.poses.size() == kMaxPoseReports) {
      FailLine(name, number, "more than " + std::to_string(kMaxPoseReports) + " reports (docs/reliability.md#limits)", "decimate the log");
    }
    TrackedPose p;
    p.time = v[0];
    p.tracker_from_hmd.R = RotationFromQuaternionWxyz({v[7] / norm, v[4] / norm, v[5] / norm, v[6] / norm});
    p.tracker_from_hmd.t = Eigen::Vector3d(v[1], v[2], v[3]);
    log.poses.push_back(p);
    if (const std::string problem = OrderProblem(log.poses); !problem.empty()) FailLine(name, number, problem, kOrderFix);
  }
  if (log.poses.size() < 2) {
    throw InputError(name + ": " + std::to_string(log.poses.size()) + " poses; a tracker's log needs at least 2 (TUM: timestamp tx ty tz qx qy qz qw a line)");
  }
  return log;
}

PoseLog PoseLogFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.at("format").OneOf({kFormat});
  PoseLog log;
  const std::string unit = root.at("length_unit").OneOf(kLengthUnitNames);
  log.length_unit = *LengthUnitFromName(unit);
  root.at("frame").OneOf({"tracker_from_hmd"});
  const JsonNode poses = root.at("poses");
  const size_t n = poses.ArraySize();
  if (n < 2) poses.Fail(std::to_string(n) + " poses", "a tracker's log needs at least 2");
  if (n > kMaxPoseReports) poses.Fail(std::to_string(n) + " poses, more than " + std::to_string(kMaxPoseReports), "decimate the log");
  for (size_t i = 0; i < n; ++i) {
    const JsonNode p = poses.at(i);
    TrackedPose pose;
    pose.time = p.at("time").Number();
    const JsonNode q = p.at("q_wxyz");
    const Eigen::Vector4d wxyz = q.Vector<4>();
    if (!(std::abs(wxyz.norm() - 1) <= kUnitTolerance)) q.Fail("the quaternion's norm is " + MessageNumber(wxyz.norm()) + ", not 1", "write unit quaternions (w, x, y, z)");
    const Eigen::Vector4d u = wxyz.normalized();
    pose.tracker_from_hmd.R = RotationFromQuaternionWxyz({u(0), u(1), u(2), u(3)});
    pose.tracker_from_hmd.t = p.at("t").Vector<3>();
    log.poses.push_back(pose);
    if (const std::string problem = OrderProblem(log.poses); !problem.empty()) p.at("time").Fail(problem, kOrderFix);
  }
  return log;
}

PoseLog ReadPoseLog(const std::filesystem::path& path, LengthUnit tum_unit) {
  if (path.extension() == ".json") return PoseLogFromJson(JsonDocument::Load(path));
  return PoseLogFromTum(ReadInputFile(path, "a pose log"), path.string(), tum_unit);
}

OrderedJson PoseLogToJson(const PoseLog& log, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kFormat;
  j["length_unit"] = LengthUnitName(log.length_unit);
  j["frame"] = "tracker_from_hmd";
  OrderedJson poses = OrderedJson::array();
  for (const TrackedPose& p : log.poses) {
    const auto q = QuaternionWxyzFromRotation(p.tracker_from_hmd.R);
    poses.push_back({{"time", p.time}, {"q_wxyz", {q[0], q[1], q[2], q[3]}}, {"t", {p.tracker_from_hmd.t.x(), p.tracker_from_hmd.t.y(), p.tracker_from_hmd.t.z()}}});
  }
  j["poses"] = std::move(poses);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

std::string PoseLogToTum(const PoseLog& log) {
  std::string text = "# timestamp tx ty tz qx qy qz qw (tracker_from_hmd, " + std::string(LengthUnitName(log.length_unit)) + ")\n";
  for (const TrackedPose& p : log.poses) {
    const auto q = QuaternionWxyzFromRotation(p.tracker_from_hmd.R);
    char line[400];
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", p.time, p.tracker_from_hmd.t.x(),
                  p.tracker_from_hmd.t.y(), p.tracker_from_hmd.t.z(), q[1], q[2], q[3], q[0]);
    text += line;
  }
  return text;
}

PoseLog InUnit(PoseLog log, LengthUnit unit) {
  const double scale = MetresPer(log.length_unit) / MetresPer(unit);
  for (TrackedPose& p : log.poses) p.tracker_from_hmd.t *= scale;
  log.length_unit = unit;
  return log;
}

}  // namespace vstcal
