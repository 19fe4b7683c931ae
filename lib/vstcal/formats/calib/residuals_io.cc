#include "vstcal/formats/calib/residuals_io.h"

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"

namespace vstcal {

OrderedJson ResidualsToJson(const Correspondences& c, const Fit& fit, const Provenance& provenance) {
  VSTCAL_CHECK(fit.views.size() == c.views.size(), "fit and correspondences differ in views");
  OrderedJson j;
  j["format"] = "vstcal/residuals@1";
  if (!c.camera.empty()) j["camera"] = c.camera;
  j["image_size"] = {c.image_size.width, c.image_size.height};
  j["length_unit"] = LengthUnitName(c.length_unit);
  OrderedJson views = OrderedJson::array();
  for (size_t v = 0; v < c.views.size(); ++v) {
    const View& view = c.views[v];
    const ViewFit& vf = fit.views[v];
    VSTCAL_CHECK(vf.residuals_px.size() == view.observations.size(), "fit and view differ in points");
    OrderedJson points = OrderedJson::array();
    for (size_t k = 0; k < view.observations.size(); ++k) {
      const Observation& o = view.observations[k];
      const Eigen::Vector2d& r = vf.residuals_px[k];
      OrderedJson row = {o.point.x(), o.point.y(), o.point.z(), o.pixel.x(), o.pixel.y()};
      row.push_back(r.allFinite() ? OrderedJson(r.x()) : OrderedJson(nullptr));
      row.push_back(r.allFinite() ? OrderedJson(r.y()) : OrderedJson(nullptr));
      points.push_back(std::move(row));
    }
    views.push_back({{"name", view.name}, {"rms_px", vf.stats.rms_px}, {"max_px", vf.stats.max_px}, {"points", std::move(points)}});
  }
  j["views"] = std::move(views);
  j["test_points"] = FitToJson(fit)["test_points"];
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

}  // namespace vstcal
