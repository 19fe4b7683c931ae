#include "vstcal/geometry/convex_hull.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}

#include "vstcal/core/error.h"
#include "vstcal/geometry/linalg.h"

namespace vstcal {
namespace {

// Qhull reports its errors on a FILE*; they become `why` instead of reaching a tool's stderr.
class MemoryFile {
 public:
  MemoryFile() : file_(open_memstream(&buffer_, &size_)) { VSTCAL_CHECK(file_ != nullptr, "open_memstream"); }
  ~MemoryFile() {
    if (file_) std::fclose(file_);
    std::free(buffer_);
  }
  FILE* get() const { return file_; }
  std::string FirstLine() {
    std::fflush(file_);
    std::string text = buffer_ ? std::string(buffer_, size_) : std::string();
    return text.substr(0, text.find('\n'));
  }

 private:
  char* buffer_ = nullptr;
  size_t size_ = 0;
  FILE* file_;
};

// Why the points span no volume, or empty: the smallest singular value of the centred points
// against the largest tells a plane or a line apart from a volume before Qhull is asked.
std::string WhyNoVolume(std::span<const Eigen::Vector3d> points) {
  if (points.size() < 4) return "fewer than 4 points";
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::MatrixXd centred(points.size(), 3);
  for (size_t i = 0; i < points.size(); ++i) centred.row(static_cast<Eigen::Index>(i)) = (points[i] - mean).transpose();
  const Eigen::Vector3d s = DecomposeSvd(centred, 0).singular_values;
  if (!(s(0) > 0)) return "all points coincide";
  if (s(1) <= 1e-12 * s(0)) return "the points lie on one line";
  if (s(2) <= 1e-12 * s(0)) return "the points lie on one plane: they span no volume";
  return {};
}

}  // namespace

ConvexHullOutcome ConvexHull3::Of(std::span<const Eigen::Vector3d> given) {
  // Computed on the points scaled by a power of two to a largest coordinate in [1, 2): exactly the
  // same arithmetic as on the points themselves, whatever their length unit, without squares that
  // overflow (1e200) or underflow (1e-150), nor Qhull's limits on coordinates.
  double largest = 0;
  for (const Eigen::Vector3d& p : given) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  const double scale = largest > 0 && std::isfinite(largest) ? std::ldexp(1.0, -std::ilogb(largest)) : 1.0;
  std::vector<Eigen::Vector3d> scaled(given.begin(), given.end());
  for (Eigen::Vector3d& p : scaled) p *= scale;
  const std::span<const Eigen::Vector3d> points = scaled;
  if (std::string why = WhyNoVolume(points); !why.empty()) return {std::nullopt, std::move(why)};
  std::vector<coordT> coordinates;
  coordinates.reserve(3 * points.size());
  Eigen::Vector3d lo = points[0], hi = points[0];
  for (const Eigen::Vector3d& p : points) {
    coordinates.insert(coordinates.end(), {p.x(), p.y(), p.z()});
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  MemoryFile errors;
  qhT qh_qh;
  qhT* qh = &qh_qh;
  qh_zero(qh, errors.get());
  char command[] = "qhull";  // default options: merged facets, no random perturbation (deterministic)
  const int status = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coordinates.data(), False, command, nullptr,
                                  errors.get());
  ConvexHull3 hull;
  if (status == 0) {
    facetT* facet;
    FORALLfacets {
      // Back to the points' own unit: the normals are unit vectors in both, the offsets scale
      // (exactly: a power of two).
      hull.facets_.emplace_back(facet->normal[0], facet->normal[1], facet->normal[2], facet->offset / scale);
    }
    hull.num_vertices_ = static_cast<size_t>(qh->num_vertices);
  }
  qh_freeqhull(qh, !qh_ALL);
  int still_long = 0, total_long = 0;
  qh_memfreeshort(qh, &still_long, &total_long);
  if (status != 0) return {std::nullopt, "qhull could not build the hull: " + errors.FirstLine()};
  hull.tolerance_ = 1e-9 * (hi - lo).norm() / scale;
  return {std::move(hull), {}};
}

double ConvexHull3::SignedDistance(const Eigen::Vector3d& point) const {
  // No squares here: n·p + d overflows only beyond the doubles themselves, to +inf (outside) for a
  // point far outside (1e308), never to NaN (|n| = 1).
  double farthest = -INFINITY;
  for (const Eigen::Vector4d& f : facets_) farthest = std::max(farthest, f.head<3>().dot(point) + f(3));
  return farthest;
}

bool ConvexHull3::Contains(const Eigen::Vector3d& point) const { return SignedDistance(point) <= tolerance_; }

}  // namespace vstcal
