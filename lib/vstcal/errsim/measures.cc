#include "vstcal/errsim/measures.h"

namespace vstcal {

ErrorOutputs::ErrorOutputs(const ChainModel& model, OutputSet set) : set_(set) {
  const std::vector<std::string> measures =
      set == OutputSet::kFull ? std::vector<std::string>{"linear", "lateral", "depth", "depth_abs", "angular_deg"}
                              : std::vector<std::string>{"linear"};
  for (size_t k = 0; k < model.geometry.test_points.size(); ++k) {
    const ChainTestPoint& tp = model.geometry.test_points[k];
    offsets_.push_back(names_.size());
    occlusion_.push_back(tp.surface_behind.has_value());
    auto add = [&](const std::string& name, bool percentiles) {
      names_.push_back(tp.name + "." + name);
      point_of_.push_back(k);
      percentiles_.push_back(set == OutputSet::kFull && percentiles);
    };
    for (const std::string_view eye : kEyeNames) add("image." + std::string(eye) + ".pixel_px", true);
    for (const std::string measure : {"misregistration", "misperception"}) {
      for (const std::string& m : measures) add(measure + "." + m, m == "linear");
    }
    if (tp.surface_behind) {
      for (const std::string_view eye : kEyeNames) add("occlusion." + std::string(eye) + ".wrong", false);
    }
  }
}

}  // namespace vstcal
