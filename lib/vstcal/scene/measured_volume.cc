#include "vstcal/scene/measured_volume.h"

#include <vector>

namespace vstcal {

MeasuredVolume MeasuredVolumeOf(std::span<const Correspondences* const> files) {
  MeasuredVolume volume;
  std::vector<Eigen::Vector3d> points;
  for (const Correspondences* c : files) {
    if (c->rig != Rig::kVolume) {
      volume.status = "planar views: the boards share no world frame";
      return volume;
    }
    for (const Observation& o : AllObservations(*c)) points.push_back(o.point);
  }
  ConvexHullOutcome outcome = ConvexHull3::Of(points);
  volume.hull = std::move(outcome.hull);
  volume.status = volume.hull ? "ok" : outcome.why;
  if (volume.hull) {
    volume.vertices = volume.hull->num_vertices();
    volume.facets = volume.hull->num_facets();
  }
  return volume;
}

const char* VolumeSideName(std::optional<bool> inside_volume) {
  if (!inside_volume) return "no hull";
  return *inside_volume ? "inside" : "outside";
}

}  // namespace vstcal
