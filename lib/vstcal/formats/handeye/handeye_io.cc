#include "vstcal/formats/handeye/handeye_io.h"

#include <opencv2/core.hpp>

#include "vstcal/camera/opencv_mat.h"
#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

OrderedJson PoseJson(const Rigid3d& p) {
  OrderedJson R = OrderedJson::array();
  for (int r = 0; r < 3; ++r) R.push_back({p.R(r, 0), p.R(r, 1), p.R(r, 2)});
  return {{"R", std::move(R)}, {"t", {p.t.x(), p.t.y(), p.t.z()}}};
}

OrderedJson NoiseJson(const NoiseEstimate& e) {
  return {{"sigma", e.sigma}, {"ci95", {e.lower, e.upper}}, {"per_axis", {e.per_axis.x(), e.per_axis.y(), e.per_axis.z()}}};
}

}  // namespace

std::string HandEyeOpenCvYaml(const HandEyeSolution& s, LengthUnit length_unit, const Provenance& provenance) {
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs.writeComment(ProvenanceComment(provenance));
  fs.writeComment("OpenCV's hand-eye names: gripper = the tracked HMD, base = the tracker, target = the board; x_a = R x_b + t, t in " +
                  std::string(LengthUnitName(length_unit)));
  fs << "R_cam2gripper" << ToCvMat(s.hmd_from_camera.R) << "t_cam2gripper" << ToCvMat(s.hmd_from_camera.t);
  fs << "R_target2base" << ToCvMat(s.tracker_from_board.R) << "t_target2base" << ToCvMat(s.tracker_from_board.t);
  fs.writeComment("seconds: the tracker's clock reads t + time_offset when the camera's reads t");
  fs << "time_offset" << s.time_offset;
  return fs.releaseAndGetString();
}

OrderedJson TrackerNoiseToJson(const TrackerNoise& n, LengthUnit length_unit, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = "vstcal/tracker-noise@1";
  j["length_unit"] = LengthUnitName(length_unit);
  j["segment"] = {{"from", n.from}, {"to", n.to}, {"reports", n.reports}};
  j["tracker_from_hmd"] = PoseJson(n.mean);
  j["rotation_rad"] = NoiseJson(n.rotation);
  j["translation"] = NoiseJson(n.translation);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

OrderedJson HandEyeToJson(const HandEyeSolution& s, LengthUnit length_unit, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = "vstcal/handeye@1";
  j["length_unit"] = LengthUnitName(length_unit);
  j["hmd_from_camera"] = PoseJson(s.hmd_from_camera);
  j["tracker_from_board"] = PoseJson(s.tracker_from_board);
  j["time_offset_s"] = s.time_offset;
  OrderedJson matrix = OrderedJson::array();
  for (Eigen::Index r = 0; r < s.covariance.rows(); ++r) {
    OrderedJson row = OrderedJson::array();
    for (Eigen::Index c = 0; c < s.covariance.cols(); ++c) row.push_back(s.covariance(r, c));
    matrix.push_back(std::move(row));
  }
  if (s.covariance.size() == 0) {  // a truth (calib-synth): nothing was estimated
    j["fit"] = {{"views", s.views}, {"corners", s.corners}};
    j["provenance"] = ProvenanceToJson(provenance);
    return j;
  }
  j["covariance"] = {{"parameters", s.names}, {"matrix", std::move(matrix)}};
  j["fit"] = {{"views", s.views}, {"corners", s.corners}, {"rms_px", s.rms_px}, {"sigma_px", s.sigma_px}, {"iterations", s.iterations}};
  j["start"] = {{"method", "park-martin"},
                {"hmd_from_camera", PoseJson(s.start.hmd_from_camera)},
                {"tracker_from_board", PoseJson(s.start.tracker_from_board)},
                {"time_offset_s", s.start_time_offset},
                {"pairs", s.start.pairs},
                {"second_axis_spread", s.start.second_axis_spread}};
  OrderedJson rejected = OrderedJson::array();
  for (const Rejection& r : s.rejected) {
    rejected.push_back({{"round", r.round}, {"view", r.view}, {"name", r.view_name}, {"rms_px", r.rms_px}, {"threshold_px", r.threshold_px},
                        {"because", r.because}});
  }
  j["rejected_views"] = std::move(rejected);
  j["warnings"] = s.warnings;
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
