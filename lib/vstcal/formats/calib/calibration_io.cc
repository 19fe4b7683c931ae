#include "vstcal/formats/calib/calibration_io.h"

#include "vstcal/formats/calib/dlt_io.h"

namespace vstcal {
namespace {

OrderedJson EllipseToJson(const Ellipse& e) {
  return {{"sigma_major_px", e.sigma_major_px}, {"sigma_minor_px", e.sigma_minor_px}, {"angle_deg", e.angle_deg}};
}

std::string_view VariantName(TsaiOptions::Variant v) {
  return NameOf(TsaiOptions::kVariantNames, v);
}

std::string_view PlanePrincipalPointModeName(CalibrationOptions::PlanePrincipalPoint mode) {
  return NameOf(CalibrationOptions::kPlanePrincipalPointNames, mode);
}

std::string_view LossName(RefineOptions::Loss loss) {
  return NameOf(RefineOptions::kLossNames, loss);
}

}  // namespace

OrderedJson CalibrationBlocksToJson(const CalibrationResult& r, const CalibrationOptions& options) {
  OrderedJson j = OrderedJson::object();
  if (r.dlt) {
    j["dlt"] = DltDiagnosticsToJson(*r.dlt, r.eq13, options.dlt);
    if (r.dlt_uncertainty && r.dlt_covariance) {
      const auto d = DecomposeProjection(r.dlt->P);
      VSTCAL_CHECK(d.has_value(), "a solved DLT P decomposes");
      j["dlt"]["uncertainty"] = DltUncertaintyToJson(*r.dlt_uncertainty, *r.dlt_covariance, d->camera_from_world);
    }
  }
  if (r.tsai) {
    const TsaiResult& t = *r.tsai;
    j["tsai"] = {{"variant", VariantName(t.variant)},
                 {"f_px", t.f},
                 {"f_sigma_px", t.f_sigma},
                 {"sx", t.sx},
                 {"kappa1_per_px2", t.kappa1},
                 {"principal_point", MatrixToJson(t.principal_point)},
                 {"nonlinear_iterations", t.nonlinear_iterations},
                 {"plane_rms", t.plane_rms},
                 {"conversion", {{"k1", t.camera.Param("k1")}, {"k2", t.camera.Param("k2")}, {"k3", t.camera.Param("k3")},
                                 {"max_error_px", t.conversion_max_error_px}}}};
  }
  if (r.fisheye_start) {
    const FisheyeStartDecision& d = *r.fisheye_start;
    OrderedJson candidates = OrderedJson::array();
    for (const FisheyeStartCandidate& x : d.candidates) {
      candidates.push_back({{"name", x.name},
                            {"coefficients", !x.ok ? OrderedJson(nullptr) : OrderedJson(x.coefficients_fitted ? "fitted" : "zero")},
                            {"rms_px", x.ok ? OrderedJson(d.RmsPx(x.cost)) : OrderedJson(nullptr)}});
    }
    const bool chosen = !d.chosen.empty();
    j["fisheye_start"] = {{"chosen", chosen ? OrderedJson(d.chosen) : OrderedJson(nullptr)},
                          {"coefficients", chosen ? OrderedJson(d.coefficients_fitted ? "fitted" : "zero") : OrderedJson(nullptr)},
                          {"rms_px", chosen ? OrderedJson(d.RmsPx(d.cost)) : OrderedJson(nullptr)},
                          {"candidates", std::move(candidates)}};
  }
  if (options.reject_views.enabled) {
    OrderedJson rejected = OrderedJson::array();
    for (const Rejection& x : r.rejections) {
      rejected.push_back({{"kind", x.kind == Rejection::Kind::kView ? "view" : "corner"},
                          {"round", x.round},
                          {"view", x.view_name},
                          {"view_index", x.view},
                          {"point_index", x.point ? OrderedJson(*x.point) : OrderedJson(nullptr)},
                          {x.kind == Rejection::Kind::kView ? "rms_px" : "residual_px", x.rms_px},
                          {"threshold_px", x.threshold_px},
                          {"because", x.because}});
    }
    j["view_rejection"] = {{"view_false_alarm", options.reject_views.view_false_alarm},
                           {"corner_false_alarm", options.reject_views.corner_false_alarm},
                           {"rounds", r.rejection_rounds},
                           {"sigma_px", r.rejection_sigma_px ? OrderedJson(*r.rejection_sigma_px) : OrderedJson(nullptr)},
                           {"rejected", std::move(rejected)}};
  }
  if (r.refinement) {
    const Refinement& f = *r.refinement;
    OrderedJson outliers = OrderedJson::array();
    for (const Outlier& o : f.outliers) {
      outliers.push_back({{"view", r.used.views[o.view].name}, {"view_index", o.view}, {"point_index", o.point},
                          {"residual_px", MatrixToJson(o.residual_px)}, {"sigmas", o.normalized}});
    }
    OrderedJson held = OrderedJson::array();
    OrderedJson conditional_on = OrderedJson::array();
    for (const HeldIntrinsic& h : f.held) {
      held.push_back({{"parameter", h.parameter}, {"value", h.value}, {"because", h.because}});
      conditional_on.push_back(h.parameter);
    }
    OrderedJson priors = OrderedJson::array();
    for (const IntrinsicPrior& p : f.priors) {
      priors.push_back({{"parameter", p.parameter}, {"value", p.value}, {"sigma", p.sigma}, {"because", p.because}});
    }
    j["refinement"] = {{"status", f.status == RefineStatus::kConverged ? "converged" : "not converged"},
                       {"iterations", f.iterations},
                       {"initial_rms_px", f.initial_rms_px},
                       {"free_intrinsics", f.free.MovedParams(f.camera.model)},
                       {"held", std::move(held)},
                       {"priors", std::move(priors)},
                       {"covariance_conditional_on", std::move(conditional_on)},
                       {"smallest_scaled_eigenvalue", f.smallest_scaled_eigenvalue},
                       {"loss", LossName(options.refinement.loss)},
                       {"loss_scale_px", options.refinement.loss_scale_px},
                       {"sigma_px", f.sigma_px},
                       {"sigma_from", f.sigma_inliers_only ? "inliers" : "all points"},
                       {"robust_sigma_px", f.robust_sigma_px},
                       {"dof", f.dof},
                       {"outlier_false_alarm", options.refinement.outlier_false_alarm},
                       {"outliers", std::move(outliers)}};
    if (r.plane_principal_point) {
      const PlanePrincipalPointDecision& d = *r.plane_principal_point;
      const bool prior = d.mode == CalibrationOptions::PlanePrincipalPoint::kPrior;
      j["refinement"]["one_plane"] = {
          {"principal_point", d.mode == CalibrationOptions::PlanePrincipalPoint::kHold ? "held" : prior ? "prior" : "free"},
          {"mode", PlanePrincipalPointModeName(d.mode)},
          {"prior_px", prior ? MatrixToJson(d.prior_px) : OrderedJson(nullptr)},
          {"prior_sigma_px", prior ? OrderedJson(d.prior_sigma_px) : OrderedJson(nullptr)},
          {"posterior_sigma_px", d.posterior_sigma_px ? MatrixToJson(*d.posterior_sigma_px) : OrderedJson(nullptr)},
          {"because", d.because}};
    }
  }
  return j;
}

OrderedJson UncertaintyToJson(const CalibratedCamera& c, const UncertaintyRequest& request) {
  if (!c.covariance) return nullptr;
  using Kind = ProjectionUncertaintyKind;
  // Both kinds at one place, under their own names, so that neither is read for the other.
  auto both = [](OrderedJson j, const auto& ellipse_of) {
    for (const auto& [key, kind] : {std::pair{"with_poses", Kind::kWithPoses}, std::pair{"intrinsics_only", Kind::kIntrinsicsOnly}}) {
      const auto e = ellipse_of(kind);
      j[key] = e ? EllipseToJson(*e) : OrderedJson(nullptr);
    }
    return j;
  };
  OrderedJson j;
  j["kinds"] = {{"with_poses", kWithPosesMeaning}, {"intrinsics_only", kIntrinsicsOnlyMeaning}};
  OrderedJson tests = OrderedJson::array();
  if (c.fit && c.camera_from_world) {
    for (const TestPointFit& t : c.fit->test_points) {
      tests.push_back(both({{"name", t.name}}, [&](Kind k) { return ProjectionUncertaintyAtWorldPoint(c, t.point_in_world, k); }));
    }
  }
  j["test_points"] = std::move(tests);
  OrderedJson points = OrderedJson::array();
  for (const Eigen::Vector3d& p : request.world_points) {
    points.push_back(both({{"world", MatrixToJson(p)}}, [&](Kind k) { return ProjectionUncertaintyAtWorldPoint(c, p, k); }));
  }
  j["world_points"] = std::move(points);
  OrderedJson pixels = OrderedJson::array();
  for (const Eigen::Vector3d& q : request.pixel_depths) {
    pixels.push_back(both({{"pixel", MatrixToJson(Eigen::Vector2d(q.head<2>()))}, {"depth", q.z()}},
                          [&](Kind k) { return ProjectionUncertaintyAtPixel(c, q.head<2>(), q.z(), k); }));
  }
  j["pixels"] = std::move(pixels);
  if (request.grid_depth) {
    const auto with_poses = ProjectionUncertaintyGrid(c, *request.grid_depth, request.grid_cols, request.grid_rows, Kind::kWithPoses);
    const auto intrinsics = ProjectionUncertaintyGrid(c, *request.grid_depth, request.grid_cols, request.grid_rows, Kind::kIntrinsicsOnly);
    OrderedJson cells = OrderedJson::array();
    for (size_t i = 0; i < with_poses.size() && i < intrinsics.size(); ++i) {
      const Ellipse& a = with_poses[i].ellipse;
      const Ellipse& b = intrinsics[i].ellipse;
      cells.push_back({with_poses[i].pixel.x(), with_poses[i].pixel.y(), a.sigma_major_px, a.sigma_minor_px, a.angle_deg,
                       b.sigma_major_px, b.sigma_minor_px, b.angle_deg});
    }
    j["grid"] = {{"depth", *request.grid_depth},
                 {"cols", request.grid_cols},
                 {"rows", request.grid_rows},
                 {"columns", {"u", "v", "with_poses.sigma_major_px", "with_poses.sigma_minor_px", "with_poses.angle_deg",
                              "intrinsics_only.sigma_major_px", "intrinsics_only.sigma_minor_px",
                              "intrinsics_only.angle_deg"}},
                 {"cells", std::move(cells)}};
  }
  return j;
}

}  // namespace vstcal
