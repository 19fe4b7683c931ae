#include "vstcal/formats/stereo/stereo_io.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/camera/residual_stats_json.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

constexpr std::string_view kFormat = "vstcal/stereo@1";
constexpr double kAgreement = 1e-6;  // relative agreement required between redundant fields

CalibratedCamera ReadRigCamera(const JsonNode& node, LengthUnit rig_unit) {
  node.ExpectObject();
  for (const std::string_view pose : {"camera_from_world", "views", "P"}) {
    if (const auto field = node.find(pose)) {
      field->Fail("a rig's cameras hold intrinsics only",
                  "delete \"" + std::string(pose) + "\": the pose between the cameras is right_from_left");
    }
  }
  CalibratedCamera c = CameraFromNode(node);
  if (c.length_unit != rig_unit) {
    node.at("length_unit").Fail("\"" + std::string(LengthUnitName(c.length_unit)) + "\", but the rig is in \"" +
                                    std::string(LengthUnitName(rig_unit)) + "\"",
                                "give the rig and its cameras one length unit");
  }
  return c;
}

ResidualStats ReadStats(const JsonNode& node) {
  ResidualStats s;
  s.rms_px = node.at("rms_px").NonNegativeNumber();
  s.max_px = node.at("max_px").NonNegativeNumber();
  const int n = node.at("n_points").Integer();
  if (n < 0) node.at("n_points").Fail("must not be negative, got " + std::to_string(n), "give a count ≥ 0");
  s.n_points = static_cast<size_t>(n);
  return s;
}

StereoFit ReadFit(const JsonNode& node) {
  StereoFit fit;
  fit.epipolar = ReadStats(node.at("epipolar"));
  const JsonNode views = node.at("views");
  for (size_t i = 0; i < views.ArraySize(); ++i) {
    const JsonNode v = views.at(i);
    fit.views.push_back({v.at("name").String(), ReadStats(v.at("epipolar"))});
  }
  return fit;
}


std::array<int, 4> ReadRoi(const JsonNode& node, const ImageSize& size) {
  node.ArraySize(4);
  std::array<int, 4> roi;
  for (int i = 0; i < 4; ++i) roi[i] = node.at(i).Integer();
  if (roi[0] < 0 || roi[1] < 0 || roi[2] < 0 || roi[3] < 0 || roi[0] + roi[2] > size.width ||
      roi[1] + roi[3] > size.height) {
    node.Fail("not a rectangle [x, y, width, height] inside the " + std::to_string(size.width) + "×" +
                  std::to_string(size.height) + " image",
              "give the rectangle cv::stereoRectify returned");
  }
  return roi;
}

Eigen::Matrix3d ReadRotation(const JsonNode& node) {
  const Eigen::Matrix3d R = node.Matrix<3, 3>();
  if (!IsRotation(R, 1e-6)) {
    node.Fail("not a rotation matrix (RᵀR ≠ I or det R < 0, tolerance 1e-6)", "write R with at least 7 significant digits");
  }
  return R;
}

// The rectified frames must be one frame seen from two places along an image axis, and P and Q
// must be the projections and the reprojection of that geometry (docs/math/stereo.md#rectification).
void CheckRectification(const JsonNode& node, const Rectification& r, const Rigid3d& right_from_left) {
  const Eigen::Matrix3d relative = r.right_rect_from_right * right_from_left.R * r.left_rect_from_left.transpose();
  if ((relative - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kAgreement) {
    node.Fail("its rotations do not align the cameras (right_rect_from_right · R · left_rect_fromleftᵀ ≠ I)",
              "rectify this rig again (calib-stereo export " VSTCAL_OPT("rectify") "), or delete \"rectification\"");
  }
  const Eigen::Vector3d t = r.right_rect_from_right * right_from_left.t;  // baseline in the rectified frame
  const int axis = std::abs(t.x()) >= std::abs(t.y()) ? 0 : 1;
  if (std::abs(t(1 - axis)) > kAgreement * t.norm() || std::abs(t.z()) > kAgreement * t.norm()) {
    node.Fail("its rotations do not put the baseline along an image axis",
              "rectify this rig again (calib-stereo export " VSTCAL_OPT("rectify") "), or delete \"rectification\"");
  }
  const Eigen::Vector3d expected_column = r.P_right.leftCols<3>() * t;
  const double scale = std::max(1.0, r.P_right.cwiseAbs().maxCoeff());
  if (!r.P_left.col(3).isZero(0) || (r.P_right.col(3) - expected_column).cwiseAbs().maxCoeff() > kAgreement * scale) {
    node.Fail("P_left or P_right disagrees with the rig (P_left = [K | 0], P_right = [K | K·right_rect_from_right·t])",
              "rectify this rig again (calib-stereo export " VSTCAL_OPT("rectify") "), or delete \"rectification\"");
  }
  // Q reprojects (u, v, disparity along the baseline's axis) to the point P_left and P_right saw.
  for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.1, -0.2, 1.0), Eigen::Vector3d(-0.3, 0.1, 2.0)}) {
    const Eigen::Vector3d point = x * (10 * t.norm());
    const Eigen::Vector3d a = r.P_left * point.homogeneous(), b = r.P_right * point.homogeneous();
    const Eigen::Vector2d q1 = a.hnormalized(), q2 = b.hnormalized();
    const Eigen::Vector4d h = r.Q * Eigen::Vector4d(q1.x(), q1.y(), q1(axis) - q2(axis), 1.0);
    if (!(std::abs(h(3)) > 0) || (h.head<3>() / h(3) - point).norm() > kAgreement * point.norm() * 10) {
      node.at("Q").Fail("does not reproject the rectified pixels of P_left and P_right to their point",
                        "rectify this rig again (calib-stereo export " VSTCAL_OPT("rectify") "), or delete \"rectification\"");
    }
  }
}

Rectification ReadRectification(const JsonNode& node, const StereoRig& rig) {
  Rectification r;
  r.alpha = node.at("alpha").Number();
  if (!(r.alpha == -1 || (r.alpha >= 0 && r.alpha <= 1))) {
    node.at("alpha").Fail("must be -1 or lie in [0, 1], got " + ShortestDecimal(r.alpha),
                          "give OpenCV's free scaling parameter: -1 (default), 0 … 1");
  }
  r.zero_disparity = node.at("zero_disparity").Boolean();
  r.left_rect_from_left = ReadRotation(node.at("left_rect_from_left"));
  r.right_rect_from_right = ReadRotation(node.at("right_rect_from_right"));
  r.P_left = node.at("P_left").Matrix<3, 4>();
  r.P_right = node.at("P_right").Matrix<3, 4>();
  r.Q = node.at("Q").Matrix<4, 4>();
  r.valid_roi_left = ReadRoi(node.at("valid_roi_left"), rig.left.camera.image_size);
  r.valid_roi_right = ReadRoi(node.at("valid_roi_right"), rig.right.camera.image_size);
  CheckRectification(node, r, rig.right_from_left);
  return r;
}

OrderedJson RectificationToJson(const Rectification& r) {
  OrderedJson j;
  j["alpha"] = r.alpha;
  j["zero_disparity"] = r.zero_disparity;
  j["left_rect_from_left"] = MatrixToJson(r.left_rect_from_left);
  j["right_rect_from_right"] = MatrixToJson(r.right_rect_from_right);
  j["P_left"] = MatrixToJson(r.P_left);
  j["P_right"] = MatrixToJson(r.P_right);
  j["Q"] = MatrixToJson(r.Q);
  j["valid_roi_left"] = r.valid_roi_left;
  j["valid_roi_right"] = r.valid_roi_right;
  return j;
}

ViewPairing ReadViewPairing(const JsonNode& node) {
  node.ExpectObject();
  ViewPairing pairing;
  const JsonNode pattern = node.at("match_views");
  pairing.match_views = pattern.String();
  try {
    Correspondences none;
    KeyViews(pairing.match_views, "", &none);  // checks the expression only
  } catch (const InputError& e) {
    std::string why = e.what();
    if (const std::string_view prefix = VSTCAL_OPT("match_views") ": "; why.starts_with(prefix)) why = why.substr(prefix.size());
    pattern.Fail(why.substr(0, why.find("; ")), "give an expression whose first group is the key, e.g. \"([0-9]+)$\"");
  }
  if (const auto rule = node.find("rule")) pairing.rule = rule->String();
  return pairing;
}

OrderedJson RigCameraToJson(const CalibratedCamera& camera, const Provenance& provenance) {
  OrderedJson j = CameraToJson(camera, provenance);
  j.erase("provenance");  // the rig's provenance is the cameras'
  return j;
}

// An entry of the joint covariance and of a marginal block the file also gives must be one
// number (the blocks are that marginal), to this relative tolerance of √(Σaa·Σbb).
void CheckJointBlock(const JsonNode& node, const ParameterCovariance& joint, const std::optional<ParameterCovariance>& marginal,
                     const std::string& prefix, const std::string& marginal_field) {
  if (!marginal) return;
  for (size_t a = 0; a < marginal->parameters.size(); ++a) {
    for (size_t b = 0; b < marginal->parameters.size(); ++b) {
      const auto ja = joint.Find(prefix + marginal->parameters[a]), jb = joint.Find(prefix + marginal->parameters[b]);
      if (!ja || !jb) continue;
      const double j = joint.matrix(*ja, *jb), m = marginal->matrix(a, b);
      const double scale = std::sqrt(std::abs(joint.matrix(*ja, *ja) * joint.matrix(*jb, *jb)));
      if (std::abs(j - m) > kAgreement * scale + 1e-300) {
        node.at("matrix").Fail("its entry (" + prefix + marginal->parameters[a] + ", " + prefix + marginal->parameters[b] + ") = " +
                                   ShortestDecimal(j) + " disagrees with " + marginal_field + "'s " + ShortestDecimal(m),
                               "give the joint covariance whose blocks are the marginals written beside it, or delete \"joint_covariance\"");
      }
    }
  }
}

}  // namespace

ParameterCovariance ReadJointCovariance(const JsonNode& node, const AnyLensModel& left, const AnyLensModel& right) {
  node.ExpectObject();
  ExpectKeys(node, {"parameters", "matrix"}, "field of a covariance");
  const JsonNode names = node.at("parameters");
  const size_t n = names.ArraySize();
  const auto& tangents = RelativePoseTangentNames();
  std::vector<std::string> read;
  for (size_t i = 0; i < n; ++i) {
    std::string name = names.at(i).String();
    bool known = std::find(tangents.begin(), tangents.end(), name) != tangents.end();
    for (int eye = 0; eye < 2 && !known; ++eye) {
      for (const std::string_view p : LensModelParamNames(eye == 0 ? left : right)) {
        if (name == JointCovarianceName(eye, p)) known = true;
      }
    }
    if (!known) {
      names.at(i).Fail("unknown parameter \"" + name + "\"",
                       "a rig's joint covariance is over left.<lens parameter>, right.<lens parameter> (fx, fy, cx, cy, s and "
                       "each camera's distortion terms) and right_from_left.rx … .tz");
    }
    if (std::find(read.begin(), read.end(), name) != read.end()) names.at(i).Fail("duplicate parameter \"" + name + "\"", "list each parameter once");
    read.push_back(std::move(name));
  }
  return ReadCovarianceMatrix(node, std::move(read));
}

namespace {

// The rig's joint covariance: its blocks are the marginals the file gives beside it.
ParameterCovariance ReadRigJointCovariance(const JsonNode& node, const StereoRig& rig) {
  ParameterCovariance joint = ReadJointCovariance(node, rig.left.camera.model, rig.right.camera.model);
  CheckJointBlock(node, joint, rig.left.covariance, "left.", "left.covariance");
  CheckJointBlock(node, joint, rig.right.covariance, "right.", "right.covariance");
  CheckJointBlock(node, joint, rig.covariance, "", "covariance");
  return joint;
}

}  // namespace

ParameterCovariance ReadRelativePoseCovariance(const JsonNode& node) {
  const JsonNode names = node.at("parameters");
  const auto& expected = RelativePoseTangentNames();
  names.ArraySize(expected.size());
  std::vector<std::string> read;
  for (size_t i = 0; i < expected.size(); ++i) {
    const std::string name = names.at(i).String();
    if (std::find(expected.begin(), expected.end(), name) == expected.end()) {
      names.at(i).Fail("unknown parameter \"" + name + "\"",
                       "a rig's covariance is over right_from_left.rx, .ry, .rz, .tx, .ty, .tz");
    }
    if (std::find(read.begin(), read.end(), name) != read.end()) {
      names.at(i).Fail("duplicate parameter \"" + name + "\"", "list each parameter once");
    }
    read.push_back(name);
  }
  return ReadCovarianceMatrix(node, std::move(read));
}

bool IsStereoRigDocument(const JsonDocument& doc) {
  const auto format = doc.root().find("format");
  try {
    return format && format->String() == kFormat;
  } catch (const InputError&) {  // not a string: not a rig (its own reader says what is wrong)
    return false;
  }
}

StereoRig StereoRigFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kFormat);
  StereoRig rig;
  rig.length_unit = ReadLengthUnit(root.at("length_unit"));
  rig.method = root.at("method").String();
  rig.left = ReadRigCamera(root.at("left"), rig.length_unit);
  rig.right = ReadRigCamera(root.at("right"), rig.length_unit);
  const JsonNode pose = root.at("right_from_left");
  rig.right_from_left = ReadRigid(pose);
  const JsonNode baseline = root.at("baseline");
  const double b = baseline.PositiveNumber();
  CheckBaseline(rig.right_from_left, doc.name() + ": right_from_left.t");
  if (std::abs(b - rig.baseline()) > kAgreement * rig.baseline()) {
    baseline.Fail("disagrees with |right_from_left.t| = " + ShortestDecimal(rig.baseline()),
                  "delete \"baseline\" or make it the distance between the camera centres");
  }
  if (const auto fit = root.find("fit"); fit && !fit->json().is_null()) rig.fit = ReadFit(*fit);
  if (const auto cov = root.find("covariance")) rig.covariance = ReadRelativePoseCovariance(*cov);
  if (const auto joint = root.find("joint_covariance")) rig.joint_covariance = ReadRigJointCovariance(*joint, rig);
  if (const auto rect = root.find("rectification")) rig.rectification = ReadRectification(*rect, rig);
  if (const auto pairing = root.find("view_pairing")) rig.view_pairing = ReadViewPairing(*pairing);
  return rig;
}

StereoRig ReadStereoRig(const std::filesystem::path& path) { return StereoRigFromJson(JsonDocument::Load(path)); }

OrderedJson StereoRigToJson(const StereoRig& rig, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kFormat;
  j["length_unit"] = LengthUnitName(rig.length_unit);
  j["method"] = rig.method;
  j["left"] = RigCameraToJson(rig.left, provenance);
  j["right"] = RigCameraToJson(rig.right, provenance);
  j["right_from_left"] = RigidToJson(rig.right_from_left);
  j["baseline"] = rig.baseline();
  if (rig.fit) {
    OrderedJson views = OrderedJson::array();
    for (const StereoViewFit& v : rig.fit->views) views.push_back({{"name", v.name}, {"epipolar", ResidualStatsToJson(v.epipolar)}});
    j["fit"] = {{"epipolar", ResidualStatsToJson(rig.fit->epipolar)}, {"views", std::move(views)}};
  } else {
    j["fit"] = nullptr;
  }
  if (rig.covariance) {
    j["covariance"] = {{"parameters", rig.covariance->parameters}, {"matrix", MatrixToJson(rig.covariance->matrix)}};
    const Eigen::Vector3d rotation = *RelativeRotationSigma(rig);
    j["relative_pose_sigma"] = {{"baseline", *BaselineSigma(rig)},
                                {"rotation_deg", {RadToDeg(rotation.x()), RadToDeg(rotation.y()), RadToDeg(rotation.z())}}};
  }
  if (rig.joint_covariance) {
    j["joint_covariance"] = {{"parameters", rig.joint_covariance->parameters}, {"matrix", MatrixToJson(rig.joint_covariance->matrix)}};
  }
  if (rig.rectification) j["rectification"] = RectificationToJson(*rig.rectification);
  if (rig.view_pairing) {
    j["view_pairing"] = {{"match_views", rig.view_pairing->match_views}, {"rule", rig.view_pairing->rule}};
  }
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
