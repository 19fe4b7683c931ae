#include "vstcal/formats/camera/camera_io.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "vstcal/estimators/decompose.h"
#include "vstcal/camera/intrinsics.h"
#include "vstcal/core/limits.h"
#include "vstcal/core/suggest.h"
#include "vstcal/geometry/linalg.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr std::string_view kCameraFormat = "vstcal/camera@1";
constexpr double kAgreement = 1e-6;  // relative agreement required between redundant fields

bool Agrees(double a, double b, double scale) { return std::abs(a - b) <= kAgreement * std::max(1.0, scale); }

Eigen::Matrix3d ReadK(const JsonNode& node) {
  const Eigen::Matrix3d K = node.Matrix<3, 3>();
  if (const auto problem = CameraMatrixProblem(K)) node.Fail(problem->reason, problem->fix);
  return K;
}

void CheckIntrinsicsAgree(const JsonNode& node, const Eigen::Matrix3d& K) {
  SkewForm f;
  f.fu = node.at("fu").PositiveNumber();
  f.fv = node.at("fv").PositiveNumber();
  f.u0 = node.at("u0").Number();
  f.v0 = node.at("v0").Number();
  const double theta_deg = node.at("skew_angle_deg").Number();
  if (!(theta_deg > 0 && theta_deg < 180)) node.at("skew_angle_deg").Fail("must lie in (0, 180)", "90 means no skew");
  f.theta_rad = DegToRad(theta_deg);
  const Eigen::Matrix3d K2 = KFromSkewForm(f);
  const double scale = K.cwiseAbs().maxCoeff();
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (!Agrees(K(r, c), K2(r, c), scale)) {
        node.Fail("disagrees with K (K is authoritative)", "delete \"intrinsics\" or make it match K");
      }
    }
  }
}

std::vector<double> ReadDistortion(const JsonNode& node, AnyLensModel* model) {
  node.ExpectObject();
  const JsonNode name = node.at("model");
  const auto found = LensModelFromName(name.String());
  if (!found) name.Fail("unknown distortion model \"" + name.String() + "\"", "use one of " + KnownLensModelNames());
  *model = *found;
  const auto names = LensModelParamNames(*model);
  std::vector<double> coefficients;
  for (size_t i = kNumIntrinsicParams; i < names.size(); ++i) coefficients.push_back(node.at(names[i]).Number());
  return coefficients;
}

constexpr std::string_view kTangentAxes[] = {"rx", "ry", "rz", "tx", "ty", "tz"};

// The pose a pose name refers to (parameter_covariance.h): "camera_from_world" or
// "views[<i>].camera_from_board"; nullopt for any other name.
struct TangentPose {
  std::optional<size_t> view;  // nullopt: camera_from_world
};

std::optional<TangentPose> PoseOfName(std::string_view name) {
  if (name == "camera_from_world") return TangentPose{};
  if (!name.starts_with("views[")) return std::nullopt;
  const size_t close = name.find(']');
  const std::string_view index = name.substr(6, close == std::string_view::npos ? 0 : close - 6);
  // More than 9 digits is no view index a file can have (and a long one would overflow stoul).
  if (index.empty() || index.size() > 9 || !std::all_of(index.begin(), index.end(), [](char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  if (name.substr(close + 1) != ".camera_from_board") return std::nullopt;
  return TangentPose{std::stoul(std::string(index))};
}

// The pose a pose-tangent name "<pose>.<axis>" refers to; nullopt for any other name.
std::optional<TangentPose> PoseOfTangentName(std::string_view name) {
  const size_t dot = name.rfind('.');
  if (dot == std::string_view::npos) return std::nullopt;
  const std::string_view axis = name.substr(dot + 1);
  if (std::find(std::begin(kTangentAxes), std::end(kTangentAxes), axis) == std::end(kTangentAxes)) return std::nullopt;
  return PoseOfName(name.substr(0, dot));
}

// A pose tangent must name a pose the file has.
void CheckTangentPoseExists(const JsonNode& name_node, const std::string& name, const TangentPose& pose,
                            const CovariancePoses& poses) {
  if (!pose.view) {
    if (!poses.camera_from_world) {
      name_node.Fail("\"" + name + "\" is a tangent of camera_from_world, which the file does not have",
                     "add \"camera_from_world\" or drop the parameter");
    }
    return;
  }
  if (*pose.view < poses.num_views) return;
  const std::string has = poses.num_views == 0 ? "the file has no views" : "the file has " + std::to_string(poses.num_views) + " views";
  const std::string fix = poses.num_views == 0 ? "add the views or drop the parameter"
                                               : "use views[0] … views[" + std::to_string(poses.num_views - 1) + "] or drop the parameter";
  name_node.Fail("\"" + name + "\" names view " + std::to_string(*pose.view) + ", but " + has, fix);
}

// A covariance read from `node` (rows as written): no negative variance (`names` name the rows),
// symmetric to 1e-9 of its largest entry.
void CheckCovarianceMatrix(const JsonNode& node, const Eigen::MatrixXd& matrix, const std::vector<std::string>& names) {
  const Eigen::Index n = matrix.rows();
  const double tolerance = 1e-9 * std::max(matrix.cwiseAbs().maxCoeff(), 1e-300);
  for (Eigen::Index r = 0; r < n; ++r) {
    if (matrix(r, r) < 0) {
      node.at(static_cast<size_t>(r)).at(static_cast<size_t>(r)).Fail("the variance of \"" + names[r] + "\" is negative", "fix the matrix");
    }
    for (Eigen::Index k = 0; k < r; ++k) {
      if (std::abs(matrix(r, k) - matrix(k, r)) > tolerance) {
        node.at(static_cast<size_t>(r)).at(static_cast<size_t>(k)).Fail(
            "differs from matrix[" + std::to_string(k) + "][" + std::to_string(r) + "]: not symmetric",
            "write a symmetric covariance matrix");
      }
    }
  }
}

// Positive semi-definite to −1e-9 of the largest |eigenvalue| (the lower triangle is read).
void CheckPositiveSemiDefinite(const JsonNode& node, const Eigen::MatrixXd& matrix, const std::string& what) {
  const Eigen::VectorXd eigenvalues = DecomposeSymmetric(matrix, /*with_vectors=*/false).values;
  const double smallest = eigenvalues.minCoeff();
  const double largest = eigenvalues.cwiseAbs().maxCoeff();
  if (smallest < -1e-9 * largest) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%snot positive semi-definite: eigenvalue %.6g < -1e-9 × largest |eigenvalue| %.6g",
                  what.c_str(), smallest, largest);
    node.Fail(buf, "write a covariance matrix (correlations within [-1, 1], no negative eigenvalue)");
  }
}

// "poses": [{"pose", "matrix" (6×6), "with_parameters" (6 × parameters)}, …]: one pose block each
// (parameter_covariance.h). Each names a pose the file has (when `poses` is known), once, and
// not also by tangents in "parameters"; its matrix is a covariance; and the joint covariance of
// the parameters and the pose is positive semi-definite — which, poses being correlated only
// through the parameters, makes the whole matrix so.
void ReadPoseBlocks(const JsonNode& node, const std::optional<CovariancePoses>& poses, ParameterCovariance* cov) {
  const size_t count = node.ArraySize();
  const Eigen::Index n = static_cast<Eigen::Index>(cov->parameters.size());
  for (size_t i = 0; i < count; ++i) {
    const JsonNode b = node.at(i);
    PoseCovariance block;
    block.pose = b.at("pose").String();
    const auto pose = PoseOfName(block.pose);
    if (!pose) {
      b.at("pose").Fail("unknown pose \"" + block.pose + "\"", "name camera_from_world or views[i].camera_from_board");
    }
    if (poses) CheckTangentPoseExists(b.at("pose"), block.pose, *pose, *poses);
    if (cov->FindPose(block.pose)) b.at("pose").Fail("duplicate pose \"" + block.pose + "\"", "give each pose one block");
    for (const std::string_view axis : kTangentAxes) {
      if (cov->Find(block.pose + "." + std::string(axis))) {
        b.at("pose").Fail("\"" + block.pose + "\" also has tangents in \"parameters\"",
                          "give a pose either tangents in parameters or a block here, not both");
      }
    }
    const JsonNode m = b.at("matrix");
    block.matrix = m.Matrix<6, 6>();
    std::vector<std::string> names;
    for (const std::string_view axis : kTangentAxes) names.push_back(block.pose + "." + std::string(axis));
    CheckCovarianceMatrix(m, block.matrix, names);
    CheckPositiveSemiDefinite(m, block.matrix, "");
    const JsonNode w = b.at("with_parameters");
    w.ArraySize(6);
    block.with_parameters.resize(6, n);
    for (size_t r = 0; r < 6; ++r) {
      const JsonNode row = w.at(r);
      row.ArraySize(static_cast<size_t>(n));
      for (Eigen::Index k = 0; k < n; ++k) block.with_parameters(static_cast<Eigen::Index>(r), k) = row.at(static_cast<size_t>(k)).Number();
    }
    Eigen::MatrixXd joint(n + 6, n + 6);
    joint << cov->matrix, block.with_parameters.transpose(), block.with_parameters, block.matrix;
    CheckPositiveSemiDefinite(b, joint, "with the parameters, ");
    cov->poses.push_back(std::move(block));
  }
}

}  // namespace

ParameterCovariance ReadCovariance(const JsonNode& node, const Camera& camera, const std::optional<CovariancePoses>& poses) {
  ParameterCovariance cov;
  const JsonNode names = node.at("parameters");
  const size_t n = names.ArraySize();
  if (n == 0) names.Fail("no parameters", "list the parameters the matrix refers to");
  const auto intrinsics = LensModelParamNames(camera.model);
  for (size_t i = 0; i < n; ++i) {
    const std::string name = names.at(i).String();
    const bool intrinsic = std::find(intrinsics.begin(), intrinsics.end(), name) != intrinsics.end();
    const auto pose = intrinsic ? std::nullopt : PoseOfTangentName(name);
    if (!intrinsic && !pose) {
      std::string lens;
      for (const std::string_view p : intrinsics) lens += (lens.empty() ? "" : ", ") + std::string(p);
      std::vector<std::string> tangents;
      for (const std::string_view axis : kTangentAxes) tangents.push_back("camera_from_world." + std::string(axis));
      std::vector<std::string_view> candidates(intrinsics.begin(), intrinsics.end());
      candidates.insert(candidates.end(), tangents.begin(), tangents.end());
      const auto near = ClosestMatch(name, candidates);
      const std::string known = lens + " for this lens model, camera_from_world.rx … tz or views[i].camera_from_board.rx … tz";
      names.at(i).Fail("unknown parameter \"" + name + "\"",
                       near ? "did you mean \"" + std::string(*near) + "\"? (known: " + known + ")" : "use " + known);
    }
    if (pose && poses) CheckTangentPoseExists(names.at(i), name, *pose, *poses);
    if (cov.Find(name)) names.at(i).Fail("duplicate parameter \"" + name + "\"", "list each parameter once");
    cov.parameters.push_back(name);
  }
  ParameterCovariance read = ReadCovarianceMatrix(node, std::move(cov.parameters));
  if (const auto blocks = node.find("poses")) ReadPoseBlocks(*blocks, poses, &read);
  return read;
}

ParameterCovariance ReadCovarianceMatrix(const JsonNode& node, std::vector<std::string> names) {
  ParameterCovariance cov;
  cov.parameters = std::move(names);
  const size_t n = cov.parameters.size();
  const JsonNode m = node.at("matrix");
  m.ArraySize(n);
  cov.matrix.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (size_t r = 0; r < n; ++r) {
    const JsonNode row = m.at(r);
    row.ArraySize(n);
    for (size_t k = 0; k < n; ++k) cov.matrix(r, k) = row.at(k).Number();
  }
  CheckCovarianceMatrix(m, cov.matrix, cov.parameters);
  // Symmetric to that tolerance, so the lower triangle the solvers read is the matrix.
  CheckPositiveSemiDefinite(m, cov.matrix, "");
  return cov;
}


std::optional<FieldProblem> CameraMatrixProblem(const Eigen::Matrix3d& K) {
  if (K(1, 0) != 0 || K(2, 0) != 0 || K(2, 1) != 0 || K(2, 2) != 1) {
    return FieldProblem{"K must be upper triangular with K[2][2] = 1", "write K as [[fx, s, cx], [0, fy, cy], [0, 0, 1]]"};
  }
  if (!(K(0, 0) > 0) || !(K(1, 1) > 0)) return FieldProblem{"fx and fy must be positive", "check the signs of K[0][0] and K[1][1]"};
  return std::nullopt;
}

std::optional<FieldProblem> PoseProblem(const Eigen::Matrix3d& K, const Rigid3d& camera_from_world) {
  if (ProjectionMatrix(K, camera_from_world).allFinite()) return std::nullopt;
  return FieldProblem{"the translation is so large that K [R | t] overflows a double",
                      "give the translation in a larger length unit"};
}

Camera ReadCameraIntrinsics(const JsonNode& node) {
  const ImageSize size = ReadImageSize(node.at("image_size"));
  const Eigen::Matrix3d K = ReadK(node.at("K"));
  if (auto intrinsics = node.find("intrinsics")) CheckIntrinsicsAgree(*intrinsics, K);
  AnyLensModel model;
  const std::vector<double> coefficients = ReadDistortion(node.at("distortion"), &model);
  return Camera::FromK(K, size, model, coefficients);
}

CalibratedCamera CameraFromJson(const JsonDocument& doc) { return CameraFromNode(doc.root()); }

CalibratedCamera CameraFromNode(const JsonNode& root) {
  root.ExpectObject();
  CheckFormat(root, kCameraFormat);
  CalibratedCamera c;
  if (auto name = root.find("camera")) c.name = name->String();
  c.length_unit = ReadLengthUnit(root.at("length_unit"));
  c.method = root.at("method").String();
  c.camera = ReadCameraIntrinsics(root);
  if (auto pose = root.find("camera_from_world")) {
    c.camera_from_world = ReadRigid(*pose);
    if (const auto problem = PoseProblem(c.camera.K(), *c.camera_from_world)) pose->at("t").Fail(problem->reason, problem->fix);
  }
  if (auto views = root.find("views")) {
    const size_t n = views->ArraySize();
    if (n > limits::kMaxViews) {
      views->Fail(std::to_string(n) + " views, more than the " + std::to_string(limits::kMaxViews) + " vstcal reads",
                  "keep a subset of the views");
    }
    for (size_t i = 0; i < n; ++i) {
      const JsonNode v = views->at(i);
      ViewPose pose;
      pose.name = v.at("name").String();
      pose.camera_from_board = ReadRigid(v.at("camera_from_board"));
      if (auto rms = v.find("rms_px")) pose.rms_px = rms->NonNegativeNumber();
      c.views.push_back(std::move(pose));
    }
  }
  if (auto cov = root.find("covariance")) {
    c.covariance = ReadCovariance(*cov, c.camera, CovariancePoses{c.camera_from_world.has_value(), c.views.size()});
  }
  if (auto P = root.find("P")) {
    Matrix34d m = P->Matrix<3, 4>();
    const double det = m.leftCols<3>().determinant();
    if (!(std::abs(det) > 0) || !(m.row(2).head<3>().norm() > 0)) {
      P->Fail("P(:, 0:3) is singular", "write a valid projection matrix K [R | t]");
    }
    // The overall sign of a stored P is free: the canonical one has det P(:, 0:3) > 0. A P already
    // scaled to a unit third row (to 4 ulps, as written) keeps its bits: dividing by a norm of
    // 1 ± 1 ulp would change them on every read.
    const double sign = det > 0 ? 1.0 : -1.0;
    if (std::abs(m.row(2).head<3>().norm() - 1) <= 4 * std::numeric_limits<double>::epsilon()) {
      m *= sign;
    } else {
      m = NormalizeProjectionScale(m, sign);
    }
    if (!m.allFinite() || std::abs(m.row(2).head<3>().norm() - 1) > kAgreement) {
      P->Fail("its third row cannot be scaled to unit length (entries near the limits of a double)",
              "write P scaled so that the first three entries of its third row have unit norm");
    }
    const auto decomposed = DecomposeProjection(m);
    const Matrix34d expected = c.camera_from_world ? ProjectionMatrix(c.camera.K(), *c.camera_from_world)
                                                   : decomposed ? ProjectionMatrix(decomposed->K, decomposed->camera_from_world)
                                                                : m;
    // The 3×3 block (≈ K R, px) and the last column (≈ K t, px·length) have different scales:
    // compare each against its own.
    const double block_scale = expected.leftCols<3>().cwiseAbs().maxCoeff();
    const double column_scale = std::max(block_scale, expected.col(3).cwiseAbs().maxCoeff());
    if ((m.leftCols<3>() - expected.leftCols<3>()).cwiseAbs().maxCoeff() > kAgreement * block_scale ||
        (m.col(3) - expected.col(3)).cwiseAbs().maxCoeff() > kAgreement * column_scale) {
      P->Fail("disagrees with K [R | t]", "delete \"P\" or make it match K and camera_from_world");
    }
    if (!c.camera_from_world && decomposed && !(decomposed->K - c.camera.K()).isZero(kAgreement * block_scale)) {
      P->Fail("its intrinsic part disagrees with K", "delete \"P\" or make it match K");
    }
    c.P = m;
  }
  return c;
}

CalibratedCamera ReadCamera(const std::filesystem::path& path) { return CameraFromJson(JsonDocument::Load(path)); }

OrderedJson DistortionToJson(const Camera& camera) {
  OrderedJson d;
  d["model"] = LensModelName(camera.model);
  const auto names = LensModelParamNames(camera.model);
  for (size_t i = kNumIntrinsicParams; i < names.size(); ++i) d[std::string(names[i])] = camera.params[i];
  return d;
}

OrderedJson FitToJson(const Fit& fit) {
  OrderedJson j;
  j["rms_px"] = fit.overall.rms_px;
  j["max_px"] = fit.overall.max_px;
  j["n_points"] = fit.overall.n_points;
  j["n_behind_camera"] = fit.n_behind_camera;
  OrderedJson views = OrderedJson::array();
  for (const ViewFit& v : fit.views) {
    views.push_back({{"name", v.name}, {"rms_px", v.stats.rms_px}, {"max_px", v.stats.max_px}, {"n_points", v.stats.n_points}});
  }
  j["views"] = std::move(views);
  if (fit.volume) j["volume"] = MeasuredVolumeToJson(*fit.volume);
  OrderedJson tests = OrderedJson::array();
  for (const TestPointFit& t : fit.test_points) {
    OrderedJson jt;
    jt["name"] = t.name;
    jt["world"] = MatrixToJson(t.point_in_world);
    jt["predicted"] = t.predicted ? MatrixToJson(*t.predicted) : OrderedJson(nullptr);
    jt["measured"] = t.measured ? MatrixToJson(*t.measured) : OrderedJson(nullptr);
    const auto error = t.error_px();
    jt["error_px"] = error ? OrderedJson(*error) : OrderedJson(nullptr);
    jt["inside_volume"] = t.inside_volume ? OrderedJson(*t.inside_volume) : OrderedJson(nullptr);
    tests.push_back(std::move(jt));
  }
  j["test_points"] = std::move(tests);
  return j;
}

OrderedJson MeasuredVolumeToJson(const MeasuredVolume& volume) {
  return {{"hull", volume.status}, {"vertices", volume.vertices}, {"facets", volume.facets}};
}

OrderedJson CameraToJson(const CalibratedCamera& c, const Provenance& provenance, const OrderedJson& extra) {
  OrderedJson j;
  j["format"] = kCameraFormat;
  if (!c.name.empty()) j["camera"] = c.name;
  j["image_size"] = {c.camera.image_size.width, c.camera.image_size.height};
  j["length_unit"] = LengthUnitName(c.length_unit);
  j["method"] = c.method;
  const Eigen::Matrix3d K = c.camera.K();
  j["K"] = MatrixToJson(K);
  const SkewForm f = SkewFormFromK(K);
  j["intrinsics"] = {{"fu", f.fu}, {"fv", f.fv}, {"u0", f.u0}, {"v0", f.v0},
                     {"skew_angle_deg", RadToDeg(f.theta_rad)}};
  j["distortion"] = DistortionToJson(c.camera);
  if (c.camera_from_world) {
    j["camera_from_world"] = RigidToJson(*c.camera_from_world);
    j["P"] = MatrixToJson(c.P ? *c.P : ProjectionMatrix(K, *c.camera_from_world));
  }
  if (!c.views.empty()) {
    OrderedJson views = OrderedJson::array();
    for (const ViewPose& v : c.views) {
      views.push_back({{"name", v.name}, {"camera_from_board", RigidToJson(v.camera_from_board)}, {"rms_px", v.rms_px}});
    }
    j["views"] = std::move(views);
  }
  if (c.fit) j["fit"] = FitToJson(*c.fit);
  if (c.covariance) {
    j["covariance"] = {{"parameters", c.covariance->parameters}, {"matrix", MatrixToJson(c.covariance->matrix)}};
    if (!c.covariance->poses.empty()) {
      OrderedJson poses = OrderedJson::array();
      for (const PoseCovariance& p : c.covariance->poses) {
        poses.push_back({{"pose", p.pose}, {"matrix", MatrixToJson(p.matrix)}, {"with_parameters", MatrixToJson(p.with_parameters)}});
      }
      j["covariance"]["poses"] = std::move(poses);
    }
  }
  for (const auto& [key, value] : extra.items()) j[key] = value;
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
