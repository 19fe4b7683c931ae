// The covariance by Schur elimination of the poses (estimators/information.h, arrow_information.h)
// against the dense path it replaced (tests/support/dense_covariance.h, the old refine.cc code):
// every block equal to 1e-9 relative on small problems — planar views, a volume, a tied aspect,
// weights, a robust loss — and the pose–pose blocks it does not store, implied through the
// parameters, equal too. Then the verdict and the covariance are unit-free: the same data in
// mm, cm, m, in and ×1e±6 give the same verdict and the same covariance up to the unit
// conversion, and an unobservable parameter is named.
#include <gtest/gtest.h>

#include <cmath>

#include "support/dense_covariance.h"
#include "support/scenes.h"
#include "vstcal/estimators/information.h"
#include "vstcal/calib/refine.h"
#include "vstcal/calib/zhang.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

Camera WideCamera() { return testing::DistortedWideCamera(); }

SyntheticViews Planar(int views, double noise, uint64_t seed) {
  PlanarViewsSpec spec;
  spec.num_views = views;
  spec.noise_px = noise;
  spec.seed = seed;
  return SynthesizePlanarViews(WideCamera(), spec);
}

Refinement RefinePlanar(const Correspondences& c, const RefineOptions& options = {}) {
  const ZhangResult zhang = ZhangInitialization(c);
  EXPECT_TRUE(zhang.ok) << zhang.message;
  return Refine(c, zhang.camera, zhang.camera_from_board, options);
}

// |a − b| ≤ tolerance · √(b_ii b_jj) for a block of a covariance whose diagonals are di, dj.
void ExpectBlockNear(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const Eigen::VectorXd& di,
                     const Eigen::VectorXd& dj, double tolerance, const std::string& what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    for (Eigen::Index j = 0; j < a.cols(); ++j) {
      EXPECT_LE(std::abs(a(i, j) - b(i, j)), tolerance * std::sqrt(di(i) * dj(j))) << what << " (" << i << ", " << j << ")";
    }
  }
}

// The rows of B that move a lens parameter (CovarianceAt's parameter order).
Eigen::MatrixXd MovedBasis(const FreeIntrinsics& free) {
  std::vector<Eigen::Index> rows;
  for (Eigen::Index i = 0; i < free.basis.rows(); ++i) {
    if (!free.basis.row(i).isZero(0)) rows.push_back(i);
  }
  Eigen::MatrixXd B(static_cast<Eigen::Index>(rows.size()), free.basis.cols());
  for (size_t k = 0; k < rows.size(); ++k) B.row(static_cast<Eigen::Index>(k)) = free.basis.row(rows[k]);
  return B;
}

// Every stored block of CovarianceAt equals the dense oracle's to 1e-9 relative, and so do the
// pose–pose blocks it implies (checked through PropagateCovariance on random Jacobians).
// `dense_data` (default: c) and `sigma_per_view` are what the oracle is given instead.
void ExpectEqualToDense(const Correspondences& c, const Camera& camera, const std::vector<Rigid3d>& poses,
                        const RefineOptions& options, double sigma, const Correspondences* dense_data = nullptr,
                        const std::optional<std::vector<double>>& sigma_per_view = std::nullopt) {
  constexpr double kTolerance = 1e-9;
  const CalibrationCovariance arrow = CovarianceAt(c, camera, poses, options, sigma);
  const testing::DenseCovariance dense =
      testing::DenseCovarianceAt(dense_data ? *dense_data : c, camera, poses, options, sigma, sigma_per_view);
  ASSERT_TRUE(arrow.observable) << arrow.message;
  ASSERT_GT(dense.covariance.size(), 0);
  const Eigen::MatrixXd& D = dense.covariance;
  const Eigen::VectorXd d = D.diagonal();
  const int g = arrow.free.size();
  ExpectBlockNear(arrow.free_covariance, D.topLeftCorner(g, g), d.head(g), d.head(g), kTolerance, "intrinsics");

  // Over lens parameters: Σ_θ = B Σ_β Bᵀ, Cov(δ, θ) = Cov(δ, β) Bᵀ.
  const Eigen::MatrixXd B = MovedBasis(arrow.free);
  const Eigen::Index n = B.rows();
  const Eigen::MatrixXd theta = B * D.topLeftCorner(g, g) * B.transpose();
  const ParameterCovariance& cov = arrow.covariance;
  ExpectBlockNear(cov.matrix.topLeftCorner(n, n), theta, theta.diagonal(), theta.diagonal(), kTolerance, "lens parameters");
  for (size_t v = 0; v < poses.size(); ++v) {
    const Eigen::Index at = g + 6 * static_cast<Eigen::Index>(v);
    const Eigen::MatrixXd pose = D.block(at, at, 6, 6);
    const Eigen::MatrixXd cross = D.block(at, 0, 6, g) * B.transpose();
    const Eigen::MatrixXd got_pose = c.rig == Rig::kVolume ? Eigen::MatrixXd(cov.matrix.bottomRightCorner(6, 6)) : Eigen::MatrixXd(cov.poses[v].matrix);
    const Eigen::MatrixXd got_cross =
        c.rig == Rig::kVolume ? Eigen::MatrixXd(cov.matrix.bottomLeftCorner(6, n)) : Eigen::MatrixXd(cov.poses[v].with_parameters);
    ExpectBlockNear(got_pose, pose, pose.diagonal(), pose.diagonal(), kTolerance, "pose " + std::to_string(v));
    ExpectBlockNear(got_cross, cross, pose.diagonal(), theta.diagonal(), kTolerance, "pose–intrinsics " + std::to_string(v));
  }
  if (c.rig == Rig::kVolume) return;
  // Pose–pose blocks are not stored: y = J_θ θ + Σ_v J_v δ_v with random Jacobians propagates
  // through the implied Σ_vg Σ_gg⁻ Σ_gw exactly as through the dense matrix.
  const CounterRng rng(99, 0);
  Eigen::MatrixXd J_theta(2, n), J_full = Eigen::MatrixXd::Zero(2, D.cols());
  for (Eigen::Index i = 0; i < n; ++i) J_theta.col(i) << rng.Normal2(static_cast<uint64_t>(i), 0)[0], rng.Normal2(static_cast<uint64_t>(i), 0)[1];
  J_full.leftCols(g) = J_theta * B;
  std::vector<PoseJacobian> pose_jacobians;
  for (size_t v = 0; v < poses.size(); ++v) {
    Eigen::MatrixXd Jv(2, 6);
    for (int k = 0; k < 6; ++k) {
      const auto z = rng.Normal2(1000 + 6 * v + static_cast<uint64_t>(k), 0);
      Jv.col(k) << z[0], z[1];
    }
    J_full.middleCols(g + 6 * static_cast<Eigen::Index>(v), 6) = Jv;
    pose_jacobians.push_back({v, Jv});
  }
  const Eigen::Matrix2d want = J_full * D * J_full.transpose();
  const Eigen::Matrix2d got = PropagateCovariance(cov, J_theta, pose_jacobians);
  ExpectBlockNear(got, want, want.diagonal(), want.diagonal(), kTolerance, "propagated through every pose");
}

TEST(SchurCovariance, PlanarViewsEqualTheDensePath) {
  const SyntheticViews data = Planar(12, 0.3, 2);
  const Refinement r = RefinePlanar(data.correspondences);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  ExpectEqualToDense(data.correspondences, r.camera, r.poses, RefineOptions{}, r.sigma_px);
  // And the refinement reports exactly that covariance.
  const CalibrationCovariance again = CovarianceAt(data.correspondences, r.camera, r.poses, RefineOptions{}, r.sigma_px);
  EXPECT_EQ(r.covariance.matrix, again.covariance.matrix);
  EXPECT_EQ(r.covariance.parameters, again.covariance.parameters);
}

TEST(SchurCovariance, RationalModelSkewWeightsAndRobustLossEqualTheDensePath) {
  SyntheticViews data = Planar(10, 0.3, 3);
  Correspondences& c = data.correspondences;
  for (size_t v = 0; v < c.views.size(); ++v) {
    for (size_t k = 0; k < c.views[v].observations.size(); ++k) c.views[v].observations[k].weight = 0.25 + 0.5 * ((v + k) % 4);
  }
  c.views[2].observations[5].pixel.x() += 9;  // an outlier, so that ρ′ < 1 somewhere
  RefineOptions options;
  options.free_distortion = {"k1", "k2", "p1", "p2", "k4"};
  options.free_skew = true;
  options.loss = RefineOptions::Loss::kHuber;
  options.loss_scale_px = 0.8;
  const Refinement r = RefinePlanar(c, options);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  EXPECT_EQ(LensModelName(r.camera.model), "rational");
  ExpectEqualToDense(c, r.camera, r.poses, options, r.sigma_px);
}

TEST(SchurCovariance, VolumeAndTiedAspectEqualTheDensePath) {
  VolumeSpec spec = testing::NearWideVolumeSpec();
  spec.noise_px = 0.2;
  const SyntheticVolume volume = SynthesizeVolume(WideCamera(), spec, {});
  const Camera truth = WideCamera();
  ExpectEqualToDense(volume.correspondences, truth, {volume.camera_from_world}, RefineOptions{}, 0.2);
  RefineOptions tied;
  tied.focal_aspect = 700.2 / 698.4;
  tied.free_principal_point = false;
  ExpectEqualToDense(volume.correspondences, truth, {volume.camera_from_world}, tied, 0.2);
  // fx and fy move as one: their correlation is exactly 1 in the written covariance.
  const ParameterCovariance cov = CovarianceAt(volume.correspondences, truth, {volume.camera_from_world}, tied, 0.2).covariance;
  ASSERT_EQ(cov.parameters[0], "fx");
  ASSERT_EQ(cov.parameters[1], "fy");
  EXPECT_NEAR(cov.matrix(0, 1) / std::sqrt(cov.matrix(0, 0) * cov.matrix(1, 1)), 1.0, 1e-12);
  EXPECT_NEAR(std::sqrt(cov.matrix(0, 0) / cov.matrix(1, 1)), *tied.focal_aspect, 1e-12);
}

// Weights enter the information as inverse variances: scaling view v's weights by k gives what
// the dense path gives with view v's σ divided by √k (and weight 1) — the dense path scales rows
// by 1/σ_v, knowing nothing of weights.
TEST(Weights, ScalingAViewsWeightsByKIsDividingItsSigmaBySqrtK) {
  const SyntheticViews data = Planar(8, 0.3, 4);
  const Refinement r = RefinePlanar(data.correspondences);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  for (const double k : {4.0, 0.3}) {
    Correspondences weighted = data.correspondences;
    for (Observation& o : weighted.views[3].observations) o.weight = k;
    std::vector<double> sigma(weighted.views.size(), 0.3);
    sigma[3] = 0.3 / std::sqrt(k);
    ExpectEqualToDense(weighted, r.camera, r.poses, RefineOptions{}, 0.3, &data.correspondences, sigma);
  }
}

// A point of integer weight k counts as k points: weighting view 4 by 3 gives the estimate,
// the information and the weighted residual sum of listing view 4's points three times.
TEST(Weights, IntegerWeightEqualsRepeatedPoints) {
  const SyntheticViews data = Planar(8, 0.3, 5);
  Correspondences weighted = data.correspondences, repeated = data.correspondences;
  for (Observation& o : weighted.views[4].observations) o.weight = 3;
  std::vector<Observation>& obs = repeated.views[4].observations;
  const std::vector<Observation> once = obs;
  for (int copy = 0; copy < 2; ++copy) obs.insert(obs.end(), once.begin(), once.end());
  const Refinement a = RefinePlanar(weighted), b = RefinePlanar(repeated);
  ASSERT_EQ(a.status, RefineStatus::kConverged) << a.message;
  ASSERT_EQ(b.status, RefineStatus::kConverged) << b.message;
  for (size_t i = 0; i < a.camera.params.size(); ++i) {
    EXPECT_NEAR(a.camera.params[i], b.camera.params[i], 1e-8 * (1 + std::abs(b.camera.params[i]))) << i;
  }
  // σ̂² dof is the weighted residual sum; dof counts points, so it differs by the copies.
  EXPECT_EQ(b.dof - a.dof, 2 * 2 * static_cast<int>(once.size()));
  EXPECT_NEAR(a.sigma_px * a.sigma_px * a.dof, b.sigma_px * b.sigma_px * b.dof, 1e-8 * b.sigma_px * b.sigma_px * b.dof);
  const Eigen::MatrixXd ia = a.covariance.matrix / (a.sigma_px * a.sigma_px);
  const Eigen::MatrixXd ib = b.covariance.matrix / (b.sigma_px * b.sigma_px);
  ExpectBlockNear(ia, ib, ib.diagonal(), ib.diagonal(), 1e-6, "(JᵀWJ)⁻¹");
}

// When the noise really differs between views, weights of 1/σ_v² beat equal weights: over 24
// noise draws (half the views at 0.1 px, half at 1 px) the weighted estimate's mean squared error
// of fx, fy, cx, cy is several times smaller (theory for this split: about 25×; required: 4×),
// and the weighted fit's σ̂ estimates the weight-1 noise, 0.1 px.
TEST(Weights, WeightedFitsBeatUnweightedWhenTheNoiseDiffers) {
  const SyntheticViews clean = Planar(12, 0.0, 6);
  const Camera truth = WideCamera();
  double mse_weighted = 0, mse_plain = 0;
  const int trials = 24;
  for (int t = 0; t < trials; ++t) {
    Correspondences plain = clean.correspondences;
    const CounterRng rng(500 + static_cast<uint64_t>(t), 0);
    uint64_t k = 0;
    for (size_t v = 0; v < plain.views.size(); ++v) {
      const double sigma = v % 2 == 0 ? 0.1 : 1.0;
      for (Observation& o : plain.views[v].observations) {
        const auto e = rng.Normal2(k++, 0);
        o.pixel += sigma * Eigen::Vector2d(e[0], e[1]);
      }
    }
    Correspondences weighted = plain;
    for (size_t v = 1; v < weighted.views.size(); v += 2) {
      for (Observation& o : weighted.views[v].observations) o.weight = 0.01;  // (0.1 / 1)²
    }
    const Refinement a = RefinePlanar(weighted), b = RefinePlanar(plain);
    ASSERT_EQ(a.status, RefineStatus::kConverged) << a.message;
    ASSERT_EQ(b.status, RefineStatus::kConverged) << b.message;
    for (int i = 0; i < 4; ++i) {
      mse_weighted += std::pow(a.camera.params[i] - truth.params[i], 2);
      mse_plain += std::pow(b.camera.params[i] - truth.params[i], 2);
    }
    EXPECT_NEAR(a.sigma_px, 0.1, 5 * 0.1 / std::sqrt(2.0 * a.dof)) << t;
  }
  ::testing::Test::RecordProperty("mse ratio plain/weighted", ::testing::PrintToString(mse_plain / mse_weighted));
  EXPECT_GT(mse_plain / mse_weighted, 4.0);
}

// Before any capture (what calib-capture plan does): the covariance at the planned camera and
// board poses with a stated noise, without solving, predicts what the solve of the noisy capture
// reports — the same code path at a nearby point. Intrinsics' σ's agree to a few percent.
TEST(CovarianceAt, PredictsBeforeCaptureWhatTheSolveReports) {
  const SyntheticViews clean = Planar(15, 0.0, 13);
  const CalibrationCovariance plan = CovarianceAt(clean.correspondences, WideCamera(), clean.camera_from_board, RefineOptions{}, 0.3);
  ASSERT_TRUE(plan.observable) << plan.message;
  const Correspondences noisy = testing::WithNoise(clean.correspondences, 0.3, 14);
  const Refinement r = RefinePlanar(noisy);
  ASSERT_EQ(r.status, RefineStatus::kConverged) << r.message;
  ASSERT_EQ(plan.covariance.parameters, r.covariance.parameters);
  const double scale = 0.3 / r.sigma_px;  // the plan states σ; the solve estimates it
  for (size_t i = 0; i < plan.covariance.parameters.size(); ++i) {
    const double planned = std::sqrt(plan.covariance.matrix(i, i));
    const double reported = scale * std::sqrt(r.covariance.matrix(i, i));
    EXPECT_NEAR(planned / reported, 1.0, 0.03) << plan.covariance.parameters[i];
  }
}

// The same capture in mm, cm, m, in and with its coordinates ×1e6 and ×1e-6: one verdict, and one
// covariance up to the unit conversion (translation tangents scale by the factor, rotations and
// intrinsics not at all), at the same parameters and after refining each from its own start.
TEST(Observability, UnitFree) {
  const SyntheticViews data = Planar(10, 0.3, 7);
  const Refinement mm = RefinePlanar(data.correspondences);
  ASSERT_EQ(mm.status, RefineStatus::kConverged) << mm.message;
  const ParameterCovariance& ref = mm.covariance;
  for (const double s : {0.1, 1e-3, 1 / 25.4, 1e6, 1e-6}) {
    Correspondences c = data.correspondences;
    for (View& v : c.views) {
      for (Observation& o : v.observations) o.point *= s;
    }
    std::vector<Rigid3d> poses = mm.poses;
    for (Rigid3d& p : poses) p.t *= s;
    const CalibrationCovariance at = CovarianceAt(c, mm.camera, poses, RefineOptions{}, mm.sigma_px);
    ASSERT_TRUE(at.observable) << s << ": " << at.message;
    const Eigen::VectorXd d = ref.matrix.diagonal();
    ExpectBlockNear(at.covariance.matrix, ref.matrix, d, d, 1e-9, "intrinsics at ×" + std::to_string(s));
    const Eigen::Matrix<double, 6, 1> unit = (Eigen::Matrix<double, 6, 1>() << 1, 1, 1, s, s, s).finished();
    for (size_t v = 0; v < poses.size(); ++v) {
      const Matrix6d want = unit.asDiagonal() * ref.poses[v].matrix * unit.asDiagonal();
      ExpectBlockNear(at.covariance.poses[v].matrix, want, want.diagonal(), want.diagonal(), 1e-9, "pose");
      const Matrix6Xd cross = unit.asDiagonal() * ref.poses[v].with_parameters;
      ExpectBlockNear(at.covariance.poses[v].with_parameters, cross, want.diagonal(), d, 1e-9, "pose–intrinsics");
    }
    // Refined from its own start in its own unit: the same camera and intrinsics' covariance.
    const Refinement r = RefinePlanar(c);
    ASSERT_EQ(r.status, RefineStatus::kConverged) << s << ": " << r.message;
    ASSERT_EQ(r.covariance.parameters, ref.parameters);
    // (Ceres stops at a relative cost change of 1e-10, wherever its path from this unit's start
    // led: the estimates agree to a small fraction of σ, as two solvers' do.)
    const auto names = LensModelParamNames(r.camera.model);
    for (size_t i = 0; i < names.size(); ++i) {
      if (const auto index = ref.Find(names[i])) {
        EXPECT_NEAR(r.camera.params[i], mm.camera.params[i], 0.01 * std::sqrt(d(*index))) << s << " " << names[i];
      }
    }
    ExpectBlockNear(r.covariance.matrix, ref.matrix, d, d, 0.01, "refined intrinsics at ×" + std::to_string(s));
  }
}

// A long-focal (f = 3000 px) volume in millimetres with k1, k2, p1, p2, k3 free: well posed, but
// the unscaled information's eigenvalues span more than 1e13 (the old test refused it; the dense
// oracle shows that ratio). The scaled verdict gives a covariance, the same one in metres.
TEST(Observability, LongFocalVolumeInMillimetresIsObservable) {
  Eigen::Matrix3d K;
  K << 3000, 0, 640, 0, 3000, 360, 0, 0, 1;
  const double dist[5] = {-0.05, 0.1, 0.0002, -0.0001, 0.2};
  const Camera camera = Camera::FromK(K, ImageSize{1280, 720}, RadialTangentialModel{}, dist);
  VolumeSpec spec;
  spec.grid_cols = 13;
  spec.grid_rows = 9;
  spec.spacing = 60;
  spec.far = 600;
  spec.interval = 100;
  spec.camera_distance = 2500;
  spec.tilt_deg = 10;
  const SyntheticVolume volume = SynthesizeVolume(camera, spec, {});
  RefineOptions options;
  options.free_distortion = {"k1", "k2", "p1", "p2", "k3"};
  const testing::DenseCovariance old = testing::DenseCovarianceAt(volume.correspondences, camera, {volume.camera_from_world}, options, 0.2);
  ::testing::Test::RecordProperty("unscaled eigenvalue ratio", ::testing::PrintToString(old.unscaled_eigenvalue_ratio));
  EXPECT_LT(old.unscaled_eigenvalue_ratio, 1e-13);  // what the old test called singular
  const CalibrationCovariance mm = CovarianceAt(volume.correspondences, camera, {volume.camera_from_world}, options, 0.2);
  ASSERT_TRUE(mm.observable) << mm.message;
  EXPECT_GT(mm.smallest_scaled_eigenvalue, 1e-8);
  Correspondences metres = volume.correspondences;
  metres.length_unit = LengthUnit::kMetre;
  for (View& v : metres.views) {
    for (Observation& o : v.observations) o.point *= 1e-3;
  }
  Rigid3d pose = volume.camera_from_world;
  pose.t *= 1e-3;
  const CalibrationCovariance m = CovarianceAt(metres, camera, {pose}, options, 0.2);
  ASSERT_TRUE(m.observable) << m.message;
  ExpectBlockNear(m.free_covariance, mm.free_covariance, mm.free_covariance.diagonal(), mm.free_covariance.diagonal(), 1e-9,
                  "intrinsics, m vs mm");
}

// One board seen once cannot fix fx, fy, cx and cy together (Zhang 2000, §3.1): the message names
// the parameters along the null direction and says what to hold or add.
TEST(Observability, UnobservableParametersAreNamed) {
  const SyntheticViews one = Planar(1, 0.2, 8);
  const ZhangResult zhang = ZhangInitialization(Planar(4, 0.2, 8).correspondences);
  ASSERT_TRUE(zhang.ok) << zhang.message;
  RefineOptions options;
  options.free_distortion = {};
  const CalibrationCovariance cov = CovarianceAt(one.correspondences, zhang.camera, {one.camera_from_board[0]}, options, 0.2);
  EXPECT_FALSE(cov.observable);
  EXPECT_EQ(cov.message.rfind("the information matrix is singular: ", 0), 0u) << cov.message;
  EXPECT_NE(cov.message.find("not determined by these points"), std::string::npos) << cov.message;
  EXPECT_NE(cov.message.find("hold the principal point, or add views of the board tilted about other axes"), std::string::npos)
      << cov.message;
}

// A view whose points lie on one line leaves its own pose undetermined: named by the view.
TEST(Observability, ASingularPoseNamesItsView) {
  SyntheticViews data = Planar(6, 0.2, 10);
  const ZhangResult zhang = ZhangInitialization(data.correspondences);
  ASSERT_TRUE(zhang.ok);
  std::vector<Observation>& obs = data.correspondences.views[2].observations;
  std::erase_if(obs, [](const Observation& o) { return o.point.y() != 0.0; });  // one row of the board
  const CalibrationCovariance cov = CovarianceAt(data.correspondences, WideCamera(), zhang.camera_from_board, RefineOptions{}, 0.2);
  EXPECT_FALSE(cov.observable);
  EXPECT_NE(cov.message.find("do not determine view \"" + data.correspondences.views[2].name + "\""), std::string::npos)
      << cov.message;
  EXPECT_NE(cov.message.find("views[2].camera_from_board"), std::string::npos) << cov.message;
}

}  // namespace
}  // namespace vstcal
