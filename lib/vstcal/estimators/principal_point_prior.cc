#include "vstcal/estimators/principal_point_prior.h"

#include <algorithm>
#include <cmath>

namespace vstcal {

double PrincipalPointPriorSigmaPx(const ImageSize& size, double sigma_fraction) {
  return sigma_fraction * std::hypot(size.width, size.height);
}

void AddPrincipalPointPrior(const Eigen::Vector2d& at, double sigma_px, const std::string& because, RefineOptions* options) {
  options->priors.push_back({"cx", at.x(), sigma_px, because});
  options->priors.push_back({"cy", at.y(), sigma_px, because});
}

bool PlacesPrincipalPoint(const RefineOptions& options) {
  return !options.free_principal_point ||
         std::any_of(options.priors.begin(), options.priors.end(),
                     [](const IntrinsicPrior& p) { return p.parameter == "cx" || p.parameter == "cy"; });
}

}  // namespace vstcal
