#include "vstcal/estimators/length_range.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Eigenvalues>

namespace vstcal {

std::optional<std::string> LengthsOutOfRange(const Correspondences& c, std::optional<size_t> view) {
  std::vector<Eigen::Vector3d> points;
  for (size_t v = 0; v < c.views.size(); ++v) {
    if (!view || v == *view) {
      for (const Observation& o : c.views[v].observations) points.push_back(o.point);
    }
  }
  if (points.size() <= 6) return std::nullopt;
  double largest = 0;
  for (const Eigen::Vector3d& p : points) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (!(largest > 0) || !std::isfinite(largest)) return std::nullopt;
  // The spread of the points scaled by a power of two to order 1.
  const double scale = std::ldexp(1.0, -std::ilogb(largest));
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += scale * p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) scatter += (scale * p - mean) * (scale * p - mean).transpose();
  const Eigen::Vector3d spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvalues();
  if (!(spread(1) > 1e-12 * spread(2))) return std::nullopt;  // on one line
  const double extent = std::sqrt(spread(2) / static_cast<double>(points.size())) / scale;
  if (extent > 1e-50 && extent < 1e50) return std::nullopt;
  char buf[160];
  std::snprintf(buf, sizeof buf, "the points spread over %.3g %s, beyond the lengths (1e-50 to 1e50) the solver computes with",
                extent, std::string(LengthUnitName(c.length_unit)).c_str());
  return std::string(buf);
}

}  // namespace vstcal
