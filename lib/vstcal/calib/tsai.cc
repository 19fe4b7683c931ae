#include "vstcal/calib/tsai.h"
#include "vstcal/core/option_name.h"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

std::string Format(const char* fmt, double a, double b = 0) {
  char buf[400];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

// Sensor data of one point: world point (moved to the working frame) and distorted sensor
// coordinates.
struct SensorPoint {
  Eigen::Vector3d X;
  double xd = 0, yd = 0;
};

// Tsai's stage 3: f, Tz and κ₁ by nonlinear least squares in undistorted sensor coordinates,
// R, Tx, Ty fixed. Residuals X_d(1 + κ₁r²) − f x/(w + Tz) and likewise for Y.
struct Stage3Cost {
  const std::vector<SensorPoint>* points;
  const Rigid3d* pose;  // with t.z unused

  template <typename T>
  bool operator()(const T* p, T* residuals) const {
    const T& f = p[0];
    const T& tz = p[1];
    const T& kappa = p[2];
    for (size_t i = 0; i < points->size(); ++i) {
      const SensorPoint& s = (*points)[i];
      const Eigen::Vector3d c = pose->R * s.X;
      const T depth = c.z() + tz;
      if (!(depth > T(0))) return false;
      const T radial = T(1) + kappa * (s.xd * s.xd + s.yd * s.yd);
      residuals[2 * i] = s.xd * radial - f * (c.x() + pose->t.x()) / depth;
      residuals[2 * i + 1] = s.yd * radial - f * (c.y() + pose->t.y()) / depth;
    }
    return true;
  }
};

// Stage 2: f and Tz from X_d(w + Tz) = f x and Y_d(w + Tz) = f y (distortion ignored), by linear
// least squares over both equations of every point (Tsai uses the Y equation only; with sx known
// the X equation is as good and halves the variance).
bool SolveFocalAndDepth(const std::vector<SensorPoint>& points, const Rigid3d& pose, double* f, double* tz,
                        double* residual = nullptr) {
  Eigen::MatrixXd A(2 * points.size(), 2);
  Eigen::VectorXd b(2 * points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d c = pose.R * points[i].X;
    const double x = c.x() + pose.t.x(), y = c.y() + pose.t.y(), w = c.z();
    A.row(2 * i) << x, -points[i].xd;
    A.row(2 * i + 1) << y, -points[i].yd;
    b(2 * i) = w * points[i].xd;
    b(2 * i + 1) = w * points[i].yd;
  }
  const LeastSquaresSolution ls = SolveLeastSquares(A, b, 1e-10);
  if (ls.rank < 2) return false;
  const Eigen::Vector2d sol = ls.x;
  *f = sol(0);
  *tz = sol(1);
  if (residual) *residual = (A * sol - b).norm();
  return std::isfinite(*f) && std::isfinite(*tz);
}

// The sign of Ty: with Ty > 0 assumed, the point farthest from the principal point must project
// on the same side as it was seen (x and X_d, y and Y_d of equal signs).
double TySign(const std::vector<SensorPoint>& points, const Eigen::Matrix<double, 2, 3>& rows12, double tx, double ty) {
  size_t far = 0;
  for (size_t i = 1; i < points.size(); ++i) {
    if (points[i].xd * points[i].xd + points[i].yd * points[i].yd >
        points[far].xd * points[far].xd + points[far].yd * points[far].yd) {
      far = i;
    }
  }
  const double x = rows12.row(0).dot(points[far].X) + tx, y = rows12.row(1).dot(points[far].X) + ty;
  return (x * points[far].xd >= 0 && y * points[far].yd >= 0) ? 1.0 : -1.0;
}

// Points with depth ≤ 0 for the rotation of `pose` and depth offset `tz`; sets out->n_behind and
// out->deepest_behind.
size_t CountBehind(const std::vector<SensorPoint>& points, const Rigid3d& pose, double tz, TsaiResult* out) {
  double deepest = INFINITY;
  out->n_behind = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    const double depth = (pose.R * points[i].X).z() + tz;
    if (depth > 0) continue;
    ++out->n_behind;
    if (depth < deepest) deepest = depth, out->deepest_behind = i;
  }
  return out->n_behind;
}

// f and Tz by stage 2 for the rotation of `pose`, resolving Tsai's sign ambiguity when f comes
// out negative (r3, r6, r7, r8 change sign); false when no positive f fits. `residual`: the
// stage-2 system's residual norm.
bool SolvePositiveFocal(const std::vector<SensorPoint>& points, Rigid3d* pose, double* f, double* tz, double* residual) {
  if (!SolveFocalAndDepth(points, *pose, f, tz, residual)) return false;
  if (*f >= 0) return true;
  const Eigen::Vector3d D(1, 1, -1);
  pose->R = D.asDiagonal() * pose->R * D.asDiagonal();
  return SolveFocalAndDepth(points, *pose, f, tz, residual) && *f >= 0;
}

// A world frame mirrored relative to the image fits stage 1 as well as a right-handed one; it is
// recognised by the mirrored third row fitting stage 2 better than the proper rotation did
// (`residual`) with every point in front of a camera with f > 0.
bool FitsMirrored(const std::vector<SensorPoint>& points, const Rigid3d& stage_one, double residual) {
  Rigid3d mirrored = stage_one;
  mirrored.R.row(2) *= -1;
  double f = 0, tz = 0, mirrored_residual = 0;
  TsaiResult unused;
  return SolvePositiveFocal(points, &mirrored, &f, &tz, &mirrored_residual) && mirrored_residual < residual &&
         CountBehind(points, mirrored, tz, &unused) == 0;
}

// Standard error of f at stage 3's optimum p = (f, Tz, κ₁): σ̂² (JᵀJ)⁻¹ with σ̂² the residual
// variance (sensor units, 2n − 3 degrees of freedom).
double FocalStandardError(const std::vector<SensorPoint>& points, const Rigid3d& pose, const double* p) {
  const int m = 2 * static_cast<int>(points.size());
  ceres::AutoDiffCostFunction<Stage3Cost, ceres::DYNAMIC, 3> cost(new Stage3Cost{&points, &pose}, m);
  Eigen::VectorXd r(m);
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> J(m, 3);
  double* jacobians[1] = {J.data()};
  if (!cost.Evaluate(&p, r.data(), jacobians)) return INFINITY;
  // f (px), Tz (length) and κ₁ (px⁻²) differ in scale by ten orders: invert with unit columns.
  // alignas(16): Eigen's vectorised column norms do the first column alone, summed in another
  // order, when the destination starts 8 bytes off a 16-byte boundary, and where a small fixed
  // vector sits is the compiler's choice (GCC 12 put this one on a boundary, clang 14 off it): the
  // last bits of f_sigma_px depended on the compiler (docs/performance.md#build, stop 38).
  alignas(16) const Eigen::Vector3d scale = J.colwise().norm().cwiseInverse().transpose();
  const Eigen::Matrix3d information = scale.asDiagonal() * (J.transpose() * J) * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(information);
  if (!(eig.eigenvalues()(0) > 1e-14 * eig.eigenvalues()(2))) return INFINITY;
  const double inverse_ff = (eig.eigenvectors().row(0).array().square() / eig.eigenvalues().transpose().array()).sum();
  return std::sqrt(r.squaredNorm() / (m - 3) * inverse_ff) * scale(0);
}

// Stages 2 and 3 after a stage-1 rotation and Tx, Ty.
TsaiStatus FinishStages(const std::vector<SensorPoint>& points, Rigid3d* pose, const TsaiOptions& options,
                        TsaiResult* out) {
  const Rigid3d stage_one = *pose;
  double f = 0, tz = 0;
  if (!SolveFocalAndDepth(points, *pose, &f, &tz)) {
    out->message = "f and Tz cannot be separated: the points do not vary in depth (a plane parallel to the image?); "
                   "tilt the target or use a volume";
    return TsaiStatus::kDegenerate;
  }
  // The nonlinear stage needs a positive f and every point in front of the camera.
  double residual = INFINITY;
  const bool positive = SolvePositiveFocal(points, pose, &f, &tz, &residual);
  if (!positive) residual = INFINITY;
  if (!positive || CountBehind(points, *pose, tz, out) > 0) {
    if (FitsMirrored(points, stage_one, residual)) {
      out->message = "the world frame is mirrored relative to the image: the world axes are left-handed or u/v are "
                     "swapped; flip one world axis or fix the pixel columns";
      return TsaiStatus::kMirrored;
    }
    if (!positive) {
      out->message = "no positive focal length fits the data; check the correspondences";
      return TsaiStatus::kDegenerate;
    }
    out->message = std::to_string(out->n_behind) + " of " + std::to_string(points.size()) +
                   " points lie behind the camera that the others define; check their coordinates and signs";
    return TsaiStatus::kPointsBehind;
  }
  double p[3] = {f, tz, 0.0};
  ceres::Problem problem;
  problem.AddResidualBlock(new ceres::AutoDiffCostFunction<Stage3Cost, ceres::DYNAMIC, 3>(
                               new Stage3Cost{&points, pose}, 2 * static_cast<int>(points.size())),
                           nullptr, p);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 100;
  solver.function_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-14;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out->nonlinear_iterations = static_cast<int>(summary.iterations.size()) - 1;
  if (summary.termination_type != ceres::CONVERGENCE) {
    out->message = "Tsai's nonlinear stage (f, Tz, kappa1) did not converge: " + summary.message;
    return TsaiStatus::kNotConverged;
  }
  // Stage 3 fits f from the points' depth differences only: a plane (nearly) parallel to the
  // image leaves it undetermined, whatever the linear stages' conditioning.
  out->f_sigma = FocalStandardError(points, *pose, p);
  if (!(out->f_sigma <= options.max_focal_relative_sigma * p[0])) {
    out->message = Format("f is not determined by these points (standard error %.3g%% of f, limit %.3g%%): their "
                          "depths vary too little (a plane nearly parallel to the image?); tilt the target (30 degrees "
                          "or more) or use a volume",
                          100 * out->f_sigma / p[0], 100 * options.max_focal_relative_sigma);
    return TsaiStatus::kDegenerate;
  }
  out->f = p[0];
  out->kappa1 = p[2];
  pose->t.z() = p[1];
  return TsaiStatus::kOk;
}

// Stage 1, non-coplanar: the radial alignment constraint X_d·y = Y_d·x, with x = r₁·X + Tx and
// y = r₂·X + Ty, is linear in a = (sx r₁/Ty, sx Tx/Ty, r₂/Ty) once sx is absorbed into the X_d
// of pixels: Y_d (sx r₁·X + sx Tx) − (u − Cx)(r₂·X + Ty) = 0.
TsaiStatus StageOneNonCoplanar(const std::vector<SensorPoint>& points, Rigid3d* pose, double* sx, TsaiResult* out) {
  const size_t n = points.size();
  Eigen::MatrixXd A(n, 7);
  Eigen::VectorXd b(n);
  for (size_t i = 0; i < n; ++i) {
    const SensorPoint& s = points[i];  // s.xd holds u − Cx here (sx unknown)
    A.row(i) << s.yd * s.X.transpose(), s.yd, -s.xd * s.X.transpose();
    b(i) = s.xd;
  }
  const LeastSquaresSolution ls = SolveLeastSquares(A, b, 1e-10);
  if (ls.rank < 7) {
    out->message = "the radial alignment system is rank deficient: the points do not span a volume in the view";
    return TsaiStatus::kDegenerate;
  }
  const Eigen::Matrix<double, 7, 1> a = ls.x;
  const double ty_abs = 1.0 / a.tail<3>().norm();
  *sx = a.head<3>().norm() * ty_abs;
  Eigen::Matrix<double, 2, 3> rows;
  rows.row(0) = a.head<3>().transpose() * ty_abs / *sx;
  rows.row(1) = a.tail<3>().transpose() * ty_abs;
  double tx = a(3) * ty_abs / *sx;
  // The sign test needs X_d in sensor units.
  std::vector<SensorPoint> sensor = points;
  for (SensorPoint& s : sensor) s.xd /= *sx;
  const double sign = TySign(sensor, rows, tx, ty_abs);
  rows *= sign;
  tx *= sign;
  Eigen::Matrix3d R;
  R << rows.row(0), rows.row(1), rows.row(0).cross(rows.row(1));
  pose->R = NearestRotation(R);
  pose->t = Eigen::Vector3d(tx, sign * ty_abs, 0);
  return TsaiStatus::kOk;
}

// Stage 1, coplanar (Z = 0, sx known): a = (r₁/Ty, r₂/Ty, Tx/Ty, r₄/Ty, r₅/Ty) from
// Y_d (r₁X + r₂Y + Tx) − X_d (r₄X + r₅Y + Ty) = 0, then Ty² from the 2×2 block C = [[a1, a2],
// [a4, a5]] (Tsai's closed form), the third column from orthonormality.
TsaiStatus StageOneCoplanar(const std::vector<SensorPoint>& points, Rigid3d* pose, TsaiResult* out) {
  const size_t n = points.size();
  Eigen::MatrixXd A(n, 5);
  Eigen::VectorXd b(n);
  for (size_t i = 0; i < n; ++i) {
    const SensorPoint& s = points[i];
    A.row(i) << s.yd * s.X.x(), s.yd * s.X.y(), s.yd, -s.xd * s.X.x(), -s.xd * s.X.y();
    b(i) = s.xd;
  }
  const LeastSquaresSolution ls = SolveLeastSquares(A, b, 1e-10);
  if (ls.rank < 5) {
    out->message = "the coplanar radial alignment system is rank deficient: the board points are collinear";
    return TsaiStatus::kDegenerate;
  }
  const Eigen::Matrix<double, 5, 1> a = ls.x;
  const double a1 = a(0), a2 = a(1), a3 = a(2), a4 = a(3), a5 = a(4);
  const double ty_abs = std::sqrt(CoplanarTySquared(a1, a2, a4, a5));
  Eigen::Matrix<double, 2, 3> rows;
  rows << a1 * ty_abs, a2 * ty_abs, 0, a4 * ty_abs, a5 * ty_abs, 0;
  double tx = a3 * ty_abs;
  const double sign = TySign(points, rows, tx, ty_abs);
  const double r1 = sign * a1 * ty_abs, r2 = sign * a2 * ty_abs, r4 = sign * a4 * ty_abs, r5 = sign * a5 * ty_abs;
  tx *= sign;
  const double r3 = std::sqrt(std::max(0.0, 1 - r1 * r1 - r2 * r2));
  const double r6 = (r1 * r4 + r2 * r5 > 0 ? -1.0 : 1.0) * std::sqrt(std::max(0.0, 1 - r4 * r4 - r5 * r5));
  const Eigen::Vector3d row1(r1, r2, r3), row2(r4, r5, r6);
  Eigen::Matrix3d R;
  R << row1.transpose(), row2.transpose(), row1.cross(row2).transpose();
  pose->R = NearestRotation(R);
  pose->t = Eigen::Vector3d(tx, sign * ty_abs, 0);
  return TsaiStatus::kOk;
}

TsaiResult Fail(TsaiResult r, TsaiStatus status, std::string message) {
  r.status = status;
  r.message = std::move(message);
  return r;
}

}  // namespace

KappaConversion ConvertTsaiKappa(double K, double r_max) {
  KappaConversion out;
  if (!(r_max > 0)) return out;
  // Samples of the exact inverse: r_d solves r_d (1 + K r_d²) = r_n.
  const int samples = 256;
  Eigen::MatrixXd A(samples, 3);
  Eigen::VectorXd b(samples), rn(samples), rd(samples);
  for (int i = 0; i < samples; ++i) {
    const double r = r_max * (i + 1) / samples;
    double d = r;
    for (int it = 0; it < 60; ++it) {
      const double step = (d + K * d * d * d - r) / (1 + 3 * K * d * d);
      d -= step;
      if (std::abs(step) <= 1e-17 * (1 + std::abs(d))) break;
    }
    rn(i) = r;
    rd(i) = d;
    A.row(i) << r * r * r, std::pow(r, 5), std::pow(r, 7);
    b(i) = d - r;
  }
  const Eigen::Vector3d k = SolveLeastSquares(A, b).x;
  out.k1 = k(0);
  out.k2 = k(1);
  out.k3 = k(2);
  for (int i = 0; i < samples; ++i) {
    const double r2 = rn(i) * rn(i);
    out.max_error = std::max(out.max_error, std::abs(rn(i) * (1 + r2 * (out.k1 + r2 * (out.k2 + r2 * out.k3))) - rd(i)));
  }
  return out;
}

double CoplanarTySquared(double a1, double a2, double a4, double a5) {
  const double S = a1 * a1 + a2 * a2 + a4 * a4 + a5 * a5;
  const double D = a1 * a5 - a4 * a2;
  // S² − 4D² = ((a1 − a5)² + (a2 + a4)²)((a1 + a5)² + (a2 − a4)²) ≥ 0; the max guards rounding.
  return 2 / (S + std::sqrt(std::max(0.0, S * S - 4 * D * D)));
}

TsaiResult SolveTsai(std::span<const Observation> obs, ImageSize size, const TsaiOptions& options) {
  TsaiResult out;
  const Eigen::Vector2d c = options.principal_point.value_or(Eigen::Vector2d(0.5 * (size.width - 1), 0.5 * (size.height - 1)));
  out.principal_point = c;
  for (const Observation& o : obs) {
    if (!o.point.allFinite() || !o.pixel.allFinite()) return Fail(out, TsaiStatus::kDegenerate, "a coordinate is not finite");
  }

  // Planarity from the principal extents of the points.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Observation& o : obs) centroid += o.point;
  centroid /= std::max<double>(1.0, static_cast<double>(obs.size()));
  const double pre = WorldCoordinateScale(obs, centroid);  // 1e±300 solved near 1; 1 usually
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Observation& o : obs) scatter += ((o.point - centroid) * pre) * ((o.point - centroid) * pre).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Eigen::Vector3d extents = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt();  // ascending
  const bool planar = extents(0) < options.min_extent_ratio * extents(2);
  using Variant = TsaiOptions::Variant;
  out.variant = options.variant == Variant::kAuto ? (planar ? Variant::kCoplanar : Variant::kNonCoplanar) : options.variant;
  if (out.variant == Variant::kNonCoplanar && planar) {
    return Fail(out, TsaiStatus::kCoplanarForced,
                Format("the non-coplanar variant was asked for, but the points are coplanar (thickness/extent %.3g < "
                       "%.3g); use the coplanar variant (" VSTCAL_OPT("variant") " coplanar or auto)",
                       extents(0) / extents(2), options.min_extent_ratio));
  }
  if (out.variant == Variant::kCoplanar && !planar) {
    return Fail(out, TsaiStatus::kDegenerate,
                Format("the coplanar variant was asked for, but the points span a volume (thickness/extent %.3g >= "
                       "%.3g); use the non-coplanar variant (" VSTCAL_OPT("variant") " non-coplanar or auto)",
                       extents(0) / extents(2), options.min_extent_ratio));
  }
  const size_t needed = out.variant == Variant::kCoplanar ? 5 : 7;
  if (obs.size() < needed) {
    return Fail(out, TsaiStatus::kTooFewPoints,
                "Tsai's " + std::string(out.variant == Variant::kCoplanar ? "coplanar" : "non-coplanar") +
                    " method needs at least " + std::to_string(needed) + " points, got " + std::to_string(obs.size()) +
                    "; add correspondences");
  }

  // Working frame: for a plane, its own frame (Z = 0 on it); the origin moved to the point seen
  // farthest from the principal point's row, so that Ty (the origin's camera y) is far from 0
  // (stage 1 divides by it).
  Rigid3d work_from_world;
  if (out.variant == Variant::kCoplanar) {
    Eigen::Matrix3d axes = eig.eigenvectors();  // columns ascending: normal first
    Eigen::Matrix3d R;
    R.row(0) = axes.col(2).transpose();
    R.row(1) = axes.col(1).transpose();
    R.row(2) = axes.col(0).transpose();
    if (R.determinant() < 0) R.row(1) *= -1;
    work_from_world = Rigid3d{R, -R * centroid};
  }
  size_t anchor = 0;
  for (size_t i = 1; i < obs.size(); ++i) {
    if (std::abs(obs[i].pixel.y() - c.y()) > std::abs(obs[anchor].pixel.y() - c.y())) anchor = i;
  }
  Eigen::Vector3d origin = work_from_world * obs[anchor].point;
  if (out.variant == Variant::kCoplanar) origin.z() = 0;
  work_from_world.t -= origin;

  std::vector<SensorPoint> points(obs.size());
  double plane_ss = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    points[i].X = (work_from_world * obs[i].point) * pre;
    if (out.variant == Variant::kCoplanar) {
      plane_ss += points[i].X.z() * points[i].X.z();
      points[i].X.z() = 0;
    }
    points[i].xd = obs[i].pixel.x() - c.x();  // divided by sx below, once sx is known
    points[i].yd = obs[i].pixel.y() - c.y();
  }
  out.plane_rms = std::sqrt(plane_ss / static_cast<double>(obs.size())) / pre;

  Rigid3d camera_from_work;
  TsaiStatus status;
  if (out.variant == Variant::kCoplanar) {
    out.sx = options.sx;
    for (SensorPoint& s : points) s.xd /= out.sx;
    status = StageOneCoplanar(points, &camera_from_work, &out);
  } else {
    status = StageOneNonCoplanar(points, &camera_from_work, &out.sx, &out);
    for (SensorPoint& s : points) s.xd /= out.sx;
  }
  if (status == TsaiStatus::kOk) status = FinishStages(points, &camera_from_work, options, &out);
  if (status != TsaiStatus::kOk) {
    out.status = status;
    return out;
  }
  camera_from_work.t /= pre;  // back from the scaled working frame: x_cam = R X + t'/pre
  out.camera_from_world = camera_from_work * work_from_world;

  // vstcal's camera: K from f, sx and the principal point; κ₁ converted over the image.
  Eigen::Matrix3d K;
  K << out.f * out.sx, 0, c.x(), 0, out.f, c.y(), 0, 0, 1;
  const double kappa_normalized = out.kappa1 * out.f * out.f;
  double rd_max = 0;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(-0.5, -0.5), Eigen::Vector2d(size.width - 0.5, -0.5),
                                       Eigen::Vector2d(-0.5, size.height - 0.5),
                                       Eigen::Vector2d(size.width - 0.5, size.height - 0.5)}) {
    rd_max = std::max(rd_max, Eigen::Vector2d((corner.x() - c.x()) / K(0, 0), (corner.y() - c.y()) / K(1, 1)).norm());
  }
  const KappaConversion conversion = ConvertTsaiKappa(kappa_normalized, rd_max * (1 + kappa_normalized * rd_max * rd_max));
  const double distortion[5] = {conversion.k1, conversion.k2, 0, 0, conversion.k3};
  out.camera = Camera::FromK(K, size, RadialTangentialModel{}, distortion);
  out.conversion_max_error_px = conversion.max_error * std::max(K(0, 0), K(1, 1));
  return out;
}

ExitCode TsaiStatusExitCode(TsaiStatus status) {
  switch (status) {
    case TsaiStatus::kOk: return ExitCode::kOk;
    case TsaiStatus::kTooFewPoints:
    case TsaiStatus::kPointsBehind:
    case TsaiStatus::kMirrored: return ExitCode::kBadInput;
    default: return ExitCode::kDegenerate;
  }
}

}  // namespace vstcal
