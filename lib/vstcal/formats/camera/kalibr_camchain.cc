#include "vstcal/formats/camera/kalibr_camchain.h"

#include <algorithm>

#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/reader_common.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

constexpr std::string_view kWhat = "a Kalibr camchain.yaml";
// A rotation read is kept as written when ‖RᵀR − I‖ is below this (as the JSON readers do).
constexpr double kRotationRounding = 1e-12;

std::string CamKey(size_t i) { return "cam" + std::to_string(i); }

Rigid3d ReadTransform(const YamlField& f) {
  f.Require("add T_cn_cnm1: the 4×4 transform from the previous camera's frame to this one's (metres)");
  const std::string fix = "write four rows [r, r, r, t] of four numbers, the last [0, 0, 0, 1]";
  if (f.node->kind != YamlNode::Kind::kSequence || f.node->items.size() != 4) {
    f.Fail("expected 4 rows, got " + f.Describe(), fix);
  }
  Eigen::Matrix4d T;
  for (int r = 0; r < 4; ++r) {
    const std::vector<double> row = f.Item(r).Numbers(4, fix);
    for (int c = 0; c < 4; ++c) T(r, c) = row[c];
  }
  if (T.row(3) != Eigen::RowVector4d(0, 0, 0, 1)) f.Item(3).Fail("the last row of a rigid transform is [0, 0, 0, 1]", fix);
  Rigid3d pose;
  pose.R = T.topLeftCorner<3, 3>();
  if (!IsRotation(pose.R, 1e-6)) {
    f.Fail("its 3×3 block is not a rotation matrix (RᵀR ≠ I or det R < 0, tolerance 1e-6)",
           "write R with at least 7 significant digits");
  }
  if (!IsRotation(pose.R, kRotationRounding)) pose.R = NearestRotation(pose.R);
  pose.t = T.topRightCorner<3, 1>();
  return pose;
}

KalibrCamera ReadCamera(const YamlField& f, bool chained, std::vector<std::string>* notes) {
  if (f.node->kind != YamlNode::Kind::kMap) f.Fail("expected a map, got " + f.Describe(), "write the camera's fields under it");
  KalibrCamera out;
  const YamlField model = f.Member("camera_model");
  model.Require("add camera_model: pinhole");
  if (const std::string m = model.String(); m != "pinhole") {
    model.Fail("camera model \"" + m + "\" has no vstcal model (" +
                   (m == "omni" || m == "eucm" || m == "ds" ? "a wide-angle projection" : "unknown to Kalibr") + ")",
               "calibrate with Kalibr's pinhole-radtan");
  }
  const std::string fix4 = "write [fu, fv, pu, pv] in pixels";
  const std::vector<double> in = f.Member("intrinsics").Numbers(4, fix4);
  const YamlField dm = f.Member("distortion_model");
  dm.Require("add distortion_model: radtan");
  const std::string dname = dm.String();
  int n = 0;
  const bool equidistant = dname == "equidistant";  // Kannala–Brandt k1…k4: vstcal's "kannala-brandt"
  if (dname == "radtan" || equidistant) {
    n = 4;
  } else if (dname == "none") {
    n = 0;
  } else if (dname == "fov") {
    dm.Fail("Kalibr's \"fov\" model has no vstcal lens model",
            "calibrate with pinhole-radtan or pinhole-equidistant (vstcal's radial-tangential and kannala-brandt)");
  } else {
    dm.Fail("unknown distortion model \"" + dname + "\"",
            "write radtan (k1, k2, r1, r2) or equidistant (k1, k2, k3, k4), the Kalibr models vstcal has");
  }
  const std::vector<double> d = f.Member("distortion_coeffs")
                                    .Numbers(n, !n           ? "write []"
                                                : equidistant ? "write the four equidistant coefficients [k1, k2, k3, k4]"
                                                              : "write the four radtan coefficients [k1, k2, r1, r2]");
  const YamlField res = f.Member("resolution");
  const std::vector<double> wh = res.Numbers(2, "write [width, height] in pixels");
  for (int i = 0; i < 2; ++i) {
    if (const auto problem = ImageSideProblem(wh[i], i ? "height" : "width")) res.Item(i).Fail(problem->reason, problem->fix);
  }
  Eigen::Matrix3d K;
  K << in[0], 0, in[2], 0, in[1], in[3], 0, 0, 1;
  if (const auto problem = CameraMatrixProblem(K)) f.Member("intrinsics").Fail(problem->reason, problem->fix);
  const ImageSize size{static_cast<int>(wh[0]), static_cast<int>(wh[1])};
  out.camera.camera = equidistant ? Camera::FromK(K, size, KannalaBrandtModel{}, d) : CameraFromOpenCv(K, size, d);
  out.camera.length_unit = LengthUnit::kMetre;
  out.camera.method = "kalibr";
  if (const YamlField topic = f.Member("rostopic"); topic.present()) out.rostopic = topic.String();
  const YamlField T = f.Member("T_cn_cnm1");
  if (chained) {
    out.cam_from_previous = ReadTransform(T);
  } else if (T.present()) {
    T.Fail("the first camera has no previous camera", "delete T_cn_cnm1 from " + f.path);
  }
  for (const auto& [key, value] : f.node->members) {
    static constexpr std::string_view kKnown[] = {"camera_model", "intrinsics", "distortion_model", "distortion_coeffs",
                                                  "resolution", "rostopic", "T_cn_cnm1", "cam_overlaps"};
    if (std::find(std::begin(kKnown), std::end(kKnown), key) == std::end(kKnown)) {
      notes->push_back(*f.file + ": " + f.path + "." + key + ": not read (vstcal keeps the cameras and T_cn_cnm1)");
    }
  }
  return out;
}

void WriteNumbers(std::string& out, const std::vector<double>& v) {
  out += "[";
  for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + YamlFloat(v[i]);
  out += "]\n";
}

}  // namespace

std::vector<KalibrCamera> KalibrCamchainFromText(const std::string& text, const std::string& name,
                                                 std::vector<std::string>* notes) {
  const YamlNode root = ParseYamlMap(text, name, kWhat);
  const YamlField top = RootField(root, name);
  std::vector<KalibrCamera> cameras;
  for (size_t i = 0;; ++i) {
    const YamlField cam = top.Member(CamKey(i));
    if (!cam.present()) break;
    cameras.push_back(ReadCamera(cam, i > 0, notes));
  }
  if (cameras.empty()) {
    FailField(name, "cam0", "missing field", "a camchain.yaml has one map per camera, cam0, cam1, …");
  }
  for (const auto& [key, value] : root.members) {
    if (key.starts_with("cam") && key.size() > 3 && key.find_first_not_of("0123456789", 3) == std::string::npos) {
      if (std::stoul(key.substr(3, 9)) >= cameras.size()) {
        FailField(name, key, "comes after a missing " + CamKey(cameras.size()),
                  "number the cameras cam0, cam1, … without a gap");
      }
    } else {
      notes->push_back(name + ": " + key + ": not read (vstcal keeps the cameras and T_cn_cnm1)");
    }
  }
  return cameras;
}

ExportedCamera KalibrCamchainText(const std::vector<KalibrCamera>& cameras, std::string_view source,
                                  const Provenance& provenance) {
  ExportedCamera out;
  std::string& t = out.text;
  t = "# " + ProvenanceComment(provenance) + "\n";
  for (size_t i = 0; i < cameras.size(); ++i) {
    const CalibratedCamera& cc = cameras[i].camera;
    const Camera& c = cc.camera;
    const std::string where = std::string(source) + (cameras.size() > 1 ? ": " + CamKey(i) : "");
    RefuseSkew(c, where, "Kalibr");
    const bool none = c.distortion().empty(), equidistant = !HasOpenCvDistortion(c);
    if (!none && !equidistant && FirstCoefficientBeyond(c, 4)) {
      throw InputError(where + ": distortion: Kalibr's radtan holds k1, k2, r1, r2 only, and this " +
                       std::string(LensModelName(c.model)) + " camera has a non-zero coefficient beyond them (k3" +
                       (LensModelNumParams(c.model) > 10 ? ", k4, k5 or k6" : "") +
                       "); calibrate with k3 fixed at 0, or write ROS camera_info (" VSTCAL_OPT("to") " ros), which holds it");
    }
    t += CamKey(i) + ":\n";
    if (i > 0) {
      const Rigid3d& T = *cameras[i].cam_from_previous;
      t += "  T_cn_cnm1:\n";
      for (int r = 0; r < 3; ++r) {
        t += "  - ";
        WriteNumbers(t, {T.R(r, 0), T.R(r, 1), T.R(r, 2), T.t(r)});
      }
      t += "  - [0.0, 0.0, 0.0, 1.0]\n";
    }
    t += "  camera_model: pinhole\n";
    t += "  distortion_coeffs: ";
    WriteNumbers(t, none          ? std::vector<double>{}
                    : equidistant ? std::vector<double>(c.distortion().begin(), c.distortion().end())
                                  : OpenCvDistortion(c, 4));
    t += std::string("  distortion_model: ") + (none ? "none" : equidistant ? "equidistant" : "radtan") + "\n";
    const Eigen::Matrix3d K = c.K();
    t += "  intrinsics: ";
    WriteNumbers(t, {K(0, 0), K(1, 1), K(0, 2), K(1, 2)});
    t += "  resolution: [" + std::to_string(c.image_size.width) + ", " + std::to_string(c.image_size.height) + "]\n";
    if (!cameras[i].rostopic.empty()) t += "  rostopic: " + YamlString(cameras[i].rostopic) + "\n";
    if (cc.camera_from_world) {
      out.notes.push_back(where + ": camera_from_world: not written: a camchain holds the poses between cameras only");
    }
  }
  return out;
}

}  // namespace vstcal
