#include "vstcal/calib/correspondences.h"

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

}  // namespace vstcal
