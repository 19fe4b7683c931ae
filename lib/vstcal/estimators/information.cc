#include "vstcal/estimators/information.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>

#include "vstcal/estimators/arrow_information.h"
#include "vstcal/estimators/length_range.h"
#include "vstcal/estimators/reprojection_cost.h"
#include "vstcal/estimators/robust_loss.h"
#include "vstcal/core/error.h"

namespace vstcal {
namespace {

// Rows of every observation into the arrow, point by point at δ = 0: [∂r/∂θ · B | ∂r/∂δ], times
// √ρ′ under a robust loss (the cost has applied √w already). Points behind the camera are
// counted and left out.
template <typename Model>
void AddObservations(const Correspondences& c, const std::vector<double>& params, const FreeIntrinsics& free,
                     const std::vector<Rigid3d>& poses, const ceres::LossFunction* loss, ArrowInformation* information,
                     size_t* n_behind) {
  const int m = free.size();
  std::vector<int> columns(static_cast<size_t>(m));
  std::iota(columns.begin(), columns.end(), 0);
  const Eigen::Matrix<double, Model::kNumParams, Eigen::Dynamic> B = free.basis;
  Eigen::Matrix<double, 2, Model::kNumParams, Eigen::RowMajor> d_params;
  Eigen::Matrix<double, 2, 6, Eigen::RowMajor> d_pose;
  for (size_t v = 0; v < c.views.size(); ++v) {
    const int pose = c.rig == Rig::kVolume ? 0 : static_cast<int>(v);
    const ReprojectionCost<Model> cost(c.views[v].observations, poses[pose]);
    Eigen::MatrixXd J(2 * cost.size(), m + 6);
    Eigen::Index rows = 0;
    for (size_t k = 0; k < cost.size(); ++k) {
      double r[2];
      if (!cost.EvaluatePointAtReference(k, params.data(), r, d_params.data(), d_pose.data())) {
        ++*n_behind;
        continue;
      }
      double scale = 1.0;
      if (loss) {
        double rho[3];
        loss->Evaluate(r[0] * r[0] + r[1] * r[1], rho);
        scale = std::sqrt(std::max(rho[1], 0.0));
      }
      J.block(rows, 0, 2, m) = scale * (d_params * B);
      J.block<2, 6>(rows, m) = scale * d_pose;
      rows += 2;
    }
    if (rows > 0) information->AddRows(columns, pose, J.topRows(rows));
  }
}

bool IsDistortion(const std::string& name) {
  return name != "f" && name != "fx" && name != "fy" && name != "cx" && name != "cy" && name != "s";
}

// "k3", "cx and cy", "f, cx and cy".
std::string Join(const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) list += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return list;
}

// What carries (almost) no information, along the scaled weakest direction (its components above
// 0.2, largest first), and what to hold or add: "<names> are <state> by these points (they can
// move together along …); <advice>". One line.
std::string DescribeWeakest(const ArrowObservability& verdict, const FreeIntrinsics& free, const Correspondences& c,
                            const RefineOptions& options, const std::string& state) {
  if (verdict.singular_pose) {
    const int v = *verdict.singular_pose;
    const std::string which = c.rig == Rig::kVolume ? "the camera pose" : "view \"" + c.views[v].name + "\"";
    if (const auto range = LengthsOutOfRange(c, c.rig == Rig::kVolume ? std::nullopt : std::optional<size_t>(v))) {
      return "the points do not determine " + which + " (" + PoseName(c, static_cast<size_t>(v)) + ") in double precision: " +
             *range + "; give the points in another length unit";
    }
    return "the points do not determine " + which + " (" + PoseName(c, static_cast<size_t>(v)) +
           ": too few points, or all on one line); " + (c.rig == Rig::kVolume ? "add points" : "remove the view or add points to it");
  }
  std::vector<int> order(static_cast<size_t>(free.size()));
  std::iota(order.begin(), order.end(), 0);
  const Eigen::VectorXd& d = verdict.weakest_direction;
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return std::abs(d(a)) > std::abs(d(b)); });
  std::vector<std::string> names;
  std::string direction;
  const double sign = d(order[0]) < 0 ? -1.0 : 1.0;  // the largest component written positive
  for (int i : order) {
    if (std::abs(d(i)) < 0.2 || names.size() == 5) break;
    names.push_back(free.names[i]);
    char term[64];
    std::snprintf(term, sizeof term, "%s%.2f %s", direction.empty() ? "" : sign * d(i) < 0 ? " - " : " + ",
                  direction.empty() ? sign * d(i) : std::abs(d(i)), free.names[i].c_str());
    direction += term;
  }
  char eigenvalue[48];
  std::snprintf(eigenvalue, sizeof eigenvalue, "%.2g", verdict.smallest_eigenvalue);
  std::string message = Join(names) + (names.size() == 1 ? " is " : " are ") + state +
                        " by these points (smallest eigenvalue of the scaled information " + eigenvalue +
                        "; they can move together along " + direction + ", in units of their own information); ";
  std::vector<std::string> advice;
  std::vector<std::string> terms;
  for (const std::string& n : names) {
    if (IsDistortion(n)) terms.push_back(n);
  }
  if (!terms.empty()) {
    advice.push_back("estimate fewer distortion terms (leave " + Join(terms) + " out) or add points nearer the image's edges");
  }
  if (std::find(names.begin(), names.end(), "s") != names.end()) advice.push_back("estimate no skew");
  const bool geometry = std::any_of(names.begin(), names.end(), [](const std::string& n) {
    return n == "f" || n == "fx" || n == "fy" || n == "cx" || n == "cy";
  });
  if (geometry) {
    const bool centre = std::find(names.begin(), names.end(), "cx") != names.end() ||
                        std::find(names.begin(), names.end(), "cy") != names.end();
    advice.push_back(std::string(centre && options.free_principal_point ? "hold the principal point, or " : "") +
                     (c.rig == Rig::kPlanarViews ? "add views of the board tilted about other axes"
                                                 : "add points at other depths (a volume) or views at other orientations"));
  }
  for (size_t i = 0; i < advice.size(); ++i) message += (i == 0 ? "" : "; or ") + advice[i];
  return message;
}

}  // namespace

std::string PoseName(const Correspondences& c, size_t pose) {
  return c.rig == Rig::kVolume ? "camera_from_world" : "views[" + std::to_string(pose) + "].camera_from_board";
}

CalibrationCovariance CovarianceAt(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses,
                                   const RefineOptions& options, double sigma_px) {
  const size_t num_poses = c.rig == Rig::kVolume ? 1 : c.views.size();
  VSTCAL_CHECK(poses.size() == num_poses, "one pose per rig (volume) or per view");
  CalibrationCovariance out;
  out.model = RefinedModel(camera.model, options);
  const std::vector<double> params = PromotedParams(camera, out.model);
  out.free = MakeFreeIntrinsics(out.model, options);
  const int m = out.free.size();

  ArrowInformation information(m, static_cast<int>(num_poses));
  const std::unique_ptr<ceres::LossFunction> loss = MakeLoss(options);
  std::visit(
      [&](auto model) {
        AddObservations<decltype(model)>(c, params, out.free, poses, loss.get(), &information, &out.n_behind);
      },
      out.model);
  // Each prior's information 1/σ_i² along its row of B, in the information's pixel scale (σ̂² M⁻¹
  // with M = JᵀWJ + Σ (σ̂/σ_i)² b_i b_iᵀ is (JᵀWJ/σ̂² + Σ b_i b_iᵀ/σ_i²)⁻¹): rows with no pose
  // column, so they fold into the globals (docs/math/uncertainty.md#priors).
  const std::vector<ResolvedPrior> priors = ResolvePriors(out.model, out.free, options);
  if (!priors.empty()) {
    std::vector<int> columns(static_cast<size_t>(m));
    std::iota(columns.begin(), columns.end(), 0);
    Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(priors.size()), m + 6);
    for (size_t k = 0; k < priors.size(); ++k) {
      rows.row(static_cast<Eigen::Index>(k)).head(m) = (sigma_px / priors[k].sigma) * out.free.basis.row(priors[k].index);
    }
    information.AddRows(columns, 0, rows);
  }
  const ArrowInverse inverse = InvertArrow(information, sigma_px * sigma_px);
  out.smallest_scaled_eigenvalue = inverse.observability.smallest_eigenvalue;
  if (!inverse.observability.observable) {
    out.weakest = DescribeWeakest(inverse.observability, out.free, c, options, "not determined");
    out.message = "the information matrix is singular: " + out.weakest;
    return out;
  }
  if (out.smallest_scaled_eigenvalue < kWeaklyDetermined && out.free.size() > 0) {
    out.weakest = DescribeWeakest(inverse.observability, out.free, c, options, "barely determined");
  }
  out.observable = true;
  out.free_covariance = inverse.covariance.global;

  // Over the lens parameters β moves: Σ_θ = B Σ_β Bᵀ and Cov(δ_v, θ) = Cov(δ_v, β) Bᵀ, rows of B
  // that are not zero.
  const Eigen::MatrixXd B = out.free.MovedBasis();
  const Eigen::Index n = B.rows();
  ParameterCovariance& cov = out.covariance;
  for (std::string& name : out.free.MovedParams(out.model)) cov.parameters.push_back(std::move(name));
  const Eigen::MatrixXd intrinsics = B * out.free_covariance * B.transpose();
  if (c.rig == Rig::kVolume) {
    // One pose: its tangents are named parameters beside the intrinsics (the full matrix is small).
    cov.matrix.resize(n + 6, n + 6);
    cov.matrix.topLeftCorner(n, n) = intrinsics;
    cov.matrix.bottomLeftCorner(6, n) = inverse.covariance.pose_global[0] * B.transpose();
    cov.matrix.topRightCorner(n, 6) = cov.matrix.bottomLeftCorner(6, n).transpose();
    cov.matrix.bottomRightCorner<6, 6>() = inverse.covariance.pose[0];
    for (const char* axis : {"rx", "ry", "rz", "tx", "ty", "tz"}) cov.parameters.push_back(PoseName(c, 0) + "." + axis);
  } else {
    cov.matrix = intrinsics;
    cov.poses.resize(num_poses);
    for (size_t v = 0; v < num_poses; ++v) {
      cov.poses[v] = {PoseName(c, v), inverse.covariance.pose[v], inverse.covariance.pose_global[v] * B.transpose()};
    }
  }
  cov.matrix = (0.5 * (cov.matrix + cov.matrix.transpose())).eval();
  return out;
}

}  // namespace vstcal
