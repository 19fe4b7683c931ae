#include "vstcal/estimators/dlt.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

using Vector12d = Eigen::Matrix<double, 12, 1>;

// Similarity transforms that move the centroid to the origin and scale the RMS distance to
// √3 (world) and √2 (pixels): Hartley's normalization (docs/math/dlt.md#normalization).
struct Normalization {
  Eigen::Vector3d world_centroid = Eigen::Vector3d::Zero();
  double world_scale = 1;
  Eigen::Vector2d pixel_centroid = Eigen::Vector2d::Zero();
  double pixel_scale = 1;
  bool valid = false;
};

// AᵀA of the normalized system is [[M₀, 0, −M_u], [0, M₀, −M_v], [−M_u, −M_v, M_w]] with
// M₀ = ΣX̃X̃ᵀ, M_u = ΣũX̃X̃ᵀ, M_v = ΣṽX̃X̃ᵀ, M_w = Σ(ũ² + ṽ²)X̃X̃ᵀ, X̃ = (x̃, ỹ, z̃, 1).
struct NormalizedMoments {
  Eigen::Matrix4d M0, Mu, Mv, Mw;

  Matrix12d Full() const {
    Matrix12d N = Matrix12d::Zero();
    N.block<4, 4>(0, 0) = M0;
    N.block<4, 4>(4, 4) = M0;
    N.block<4, 4>(0, 8) = -Mu;
    N.block<4, 4>(8, 0) = -Mu;
    N.block<4, 4>(4, 8) = -Mv;
    N.block<4, 4>(8, 4) = -Mv;
    N.block<4, 4>(8, 8) = Mw;
    return N;
  }
  double Trace() const { return 2 * M0.trace() + Mw.trace(); }
};

typedef double Lane4 __attribute__((vector_size(32)));

// The hot loop: raw moments shifted by (p₀, u₀, v₀) to avoid cancellation. With X = (p − p₀, 1)
// and f = (1, du, dv, du² + dv²), out[4k + g] = Σ f_g · (monomial k of X Xᵀ). Each of the 40 sums
// is a plain left-to-right sum over points; the four sums of one monomial share a 4-lane vector
// and lanes never mix, so the avx2 and default (SSE2) clones give identical bits.
__attribute__((target_clones("avx2", "default"))) void AccumulateMoments(const Observation* obs, size_t n,
                                                                         const double* shift, double scale,
                                                                         double* out) {
  Lane4 acc[10] = {};
  const double x0 = shift[0], y0 = shift[1], z0 = shift[2], u0 = shift[3], v0 = shift[4];
  for (size_t i = 0; i < n; ++i) {
    const double x = (obs[i].point.x() - x0) * scale, y = (obs[i].point.y() - y0) * scale,
                 z = (obs[i].point.z() - z0) * scale;
    const double du = obs[i].pixel.x() - u0, dv = obs[i].pixel.y() - v0;
    const Lane4 f = {1.0, du, dv, du * du + dv * dv};
    acc[0] += (x * x) * f;
    acc[1] += (x * y) * f;
    acc[2] += (x * z) * f;
    acc[3] += x * f;
    acc[4] += (y * y) * f;
    acc[5] += (y * z) * f;
    acc[6] += y * f;
    acc[7] += (z * z) * f;
    acc[8] += z * f;
    acc[9] += f;
  }
  for (int k = 0; k < 10; ++k) {
    for (int g = 0; g < 4; ++g) out[4 * k + g] = acc[k][g];
  }
}

// One pass over the data, then the normalization and the normalized moments algebraically:
// with X̃ = T X, T = [[s₃I, −s₃c], [0, 1]], ũ = s₂(du − c_u), ṽ = s₂(dv − c_v) and R_g the raw
// moment matrices,
//   M₀ = T R₀ Tᵀ,  M_u = s₂ T (R₁ − c_u R₀) Tᵀ,  M_v = s₂ T (R₂ − c_v R₀) Tᵀ,
//   M_w = s₂² T (R₃ − 2c_u R₁ − 2c_v R₂ + (c_u² + c_v²) R₀) Tᵀ   (docs/math/dlt.md#moments).
NormalizedMoments MomentsOnePass(std::span<const Observation> obs, Normalization* n) {
  const double shift[5] = {obs[0].point.x(), obs[0].point.y(), obs[0].point.z(), obs[0].pixel.x(), obs[0].pixel.y()};
  const double pre = WorldCoordinateScale(obs, obs[0].point);  // X = pre·(p − p₀), exact; 1 usually
  double r[40];
  AccumulateMoments(obs.data(), obs.size(), shift, pre, r);
  auto raw = [&r](int g) {
    Eigen::Matrix4d M;
    M << r[0 + g], r[4 + g], r[8 + g], r[12 + g],  //
        r[4 + g], r[16 + g], r[20 + g], r[24 + g],  //
        r[8 + g], r[20 + g], r[28 + g], r[32 + g],  //
        r[12 + g], r[24 + g], r[32 + g], r[36 + g];
    return M;
  };
  const Eigen::Matrix4d R0 = raw(0), R1 = raw(1), R2 = raw(2), R3 = raw(3);
  const double count = R0(3, 3);
  const Eigen::Vector3d c = R0.block<3, 1>(0, 3) / count;
  const double cu = R1(3, 3) / count, cv = R2(3, 3) / count;
  const double var3 = R0.topLeftCorner<3, 3>().trace() / count - c.squaredNorm();
  const double var2 = R3(3, 3) / count - cu * cu - cv * cv;
  n->valid = var3 > 0 && var2 > 0 && std::isfinite(var3) && std::isfinite(var2);
  const double s3 = n->valid ? std::sqrt(3.0 / var3) : 1.0;  // for the scaled points
  n->world_scale = s3 * pre;
  n->pixel_scale = n->valid ? std::sqrt(2.0 / var2) : 1.0;
  n->world_centroid = Eigen::Vector3d(shift[0], shift[1], shift[2]) + c / pre;
  n->pixel_centroid = Eigen::Vector2d(shift[3], shift[4]) + Eigen::Vector2d(cu, cv);

  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() *= s3;
  T.block<3, 1>(0, 3) = -s3 * c;
  const double s2 = n->pixel_scale;
  NormalizedMoments m;
  m.M0 = T * R0 * T.transpose();
  m.Mu = s2 * T * (R1 - cu * R0) * T.transpose();
  m.Mv = s2 * T * (R2 - cv * R0) * T.transpose();
  m.Mw = s2 * s2 * T * (R3 - 2 * cu * R1 - 2 * cv * R2 + (cu * cu + cv * cv) * R0) * T.transpose();
  return m;
}

// Hartley normalization computed directly, for the reference path.
Normalization DirectNormalization(std::span<const Observation> obs) {
  Normalization n;
  Eigen::Vector3d sum3 = Eigen::Vector3d::Zero();
  Eigen::Vector2d sum2 = Eigen::Vector2d::Zero();
  for (const Observation& o : obs) {
    sum3 += o.point;
    sum2 += o.pixel;
  }
  const double count = static_cast<double>(obs.size());
  n.world_centroid = sum3 / count;
  n.pixel_centroid = sum2 / count;
  const double pre = WorldCoordinateScale(obs, n.world_centroid);  // squares of 1e±300 coordinates
  double ss3 = 0, ss2 = 0;
  for (const Observation& o : obs) {
    ss3 += ((o.point - n.world_centroid) * pre).squaredNorm();
    ss2 += (o.pixel - n.pixel_centroid).squaredNorm();
  }
  n.valid = ss3 > 0 && ss2 > 0 && std::isfinite(ss3) && std::isfinite(ss2);
  n.world_scale = n.valid ? std::sqrt(3.0 * count / ss3) * pre : 1.0;
  n.pixel_scale = n.valid ? std::sqrt(2.0 * count / ss2) : 1.0;
  return n;
}

// The 2N×12 normalized system itself, rows [X̃ᵀ 0 −ũX̃ᵀ] and [0 X̃ᵀ −ṽX̃ᵀ] (reference path).
Eigen::MatrixXd SystemMatrix(std::span<const Observation> obs, const Normalization& n) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * static_cast<Eigen::Index>(obs.size()), 12);
  for (size_t i = 0; i < obs.size(); ++i) {
    const Eigen::Vector3d p = (obs[i].point - n.world_centroid) * n.world_scale;
    const Eigen::Vector2d q = (obs[i].pixel - n.pixel_centroid) * n.pixel_scale;
    const Eigen::Vector4d X(p.x(), p.y(), p.z(), 1.0);
    const Eigen::Index r = 2 * static_cast<Eigen::Index>(i);
    A.block<1, 4>(r, 0) = X.transpose();
    A.block<1, 4>(r, 8) = -q.x() * X.transpose();
    A.block<1, 4>(r + 1, 4) = X.transpose();
    A.block<1, 4>(r + 1, 8) = -q.y() * X.transpose();
  }
  return A;
}

// The Schur complement of AᵀA onto its third block (docs/math/dlt.md#secular). For λ below the
// smallest eigenvalue μ_min of M₀, eliminating the first two blocks of (AᵀA − λI) m = 0 gives
//   S(λ) m₃ = λ m₃,  S(λ) = M_w − M_u W M_u − M_v W M_v,  W = (M₀ − λI)⁻¹,
//   m₁ = W M_u m₃,   m₂ = W M_v m₃,
// and, by Haynsworth's inertia additivity, the number of eigenvalues of AᵀA below λ equals the
// number of eigenvalues s_j(λ) of S(λ) below λ.
class SchurComplement {
 public:
  explicit SchurComplement(const NormalizedMoments& mm) : Mw_(mm.Mw) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> m0(mm.M0);
    mu_ = m0.eigenvalues();
    Q_ = m0.eigenvectors();
    QtMu_ = Q_.transpose() * mm.Mu;
    QtMv_ = Q_.transpose() * mm.Mv;
  }

  double mu_min() const { return mu_(0); }

  Eigen::Matrix4d At(double lambda, Eigen::Vector4d* d) const {
    *d = (mu_.array() - lambda).inverse();
    return Mw_ - QtMu_.transpose() * d->asDiagonal() * QtMu_ - QtMv_.transpose() * d->asDiagonal() * QtMv_;
  }

  // The smallest eigenpair of AᵀA: the root of h(λ) = s₀(λ) − λ, which decreases with
  // h'(λ) = −(1 + ‖m₁‖² + ‖m₂‖²) for unit m₃, by Newton's method from λ = 0. nullopt when an
  // iterate reaches μ_min or Newton stalls (the caller then solves the 12×12 problem).
  std::optional<std::pair<double, Vector12d>> Smallest(double tolerance) const {
    double lambda = 0;
    for (int iteration = 0; iteration < 30; ++iteration) {
      Eigen::Vector4d d;
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(At(lambda, &d));
      const Eigen::Vector4d m3 = es.eigenvectors().col(0);
      const Eigen::Vector4d a = d.asDiagonal() * (QtMu_ * m3), b = d.asDiagonal() * (QtMv_ * m3);
      const double step = (es.eigenvalues()(0) - lambda) / (1 + a.squaredNorm() + b.squaredNorm());
      lambda += step;
      if (!(lambda < mu_(0))) return std::nullopt;
      if (std::abs(step) <= tolerance) {
        Vector12d m;
        m << Q_ * a, Q_ * b, m3;
        return std::make_pair(lambda, m.normalized());
      }
    }
    return std::nullopt;
  }

  // True when the second-smallest eigenvalue of AᵀA is at least λ: λ < μ_min and s₁(λ) ≥ λ.
  bool SecondAtLeast(double lambda) const {
    if (!(lambda < mu_(0))) return false;
    Eigen::Vector4d d;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(At(lambda, &d), Eigen::EigenvaluesOnly);
    return es.eigenvalues()(1) >= lambda;
  }

 private:
  Eigen::Matrix4d Mw_, Q_, QtMu_, QtMv_;
  Eigen::Vector4d mu_;
};

// P in original units from the normalized solution: P = T₂⁻¹ P̃ T₃.
Matrix34d Denormalize(const Vector12d& m, const Normalization& n) {
  Matrix34d Pn;
  Pn.row(0) = m.segment<4>(0).transpose();
  Pn.row(1) = m.segment<4>(4).transpose();
  Pn.row(2) = m.segment<4>(8).transpose();
  Eigen::Matrix4d T3 = Eigen::Matrix4d::Identity();
  T3.topLeftCorner<3, 3>() *= n.world_scale;
  T3.block<3, 1>(0, 3) = -n.world_scale * n.world_centroid;
  Eigen::Matrix3d T2inv = Eigen::Matrix3d::Identity();
  T2inv.topLeftCorner<2, 2>() /= n.pixel_scale;
  T2inv.block<2, 1>(0, 2) = n.pixel_centroid;
  return T2inv * Pn * T3;
}

std::string Format(const char* fmt, double a, double b) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, a, b);
  return buf;
}

DltResult Fail(DltResult r, DltStatus status, std::string message) {
  r.status = status;
  r.message = std::move(message);
  return r;
}

// World coordinates so large that the DLT's numbers leave double precision: their differences
// (beyond ~1e308) or the projection matrix and the depths (beyond ~1e305 / fx).
DltResult FailBeyondRange(DltResult r, std::span<const Observation> obs) {
  double largest = 0;
  for (const Observation& o : obs) largest = std::max(largest, o.point.cwiseAbs().maxCoeff());
  char buf[240];
  std::snprintf(buf, sizeof buf,
                "the world coordinates are beyond double precision for the DLT (largest |X|, |Y|, |Z| = %.3g); "
                "express them in a larger length unit",
                largest);
  return Fail(r, DltStatus::kNonFinite, buf);
}

// Normalization fails when every point (or pixel) is the same, or when the world coordinates'
// spread is beyond double precision (differences that overflow, or below the smallest normal
// double); say which.
DltResult FailNormalization(DltResult r, std::span<const Observation> obs) {
  bool same_point = true, same_pixel = true;
  for (const Observation& o : obs) {
    same_point = same_point && o.point == obs[0].point;
    same_pixel = same_pixel && o.pixel == obs[0].pixel;
  }
  if (same_point || same_pixel) {
    return Fail(r, DltStatus::kCoincident,
                std::string(same_point ? "all points are the same 3-D point" : "all points project to the same pixel") +
                    "; DLT needs points spread over a volume (docs/math/dlt.md#degeneracy)");
  }
  return FailBeyondRange(r, obs);
}

// Below this relative thickness a cloud is coplanar to the precision of the moments (the
// smallest eigenvalue of M₀'s 3×3 carries absolute rounding ~1e-16·λ_max, so √ of it ~1e-8).
constexpr double kCoplanarAtRounding = 1e-6;

// A cloud is "collinear" also when one point lies so far from the others (a coordinate of 1e308, a
// typo) that they shrink to a point beside it: then that point, not the cloud, is the problem.
// The message names that point when the median distance from the median point is below 1e-6 of
// the farthest.
void NoteFarPoint(std::span<const Observation> obs, DltResult* r) {
  if (obs.empty()) return;
  std::vector<double> x(obs.size()), y(obs.size()), z(obs.size());
  for (size_t i = 0; i < obs.size(); ++i) x[i] = obs[i].point.x(), y[i] = obs[i].point.y(), z[i] = obs[i].point.z();
  const auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const Eigen::Vector3d centre(median(x), median(y), median(z));
  std::vector<double> distance(obs.size());
  size_t farthest = 0;
  for (size_t i = 0; i < obs.size(); ++i) {
    distance[i] = (obs[i].point - centre).cwiseAbs().maxCoeff();  // no squares: 1e308 stays finite
    if (distance[i] > distance[farthest]) farthest = i;
  }
  if (!(median(distance) < 1e-6 * distance[farthest])) return;
  const Eigen::Vector3d& p = obs[farthest].point;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "one point, at (%.6g, %.6g, %.6g), lies more than a million times farther from the others than they "
                "lie from each other, so that the cloud looks like a line from it: check that point's coordinates",
                p.x(), p.y(), p.z());
  r->message = buf;
}

// Degeneracy of the point cloud from the principal extents of the normalized points (the centred
// second moments are M₀'s top-left 3×3 over N). Returns the failing status, or kOk.
DltStatus CheckExtents(const Eigen::Matrix4d& M0, size_t count, const DltOptions& options, DltResult* r) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> cloud;
  cloud.computeDirect(M0.topLeftCorner<3, 3>() / static_cast<double>(count), Eigen::EigenvaluesOnly);
  for (int i = 0; i < 3; ++i) r->extents[i] = std::sqrt(std::max(0.0, cloud.eigenvalues()(2 - i)));
  const double width = r->extents[1] / r->extents[0], thickness = r->extents[2] / r->extents[0];
  if (width < options.min_extent_ratio) {
    r->message = Format("the points are collinear (width/length of the point cloud %.3g < %.3g): no camera can be "
                        "solved from them; spread the points over a volume (docs/math/dlt.md#degeneracy)",
                        width, options.min_extent_ratio);
    return DltStatus::kCollinear;
  }
  if (thickness < options.min_extent_ratio) {
    r->message = std::string(thickness < kCoplanarAtRounding ? "the points are coplanar" : "the points are nearly coplanar") +
                 Format(" (thickness/extent of the point cloud %.3g < %.3g): DLT needs a 3-D volume; for a planar "
                        "target use calib-tsai with rig \"planar-views\", or move the template between a near and "
                        "a far plane (docs/math/dlt.md#degeneracy)",
                        thickness, options.min_extent_ratio);
    return DltStatus::kCoplanar;
  }
  if (thickness < options.warn_extent_ratio) {
    r->warnings.push_back(Format("the volume is thin (thickness/extent %.3g < %.3g): DLT amplifies pixel noise into "
                                 "K roughly in inverse proportion; spread the template positions further apart",
                                 thickness, options.warn_extent_ratio));
  }
  return DltStatus::kOk;
}

}  // namespace

DltResult SolveDlt(std::span<const Observation> obs, const DltOptions& options) {
  DltResult r;
  r.n_points = obs.size();
  if (obs.size() < 6) {
    return Fail(r, DltStatus::kTooFewPoints,
                "DLT needs at least 6 points in general position, got " + std::to_string(obs.size()) +
                    "; add correspondences (a calibration volume gives hundreds)");
  }
  for (const Observation& o : obs) {
    if (!o.point.allFinite() || !o.pixel.allFinite()) {
      return Fail(r, DltStatus::kNonFinite, "a coordinate is NaN or infinite; every coordinate must be finite");
    }
  }

  const bool reference = options.solver == DltOptions::Solver::kFullSvd;
  Normalization n;
  NormalizedMoments moments;
  Eigen::MatrixXd A;
  if (reference) {
    n = DirectNormalization(obs);
    A = SystemMatrix(obs, n);
    moments.M0 = A.leftCols<4>().transpose() * A.leftCols<4>();  // each X̃ appears once in the first block
  } else {
    moments = MomentsOnePass(obs, &n);
  }
  if (!n.valid) return FailNormalization(r, obs);
  if (const DltStatus s = CheckExtents(moments.M0, obs.size(), options, &r); s != DltStatus::kOk) {
    r.status = s;
    if (s == DltStatus::kCollinear) NoteFarPoint(obs, &r);
    return r;
  }

  Vector12d m;
  if (reference) {
    const SingularValueDecomposition svd = DecomposeSvd(A, Eigen::ComputeThinV);
    const auto& sv = svd.singular_values;
    r.sigma_11 = sv(10);
    r.sigma_12 = sv(11);
    r.frobenius = sv.norm();
    m = svd.V.col(11);
  } else {
    r.frobenius = std::sqrt(moments.Trace());
    const SchurComplement schur(moments);
    const auto smallest = schur.Smallest(1e-15 * moments.Trace());
    // The refusal test needs only whether σ₁₁ ≥ threshold·‖A‖_F, which one 4×4 problem decides
    // exactly; σ₁₁ itself comes from the 12×12 spectrum when asked for or when the test fails.
    const double lambda_threshold = std::pow(options.min_conditioning * r.frobenius, 2);
    const bool need_spectrum = !smallest || options.exact_diagnostics || !schur.SecondAtLeast(lambda_threshold);
    if (need_spectrum) {
      const SymmetricEigen12 eig = DecomposeSymmetric12(moments.Full());
      r.sigma_11 = std::sqrt(std::max(0.0, eig.values(1)));
      r.sigma_12 = std::sqrt(std::max(0.0, eig.values(0)));  // rounding can make λ slightly negative
      m = smallest ? smallest->second : Vector12d(eig.vectors.col(0));
    } else {
      r.sigma_11 = NAN;  // not computed; certified ≥ min_conditioning·‖A‖_F
      r.sigma_12 = std::sqrt(std::max(0.0, smallest->first));
      m = smallest->second;
    }
  }
  r.conditioning = r.sigma_11 / r.frobenius;
  if (r.conditioning < options.min_conditioning) {
    return Fail(r, DltStatus::kIllConditioned,
                Format("the DLT system is ill-conditioned (sigma11/|A|_F = %.3g < %.3g): the points and the camera "
                       "are in a critical configuration, or the volume is too thin; add points at other depths and "
                       "positions (docs/math/dlt.md#degeneracy)",
                       r.conditioning, options.min_conditioning));
  }

  // Scale and sign: unit third row, the majority of points in front. Counting is one cheap pass;
  // only when some point lies on the other side does a second pass find the deepest to report.
  Matrix34d P = NormalizeProjectionScale(Denormalize(m, n));
  if (!P.allFinite()) return FailBeyondRange(r, obs);
  const Eigen::Vector3d depth_dir = P.block<1, 3>(2, 0).transpose();
  const double depth_offset = P(2, 3);
  size_t positive = 0, negative = 0;
  bool finite = true;
  for (const Observation& o : obs) {
    const double depth = depth_dir.dot(o.point) + depth_offset;
    positive += depth > 0;
    negative += depth < 0;
    finite = finite && std::isfinite(depth);
  }
  if (!finite) return FailBeyondRange(r, obs);
  if (negative > positive) {
    P = -P;
    std::swap(positive, negative);
  }
  r.P = P;
  if (positive != obs.size()) {  // some points at or behind the camera plane
    double deepest = INFINITY;
    for (size_t i = 0; i < obs.size(); ++i) {
      const double depth = P.block<1, 3>(2, 0).dot(obs[i].point.transpose()) + P(2, 3);
      if (depth > 0) continue;
      ++r.n_behind;
      if (depth < deepest) deepest = depth, r.deepest_behind = i;
    }
    return Fail(r, DltStatus::kPointsBehind,
                std::to_string(r.n_behind) + " of " + std::to_string(obs.size()) +
                    " points lie behind the camera that the others define; check their coordinates and signs");
  }
  if (P.leftCols<3>().determinant() < 0) {
    return Fail(r, DltStatus::kMirrored,
                "the world frame is mirrored relative to the image (det M < 0): the world axes are left-handed or "
                "u/v are swapped; flip one world axis or fix the pixel columns");
  }
  return r;
}

DltUncertainty EstimateDltUncertainty(std::span<const Observation> obs, const Matrix34d& P) {
  VSTCAL_CHECK(obs.size() >= 6 && P.allFinite(), "the DLT uncertainty needs a solved P and its observations");
  const Normalization n = DirectNormalization(obs);
  Eigen::Matrix4d T3 = Eigen::Matrix4d::Identity();
  T3.topLeftCorner<3, 3>() *= n.world_scale;
  T3.block<3, 1>(0, 3) = -n.world_scale * n.world_centroid;
  const double s2 = n.pixel_scale;
  Eigen::Matrix3d T2 = Eigen::Matrix3d::Identity(), T2inv = Eigen::Matrix3d::Identity();
  T2.topLeftCorner<2, 2>() *= s2;
  T2.block<2, 1>(0, 2) = -s2 * n.pixel_centroid;
  T2inv.topLeftCorner<2, 2>() /= s2;
  T2inv.block<2, 1>(0, 2) = n.pixel_centroid;
  // The normalized solution m (unit norm) that P came from: P̃ ∝ T₂ P T₃⁻¹.
  Matrix34d Pn = T2 * P * T3.inverse();
  Pn /= Pn.norm();

  // AᵀA and Aᵀ D² A, D the rows' weights w̃ᵢ = p̃₃·X̃ᵢ: a pixel error δq̃ moves the algebraic
  // residual by −w̃ᵢ δq̃ (docs/math/dlt.md#covariance).
  Matrix12d N = Matrix12d::Zero(), B = Matrix12d::Zero();
  double squares = 0;
  for (const Observation& o : obs) {
    const Eigen::Vector4d X = T3 * o.point.homogeneous();
    const Eigen::Vector2d q = s2 * (o.pixel - n.pixel_centroid);
    Vector12d au = Vector12d::Zero(), av = Vector12d::Zero();
    au.segment<4>(0) = X;
    au.segment<4>(8) = -q.x() * X;
    av.segment<4>(4) = X;
    av.segment<4>(8) = -q.y() * X;
    const Matrix12d rows = au * au.transpose() + av * av.transpose();
    const double w = Pn.row(2).dot(X);
    N += rows;
    B += w * w * rows;
    const Eigen::Vector3d x = P * o.point.homogeneous();
    squares += (x.head<2>() / x.z() - o.pixel).squaredNorm();
  }
  DltUncertainty u;
  u.dof = 2 * static_cast<int>(obs.size()) - 11;
  u.sigma_px = std::sqrt(squares / u.dof);

  // δm = G Aᵀ D δq̃ with G = Σ_{j>0} v_j v_jᵀ / (λ_j − λ₀): first-order perturbation of the
  // smallest eigenvector, which never moves along itself (‖m‖ = 1).
  const SymmetricEigen12 eig = DecomposeSymmetric12(N);
  Matrix12d G = Matrix12d::Zero();
  for (int j = 1; j < 12; ++j) {
    const Vector12d v = eig.vectors.col(j);
    G += v * v.transpose() / (eig.values(j) - eig.values(0));
  }
  const Matrix12d cov_m = (u.sigma_px * s2) * (u.sigma_px * s2) * G * B * G;

  // vec P_raw = L m (P_raw = T₂⁻¹ P̃ T₃), then the gauge P = ±P_raw / ‖P_raw(2, 0:3)‖, whose
  // Jacobian is (±1/ν)(I − vec P · e₃ᵀ), e₃ picking P(2, 0:3).
  Matrix12d L;
  for (int k = 0; k < 12; ++k) {
    Matrix34d E = Matrix34d::Zero();
    E(k / 4, k % 4) = 1;
    const Matrix34d D = T2inv * E * T3;
    for (int i = 0; i < 12; ++i) L(i, k) = D(i / 4, i % 4);
  }
  Vector12d m, p;
  for (int i = 0; i < 12; ++i) m(i) = Pn(i / 4, i % 4), p(i) = P(i / 4, i % 4);
  const Vector12d raw = L * m;
  const double nu = raw.segment<3>(8).norm();
  const double sign = raw.dot(p) > 0 ? 1.0 : -1.0;
  Vector12d e3 = Vector12d::Zero();
  e3.segment<3>(8) = p.segment<3>(8);
  const Matrix12d Jg = (sign / nu) * (Matrix12d::Identity() - p * e3.transpose());
  const Matrix12d J = Jg * L;
  u.P_covariance = J * cov_m * J.transpose();
  u.P_covariance = 0.5 * (u.P_covariance + u.P_covariance.transpose()).eval();
  return u;
}

ExitCode DltStatusExitCode(DltStatus status) {
  switch (status) {
    case DltStatus::kOk: return ExitCode::kOk;
    case DltStatus::kCoincident:
    case DltStatus::kCollinear:
    case DltStatus::kCoplanar:
    case DltStatus::kIllConditioned: return ExitCode::kDegenerate;
    default: return ExitCode::kBadInput;
  }
}

}  // namespace vstcal
