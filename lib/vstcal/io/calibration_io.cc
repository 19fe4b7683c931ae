#include "vstcal/io/calibration_io.h"

#include "vstcal/io/dlt_io.h"

namespace vstcal::io {
namespace {

OrderedJson EllipseToJson(const Ellipse& e) {
  return {{"sigma_major_px", e.sigma_major_px}, {"sigma_minor_px", e.sigma_minor_px}, {"angle_deg", e.angle_deg}};
}

std::string_view VariantName(TsaiOptions::Variant v) {
  switch (v) {
    case TsaiOptions::Variant::kCoplanar: return "coplanar";
    case TsaiOptions::Variant::kNonCoplanar: return "non-coplanar";
    default: return "auto";
  }
}

std::string_view LossName(RefineOptions::Loss loss) {
  switch (loss) {
    case RefineOptions::Loss::kHuber: return "huber";
    case RefineOptions::Loss::kCauchy: return "cauchy";
    default: return "none";
  }
}

}  // namespace

OrderedJson CalibrationBlocksToJson(const CalibrationResult& r, const CalibrationOptions& options) {
  OrderedJson j = OrderedJson::object();
  if (r.dlt) {
    j["dlt"] = DltDiagnosticsToJson(*r.dlt, r.eq13, options.dlt);
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
                 {"conversion", {{"k1", t.camera.params[5]}, {"k2", t.camera.params[6]}, {"k3", t.camera.params[9]},
                                 {"max_error_px", t.conversion_max_error_px}}}};
  }
  if (r.refinement) {
    const Refinement& f = *r.refinement;
    OrderedJson outliers = OrderedJson::array();
    for (const Outlier& o : f.outliers) {
      outliers.push_back({{"view", r.used.views[o.view].name}, {"view_index", o.view}, {"point_index", o.point},
                          {"residual_px", MatrixToJson(o.residual_px)}, {"sigmas", o.normalized}});
    }
    j["refinement"] = {{"status", f.status == RefineStatus::kConverged ? "converged" : "not converged"},
                       {"iterations", f.iterations},
                       {"initial_rms_px", f.initial_rms_px},
                       {"free_intrinsics", FreeIntrinsicNames(f.camera.model, options.refinement)},
                       {"loss", LossName(options.refinement.loss)},
                       {"loss_scale_px", options.refinement.loss_scale_px},
                       {"sigma_px", f.sigma_px},
                       {"sigma_from", f.sigma_inliers_only ? "inliers" : "all points"},
                       {"robust_sigma_px", f.robust_sigma_px},
                       {"dof", f.dof},
                       {"outlier_false_alarm", options.refinement.outlier_false_alarm},
                       {"outliers", std::move(outliers)}};
  }
  return j;
}

OrderedJson UncertaintyToJson(const CalibratedCamera& c, const UncertaintyRequest& request) {
  if (!c.covariance) return nullptr;
  OrderedJson j;
  OrderedJson tests = OrderedJson::array();
  if (c.fit && c.camera_from_world) {
    for (const TestPointFit& t : c.fit->test_points) {
      const auto e = ProjectionUncertaintyAtWorldPoint(c, t.point_in_world);
      tests.push_back({{"name", t.name}, {"ellipse", e ? EllipseToJson(*e) : OrderedJson(nullptr)}});
    }
  }
  j["test_points"] = std::move(tests);
  OrderedJson points = OrderedJson::array();
  for (const Eigen::Vector3d& p : request.world_points) {
    const auto e = ProjectionUncertaintyAtWorldPoint(c, p);
    points.push_back({{"world", MatrixToJson(p)}, {"ellipse", e ? EllipseToJson(*e) : OrderedJson(nullptr)}});
  }
  j["world_points"] = std::move(points);
  OrderedJson pixels = OrderedJson::array();
  for (const Eigen::Vector3d& q : request.pixel_depths) {
    const auto e = ProjectionUncertaintyAtPixel(c, q.head<2>(), q.z());
    pixels.push_back({{"pixel", MatrixToJson(Eigen::Vector2d(q.head<2>()))},
                      {"depth", q.z()},
                      {"ellipse", e ? EllipseToJson(*e) : OrderedJson(nullptr)}});
  }
  j["pixels"] = std::move(pixels);
  if (request.grid_depth) {
    OrderedJson cells = OrderedJson::array();
    for (const UncertaintyCell& cell :
         ProjectionUncertaintyGrid(c, *request.grid_depth, request.grid_cols, request.grid_rows)) {
      cells.push_back({cell.pixel.x(), cell.pixel.y(), cell.ellipse.sigma_major_px, cell.ellipse.sigma_minor_px,
                       cell.ellipse.angle_deg});
    }
    j["grid"] = {{"depth", *request.grid_depth},
                 {"cols", request.grid_cols},
                 {"rows", request.grid_rows},
                 {"columns", {"u", "v", "sigma_major_px", "sigma_minor_px", "angle_deg"}},
                 {"cells", std::move(cells)}};
  }
  return j;
}

}  // namespace vstcal::io
