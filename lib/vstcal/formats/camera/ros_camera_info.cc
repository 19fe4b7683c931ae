#include "vstcal/formats/camera/ros_camera_info.h"

#include <cmath>

#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/yaml_tree.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

constexpr std::string_view kRosWhat = "a ROS camera_info file";
constexpr std::string_view kPlumbBob = "plumb_bob", kRational = "rational_polynomial", kEquidistant = "equidistant";

// A {rows, cols, data} matrix of `rows`×`cols` (`vector`: 1×n or n×1 with n = rows·cols).
Eigen::MatrixXd ReadRosMatrix(const YamlField& f, int rows, int cols, bool vector, std::string_view what) {
  const std::string shape = std::to_string(rows) + "×" + std::to_string(cols);
  f.Require("add " + std::string(what) + " as rows: " + std::to_string(rows) + ", cols: " + std::to_string(cols) +
            " and data: [ ... ]");
  const YamlField rf = f.Member("rows"), cf = f.Member("cols"), data = f.Member("data");
  const int r = rf.Integer("give the number of rows"), c = cf.Integer("give the number of columns");
  const bool fits = (r == rows && c == cols) || (vector && r == cols && c == rows);
  if (!fits) {
    f.Fail("expected " + shape + ", got " + std::to_string(r) + "×" + std::to_string(c),
           "write rows: " + std::to_string(rows) + ", cols: " + std::to_string(cols) + " and " +
               std::to_string(rows * cols) + " values, row by row");
  }
  const std::vector<double> v = data.Numbers(rows * cols, "give rows × cols = " + std::to_string(rows * cols) +
                                                              " values, row by row");
  Eigen::MatrixXd m(rows, cols);
  for (int i = 0; i < rows * cols; ++i) m(i / cols, i % cols) = v[i];
  return m;
}

int ReadSide(const YamlField& f, std::string_view what) {
  f.Require("add image_width and image_height: the size in pixels of the images the camera was calibrated with");
  const double v = f.Number();
  if (const auto problem = ImageSideProblem(v, what)) f.Fail(problem->reason, problem->fix);
  return static_cast<int>(v);
}

void WriteMatrix(std::string& out, std::string_view key, const Eigen::MatrixXd& m) {
  out += std::string(key) + ":\n  rows: " + std::to_string(m.rows()) + "\n  cols: " + std::to_string(m.cols()) +
         "\n  data: [";
  for (Eigen::Index i = 0; i < m.size(); ++i) {
    out += (i ? ", " : "") + YamlFloat(m(i / m.cols(), i % m.cols()));
  }
  out += "]\n";
}

}  // namespace

RosCameraInfo RosCameraInfoFromText(const std::string& text, const std::string& name, LengthUnit length_unit) {
  const YamlNode root = ParseYamlMap(text, name, kRosWhat);
  const YamlField top = RootField(root, name);
  RosCameraInfo info;
  const ImageSize size{ReadSide(top.Member("image_width"), "width"), ReadSide(top.Member("image_height"), "height")};
  if (const YamlField n = top.Member("camera_name"); n.present()) info.camera.name = n.String();
  const YamlField kf = top.Member("camera_matrix");
  const Eigen::Matrix3d K = ReadRosMatrix(kf, 3, 3, false, "the 3×3 camera matrix K");
  if (const auto problem = CameraMatrixProblem(K)) kf.Fail(problem->reason, problem->fix);

  const YamlField model = top.Member("distortion_model");
  model.Require("add distortion_model: plumb_bob (5 coefficients), rational_polynomial (8) or equidistant (4)");
  const std::string model_name = model.String();
  int n = 0;
  if (model_name == kPlumbBob) {
    n = 5;
  } else if (model_name == kRational) {
    n = 8;
  } else if (model_name == kEquidistant) {
    n = 4;  // image_geometry's cv::fisheye k1, k2, k3, k4: vstcal's "kannala-brandt"
  } else {
    model.Fail("unknown distortion model \"" + model_name + "\"",
               "write plumb_bob (5 coefficients), rational_polynomial (8) or equidistant (4), the ROS models vstcal has");
  }
  const YamlField df = top.Member("distortion_coefficients");
  const Eigen::MatrixXd D = ReadRosMatrix(df, 1, n, true, "the " + model_name + " coefficients");
  const std::vector<double> coefficients(D.data(), D.data() + D.size());

  const YamlField rf = top.Member("rectification_matrix");
  info.rectification = ReadRosMatrix(rf, 3, 3, false, "the 3×3 rectification rotation R (identity for one camera)");
  if (!IsRotation(info.rectification, 1e-6)) {
    rf.Fail("not a rotation matrix (RᵀR ≠ I or det R < 0, tolerance 1e-6)",
            "write the rectification rotation with at least 7 significant digits (identity for one camera)");
  }
  info.projection = ReadRosMatrix(top.Member("projection_matrix"), 3, 4, false,
                               "the 3×4 projection matrix P ([K | 0] for one camera)");

  info.camera.camera = model_name == kEquidistant ? Camera::FromK(K, size, KannalaBrandtModel{}, coefficients)
                                                  : CameraFromOpenCv(K, size, coefficients);
  info.camera.length_unit = length_unit;
  info.camera.method = "ros";
  return info;
}

ImportedCamera ImportRosCameraInfo(const RosCameraInfo& info, const std::string& name) {
  ImportedCamera out;
  out.camera = info.camera;
  Matrix34d mono = Matrix34d::Zero();
  mono.leftCols<3>() = info.camera.camera.K();
  if (info.rectification != Eigen::Matrix3d::Identity() || info.projection != mono) {
    out.notes.push_back(name +
                        ": rectification_matrix, projection_matrix: not kept (R ≠ I or P ≠ [K | 0]): camera@1 holds the "
                        "raw camera; a stereo@1 rig written as ROS gets its rectification from the rig");
  }
  return out;
}

ImportedCamera ReadRosCameraInfo(const std::filesystem::path& path, LengthUnit length_unit) {
  const std::string name = path.string();
  return ImportRosCameraInfo(RosCameraInfoFromText(ReadInputFile(path, kRosWhat, limits::kMaxOpenCvYamlBytes, "ROS camera_info YAML"), name, length_unit), name);
}

ExportedCamera RosCameraInfoText(const RosCameraInfo& info, std::string_view source, const Provenance& provenance) {
  const Camera& c = info.camera.camera;
  RefuseSkew(c, source, "ROS (image_geometry, through OpenCV)");
  ExportedCamera out;
  std::string& t = out.text;
  t = "# " + ProvenanceComment(provenance) + "\n";
  t += "image_width: " + std::to_string(c.image_size.width) + "\n";
  t += "image_height: " + std::to_string(c.image_size.height) + "\n";
  if (!info.camera.name.empty()) t += "camera_name: " + YamlString(info.camera.name) + "\n";
  WriteMatrix(t, "camera_matrix", c.K());
  // plumb_bob holds "none" and "radial-tangential" (k3 included), rational_polynomial "rational",
  // equidistant "kannala-brandt" (k1…k4 as they are).
  const bool fisheye = !HasOpenCvDistortion(c);
  const int n = fisheye ? 4 : LensModelNumParams(c.model) - kNumIntrinsicParams > 5 ? 8 : 5;
  if (c.distortion().empty()) {
    out.notes.push_back(std::string(source) + ": distortion: \"none\" is written as plumb_bob with five zeros: "
                                              "ROS has no model without distortion");
  }
  t += "distortion_model: " + std::string(fisheye ? kEquidistant : n == 5 ? kPlumbBob : kRational) + "\n";
  const std::vector<double> d =
      fisheye ? std::vector<double>(c.distortion().begin(), c.distortion().end()) : OpenCvDistortion(c, n);
  WriteMatrix(t, "distortion_coefficients", Eigen::Map<const Eigen::RowVectorXd>(d.data(), n));
  WriteMatrix(t, "rectification_matrix", info.rectification);
  WriteMatrix(t, "projection_matrix", info.projection);
  if (info.camera.camera_from_world) {
    out.notes.push_back(std::string(source) + ": camera_from_world: not written: camera_info holds no extrinsics");
  }
  return out;
}

ExportedCamera RosCameraInfoText(const CalibratedCamera& camera, std::string_view source, const Provenance& provenance) {
  RosCameraInfo info;
  info.camera = camera;
  info.projection.leftCols<3>() = camera.camera.K();
  return RosCameraInfoText(info, source, provenance);
}

}  // namespace vstcal
