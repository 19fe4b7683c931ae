#include "vstcal/errsim/holloway.h"

namespace vstcal::errsim {

ErrorOutputs::ErrorOutputs(const ChainModel& model) {
  for (const TestPoint& tp : model.geometry.test_points) {
    offsets_.push_back(names_.size());
    occlusion_.push_back(tp.surface_behind.has_value());
    for (const char* name : {".left.pixel_px", ".left.angular_deg", ".right.pixel_px", ".right.angular_deg", ".linear",
                             ".lateral", ".depth", ".depth_abs", ".angular_deg"}) {
      names_.push_back(tp.name + name);
    }
    if (tp.surface_behind) {
      names_.push_back(tp.name + ".left.wrong_occlusion");
      names_.push_back(tp.name + ".right.wrong_occlusion");
    }
  }
}

}  // namespace vstcal::errsim
