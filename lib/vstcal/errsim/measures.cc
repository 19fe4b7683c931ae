#include "vstcal/errsim/measures.h"

namespace vstcal {

ErrorOutputs::ErrorOutputs(const ChainModel& model, OutputSet set) : set_(set) {
  for (const MeasureDecl& d : kMeasures) {
    for (int e = 0; e < kNumEyes; ++e) slot_[static_cast<int>(d.measure)][e] = MeasureOffset(set, d.measure, e);
  }
  for (size_t k = 0; k < model.geometry.test_points.size(); ++k) {
    const ChainTestPoint& tp = model.geometry.test_points[k];
    const bool surface = tp.surface_behind.has_value();
    offsets_.push_back(names_.size());
    surface_.push_back(surface);
    for (const MeasureDecl& d : kMeasures) {
      if (!InSet(d, set) || (d.needs_surface && !surface)) continue;
      for (int e = 0; e < SlotsOf(d.scope); ++e) {
        // Built by appending: GCC 12's -Wrestrict misfires on std::string + "literal".
        names_.push_back(std::string(tp.name).append(".").append(MeasureName(d.measure, e)));
        point_of_.push_back(k);
        headline_.push_back(set == OutputSet::kFull && d.headline);
      }
    }
    VSTCAL_CHECK(names_.size() - offsets_.back() == static_cast<size_t>(PointMeasures(set, surface)),
                 "a test point's outputs follow kMeasures");
  }
}

}  // namespace vstcal
