#include "vstcal/scene/fit.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {

ResidualStats Summarize(const std::vector<Eigen::Vector2d>& residuals_px) {
  ResidualStats s;
  double sum2 = 0;
  for (const Eigen::Vector2d& r : residuals_px) {
    if (!r.allFinite()) continue;
    sum2 += r.squaredNorm();
    s.max_px = std::max(s.max_px, r.norm());
    ++s.n_points;
  }
  s.rms_px = s.n_points ? std::sqrt(sum2 / static_cast<double>(s.n_points)) : 0.0;
  return s;
}

Fit ComputeViewsFit(const Camera& camera, std::span<const Rigid3d> camera_from_view, const Correspondences& c) {
  VSTCAL_CHECK(camera_from_view.size() == c.views.size(), "one pose per view");
  Fit fit;
  std::vector<Eigen::Vector2d> all;
  for (size_t v = 0; v < c.views.size(); ++v) {
    const View& view = c.views[v];
    ViewFit vf;
    vf.name = view.name;
    vf.residuals_px.reserve(view.observations.size());
    for (const Observation& o : view.observations) {
      const auto predicted = camera.Project(camera_from_view[v] * o.point);
      if (!predicted) {
        ++fit.n_behind_camera;
        vf.residuals_px.push_back(Eigen::Vector2d::Constant(NAN));  // kept in place, excluded from stats
        continue;
      }
      vf.residuals_px.push_back(*predicted - o.pixel);
    }
    vf.stats = Summarize(vf.residuals_px);
    all.insert(all.end(), vf.residuals_px.begin(), vf.residuals_px.end());
    fit.views.push_back(std::move(vf));
  }
  fit.overall = Summarize(all);
  return fit;
}

Fit ComputeVolumeFit(const Camera& camera, const Rigid3d& camera_from_world, const Correspondences& c) {
  const std::vector<Rigid3d> same_pose(c.views.size(), camera_from_world);
  Fit fit = ComputeViewsFit(camera, same_pose, c);
  const Correspondences* files[] = {&c};
  fit.volume = MeasuredVolumeOf(files);
  for (const TestPoint& t : c.test_points) {
    TestPointFit tf;
    tf.name = t.name;
    tf.point_in_world = t.point_in_world;
    tf.predicted = camera.Project(camera_from_world * t.point_in_world);
    tf.measured = t.pixel;
    tf.inside_volume = fit.volume->Contains(t.point_in_world);
    fit.test_points.push_back(std::move(tf));
  }
  return fit;
}

}  // namespace vstcal
