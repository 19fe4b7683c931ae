#include "vstcal/estimators/robust_loss.h"

namespace vstcal {

std::unique_ptr<ceres::LossFunction> MakeLoss(const RefineOptions& options) {
  switch (options.loss) {
    case RefineOptions::Loss::kHuber: return std::make_unique<ceres::HuberLoss>(options.loss_scale_px);
    case RefineOptions::Loss::kCauchy: return std::make_unique<ceres::CauchyLoss>(options.loss_scale_px);
    default: return nullptr;
  }
}

}  // namespace vstcal
