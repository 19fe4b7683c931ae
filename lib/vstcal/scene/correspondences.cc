#include "vstcal/scene/correspondences.h"

#include <algorithm>
#include <cmath>

namespace vstcal {

size_t NumObservations(const Correspondences& c) {
  size_t n = 0;
  for (const View& v : c.views) n += v.observations.size();
  return n;
}

std::vector<Observation> AllObservations(const Correspondences& c) {
  std::vector<Observation> all;
  all.reserve(NumObservations(c));
  for (const View& v : c.views) all.insert(all.end(), v.observations.begin(), v.observations.end());
  return all;
}

double WorldCoordinateScale(std::span<const Observation> observations, const Eigen::Vector3d& origin) {
  double largest = 0;
  for (const Observation& o : observations) largest = std::max(largest, (o.point - origin).cwiseAbs().maxCoeff());
  if (!(largest > 0 && std::isfinite(largest)) || (largest > 1e-100 && largest < 1e100)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(largest));
}

}  // namespace vstcal
