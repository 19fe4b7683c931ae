#include "vstcal/formats/handeye/handeye_io.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>

#include "vstcal/camera/opencv_mat.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/peer_formats.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"

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

NoiseEstimate ReadNoise(const JsonNode& node) {
  ExpectKeys(node, {"sigma", "ci95", "per_axis"}, "field of a noise estimate");
  NoiseEstimate e;
  e.sigma = node.at("sigma").NonNegativeNumber();
  const JsonNode ci = node.at("ci95");
  ci.ArraySize(2);
  e.lower = ci.at(0).NonNegativeNumber();
  e.upper = ci.at(1).NonNegativeNumber();
  e.per_axis = node.at("per_axis").Vector<3>();
  return e;
}

// A σ estimated jointly: {sigma, sigma_sigma, ci95: [lower, upper]} (HandEyeToJson's).
EstimatedSigma ReadEstimatedSigma(const JsonNode& node) {
  ExpectKeys(node, {"sigma", "sigma_sigma", "ci95"}, "field of a jointly estimated σ");
  EstimatedSigma e;
  e.sigma = node.at("sigma").NonNegativeNumber();
  e.sigma_sigma = node.at("sigma_sigma").NonNegativeNumber();
  const JsonNode ci = node.at("ci95");
  ci.ArraySize(2);
  e.lower = ci.at(0).NonNegativeNumber();
  e.upper = ci.at(1).NonNegativeNumber();
  return e;
}

}  // namespace

HandEyeMeasurement HandEyeFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, "vstcal/handeye@1");
  HandEyeMeasurement out;
  out.length_unit = ReadLengthUnit(root.at("length_unit"));
  out.solution.hmd_from_camera = ReadRigid(root.at("hmd_from_camera"));
  out.solution.tracker_from_board = ReadRigid(root.at("tracker_from_board"));
  out.solution.time_offset = root.at("time_offset_s").Number();
  if (const auto cov = root.find("covariance")) {
    cov->ExpectObject();
    const JsonNode names = cov->at("parameters");
    // X, Z and δ; and the tracker's noise σ's when they were estimated jointly.
    std::vector<std::string> expected = HandEyeCovarianceNames();
    if (names.json().is_array() && names.json().size() == expected.size() + HandEyeNoiseCovarianceNames().size()) {
      expected.insert(expected.end(), HandEyeNoiseCovarianceNames().begin(), HandEyeNoiseCovarianceNames().end());
    }
    names.ArraySize(expected.size());
    std::vector<std::string> read;
    for (size_t i = 0; i < expected.size(); ++i) {
      std::string name = names.at(i).String();
      if (std::find(expected.begin(), expected.end(), name) == expected.end()) {
        names.at(i).Fail("unknown parameter \"" + name + "\"", "a handeye covariance is over hmd_from_camera.rx … .tz, tracker_from_board.rx … .tz and time_offset (then, optionally, tracker_noise.rotation and .translation)");
      }
      if (std::find(read.begin(), read.end(), name) != read.end()) names.at(i).Fail("duplicate parameter \"" + name + "\"", "list each parameter once");
      read.push_back(std::move(name));
    }
    ParameterCovariance c = ReadCovarianceMatrix(*cov, read);
    // In HandEyeCovarianceNames' order, whatever order the file lists them in.
    const auto n = static_cast<Eigen::Index>(expected.size());
    out.solution.covariance.resize(n, n);
    for (Eigen::Index a = 0; a < n; ++a)
      for (Eigen::Index b = 0; b < n; ++b) out.solution.covariance(a, b) = c.matrix(*c.Find(expected[a]), *c.Find(expected[b]));
    out.solution.names = expected;
  }
  // What calib-handeye doubted about its own estimate (strings; err-sim repeats them).
  if (const auto warnings = root.find("warnings")) {
    for (size_t i = 0; i < warnings->ArraySize(); ++i) out.solution.warnings.push_back(warnings->at(i).String());
  }
  if (const auto b = root.find("bootstrap")) {
    b->ExpectObject();
    out.bootstrap_time_offset_sigma = b->at("time_offset_sigma_s").NonNegativeNumber();
  }
  // The tracker's noise when it was estimated jointly (err-sim's tracking σ's may come from it);
  // a file whose tracker was taken as exact says so in words and has no σ's.
  if (const auto noise = root.find("tracker_noise"); noise && noise->json().is_object() && noise->json().contains("rotation_rad")) {
    JointTrackerNoise n;
    n.rotation = ReadEstimatedSigma(noise->at("rotation_rad"));
    n.translation = ReadEstimatedSigma(noise->at("translation"));
    if (const auto px = noise->find("corner_px")) n.corner_px = ReadEstimatedSigma(*px);
    if (const auto frames = noise->find("frames")) n.frames = static_cast<size_t>(frames->NonNegativeNumber());
    if (const auto rounds = noise->find("rounds")) n.rounds = static_cast<int>(rounds->NonNegativeNumber());
    out.solution.tracker_noise = n;
  }
  return out;
}

TrackerNoiseMeasurement TrackerNoiseFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, "vstcal/tracker-noise@1");
  TrackerNoiseMeasurement out;
  out.length_unit = ReadLengthUnit(root.at("length_unit"));
  out.noise.mean = ReadRigid(root.at("tracker_from_hmd"));
  out.noise.rotation = ReadNoise(root.at("rotation_rad"));
  out.noise.translation = ReadNoise(root.at("translation"));
  if (const auto segment = root.find("segment")) {
    out.noise.from = segment->at("from").Number();
    out.noise.to = segment->at("to").Number();
    out.noise.reports = static_cast<size_t>(segment->at("reports").NonNegativeNumber());
  }
  return out;
}

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

OrderedJson HandEyeToJson(const HandEyeSolution& s, LengthUnit length_unit, const Provenance& provenance, const HandEyeRigFile* rig,
                          const HandEyeBootstrap* bootstrap) {
  OrderedJson j;
  j["format"] = "vstcal/handeye@1";
  j["length_unit"] = LengthUnitName(length_unit);
  j["hmd_from_camera"] = PoseJson(s.hmd_from_camera);
  j["tracker_from_board"] = PoseJson(s.tracker_from_board);
  j["time_offset_s"] = s.time_offset;
  if (s.covariance.size() == 0) {  // a truth (calib-synth): nothing was estimated
    j["fit"] = {{"views", s.views}, {"corners", s.corners}};
    j["provenance"] = ProvenanceToJson(provenance);
    return j;
  }
  j["covariance"] = {{"parameters", s.names}, {"matrix", MatrixToJson(s.covariance)}};
  j["fit"] = {{"views", s.views}, {"corners", s.corners}, {"rms_px", s.rms_px}, {"sigma_px", s.sigma_px}, {"iterations", s.iterations},
              {"report_phases", {{"concentration", s.report_phases.concentration}, {"mean", s.report_phases.mean}, {"instants", s.report_phases.instants}}}};
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
  if (s.tracker_noise) {
    const auto sigma = [](const EstimatedSigma& e) {
      return OrderedJson{{"sigma", e.sigma}, {"sigma_sigma", e.sigma_sigma}, {"ci95", {e.lower, e.upper}}};
    };
    j["tracker_noise"] = {{"model", "R = Exp(ω) R_true, t = t_true + ρ, ω ~ N(0, σ_r² I), ρ ~ N(0, σ_t² I), independent reports"},
                          {"estimated", "jointly (restricted maximum likelihood)"},
                          {"rotation_rad", sigma(s.tracker_noise->rotation)},
                          {"translation", sigma(s.tracker_noise->translation)},
                          {"corner_px", sigma(s.tracker_noise->corner_px)},
                          {"frames", s.tracker_noise->frames},
                          {"rounds", s.tracker_noise->rounds}};
  } else {
    j["tracker_noise"] = {{"estimated", "no: the tracker's poses were taken as exact"}};
  }
  if (rig && s.right_from_left) {
    j["rig"] = {{"file", rig->file},
                {"right_views_file", rig->right_corners},
                {"right_from_left", PoseJson(*s.right_from_left)},
                {"right_from_left_held", true},
                {"pairing", rig->pairing},
                {"right_views", s.right_views},
                {"right_corners", s.right_corners}};
  }
  if (bootstrap) {
    const auto delta = static_cast<Eigen::Index>(kHandEyeParameters - 1);
    j["bootstrap"] = {{"method", "parametric: recordings simulated at the estimate, each solved again"},
                      {"replicates", bootstrap->replicates},
                      {"solved", bootstrap->solved},
                      {"seed", bootstrap->seed},
                      {"time_offset_sigma_s", std::sqrt(bootstrap->covariance(delta, delta))},
                      {"first_order_time_offset_sigma_s", std::sqrt(s.covariance(delta, delta))},
                      {"time_offset_bias_s", bootstrap->mean[delta]},
                      {"covariance", {{"parameters", HandEyeCovarianceNames()}, {"matrix", MatrixToJson(bootstrap->covariance)}}}};
  }
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
