#include "vstcal/estimators/uncertainty.h"

#include <Eigen/Eigenvalues>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

// ∂q/∂θ (intrinsics, 2 × kNumParams) and ∂q/∂p (2 × 3) at a camera-frame point, by Jets through
// the lens model's one projection.
struct ProjectionJacobian {
  Eigen::Vector2d q;
  Eigen::MatrixXd d_intrinsics;
  Eigen::Matrix<double, 2, 3> d_point;
};

std::optional<ProjectionJacobian> Differentiate(const Camera& camera, const Eigen::Vector3d& p_cam) {
  return std::visit(
      [&](auto model) -> std::optional<ProjectionJacobian> {
        using Model = decltype(model);
        constexpr int n = Model::kNumParams;
        using Jet = ceres::Jet<double, n + 3>;
        Jet params[n], point[3], q[2];
        for (int i = 0; i < n; ++i) params[i] = Jet(camera.params[i], i);
        for (int i = 0; i < 3; ++i) point[i] = Jet(p_cam(i), n + i);
        if (!Model::Project(params, point, q)) return std::nullopt;
        ProjectionJacobian J;
        J.q = Eigen::Vector2d(q[0].a, q[1].a);
        J.d_intrinsics.resize(2, n);
        for (int r = 0; r < 2; ++r) {
          J.d_intrinsics.row(r) = q[r].v.head(n).transpose();
          J.d_point.row(r) = q[r].v.tail(3).transpose();
        }
        return J;
      },
      camera.model);
}

// ∂q/∂θ over the covariance's named parameters (intrinsics; pose tangents get their columns from
// AddPose).
struct Propagation {
  Eigen::MatrixXd J;
  std::vector<PoseJacobian> poses;
};

Propagation IntrinsicColumns(const CalibratedCamera& c, const ProjectionJacobian& pj) {
  const ParameterCovariance& cov = *c.covariance;
  Propagation out{Eigen::MatrixXd::Zero(2, static_cast<Eigen::Index>(cov.parameters.size())), {}};
  const auto names = LensModelParamNames(c.camera.model);
  for (size_t i = 0; i < names.size(); ++i) {
    if (const auto index = cov.Find(names[i])) out.J.col(*index) = pj.d_intrinsics.col(static_cast<Eigen::Index>(i));
  }
  return out;
}

// Adds ∂q/∂(pose tangent) for a point p_cam = pose · X, scaled by `weight`: a left perturbation
// moves p_cam by ω × p_cam + ρ, so ∂p/∂ω = −[p]×, ∂p/∂ρ = I. The tangent is either six named
// parameters or a pose block of the covariance.
void AddPose(const ParameterCovariance& cov, const std::string& pose, const Eigen::Matrix<double, 2, 3>& d_point,
             const Eigen::Vector3d& p_cam, double weight, Propagation* out) {
  Eigen::Matrix<double, 2, 6> d_pose;
  d_pose << -d_point * Hat(p_cam), d_point;
  d_pose *= weight;
  if (const auto block = cov.FindPose(pose)) {
    out->poses.push_back({*block, d_pose});
    return;
  }
  const char* axes[6] = {"rx", "ry", "rz", "tx", "ty", "tz"};
  for (int k = 0; k < 6; ++k) {
    if (const auto index = cov.Find(pose + "." + axes[k])) out->J.col(*index) += d_pose.col(k);
  }
}

Ellipse Propagate(const CalibratedCamera& c, const Propagation& p) {
  return EllipseFromCovariance(PropagateCovariance(*c.covariance, p.J, p.poses));
}

bool HasCovariance(const CalibratedCamera& c) { return c.covariance && !c.covariance->empty(); }

}  // namespace

Ellipse EllipseFromCovariance(const Eigen::Matrix2d& covariance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(covariance);
  Ellipse e;
  e.covariance = covariance;
  e.sigma_minor_px = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  e.sigma_major_px = std::sqrt(std::max(0.0, eig.eigenvalues()(1)));
  const Eigen::Vector2d axis = eig.eigenvectors().col(1);
  double angle = RadToDeg(std::atan2(axis.y(), axis.x()));
  if (angle <= -90) angle += 180;
  if (angle > 90) angle -= 180;
  e.angle_deg = angle;
  return e;
}

std::optional<Ellipse> ProjectionUncertaintyAtWorldPoint(const CalibratedCamera& c, const Eigen::Vector3d& point_in_world,
                                                         ProjectionUncertaintyKind kind) {
  if (!HasCovariance(c) || !c.camera_from_world) return std::nullopt;
  const Eigen::Vector3d p_cam = *c.camera_from_world * point_in_world;
  const auto pj = Differentiate(c.camera, p_cam);
  if (!pj) return std::nullopt;
  Propagation p = IntrinsicColumns(c, *pj);
  if (kind == ProjectionUncertaintyKind::kWithPoses) AddPose(*c.covariance, "camera_from_world", pj->d_point, p_cam, 1.0, &p);
  return Propagate(c, p);
}

std::optional<Ellipse> ProjectionUncertaintyAtPixel(const CalibratedCamera& c, const Eigen::Vector2d& pixel, double depth,
                                                    ProjectionUncertaintyKind kind) {
  if (!HasCovariance(c)) return std::nullopt;
  const auto ray = c.camera.Unproject(pixel);
  if (!ray) return std::nullopt;
  const Eigen::Vector3d p_cam = depth * *ray;
  if (c.camera_from_world) return ProjectionUncertaintyAtWorldPoint(c, c.camera_from_world->inverse() * p_cam, kind);
  const auto pj = Differentiate(c.camera, p_cam);
  if (!pj) return std::nullopt;
  Propagation p = IntrinsicColumns(c, *pj);
  if (kind == ProjectionUncertaintyKind::kWithPoses) {
    // Each board frame carries the point back to (nominally) p_cam; the perturbed positions are
    // averaged, so each view's tangent enters with weight 1/V.
    const double weight = c.views.empty() ? 0.0 : 1.0 / static_cast<double>(c.views.size());
    for (size_t v = 0; v < c.views.size(); ++v) {
      AddPose(*c.covariance, "views[" + std::to_string(v) + "].camera_from_board", pj->d_point, p_cam, weight, &p);
    }
  }
  return Propagate(c, p);
}

std::optional<Eigen::MatrixXd> IntrinsicsJacobianAt(const CalibratedCamera& c, const Eigen::Vector3d& p_cam) {
  if (!HasCovariance(c)) return std::nullopt;
  const auto pj = Differentiate(c.camera, p_cam);
  if (!pj) return std::nullopt;
  return IntrinsicColumns(c, *pj).J;
}

std::vector<UncertaintyCell> ProjectionUncertaintyGrid(const CalibratedCamera& c, double depth, int cols, int rows,
                                                       ProjectionUncertaintyKind kind) {
  VSTCAL_CHECK(cols > 0 && rows > 0, "grid size");
  std::vector<UncertaintyCell> cells;
  const ImageSize& size = c.camera.image_size;
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < cols; ++i) {
      const Eigen::Vector2d px(-0.5 + size.width * (i + 0.5) / cols, -0.5 + size.height * (j + 0.5) / rows);
      if (const auto e = ProjectionUncertaintyAtPixel(c, px, depth, kind)) cells.push_back({px, *e});
    }
  }
  return cells;
}

}  // namespace vstcal
