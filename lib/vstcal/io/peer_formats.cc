#include "vstcal/io/peer_formats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/json/reader_common.h"

namespace vstcal::io {

void RefuseSkew(const Camera& camera, std::string_view source, std::string_view peer) {
  const Eigen::Matrix3d K = camera.K();
  const double s = K(0, 1);
  if (s == 0) return;
  // u moves by s·y_d, and y_d = (v − cy)/fy exactly: the largest move is at the top or bottom row.
  const double rows = std::max(std::abs(-0.5 - K(1, 2)), std::abs(camera.image_size.height - 0.5 - K(1, 2)));
  const double shift = std::abs(s) * rows / K(1, 1);
  throw InputError(std::string(source) + ": K[0][1]: the camera has skew " + MessageNumber(s) + " px, and " +
                   std::string(peer) + " has no skew term: written without it, pixels would move by up to " +
                   MessageNumber(shift) +
                   " px; solve the camera without skew, or set K[0][1] to 0 (and delete \"intrinsics\") "
                   "in a copy if that error is acceptable");
}

void NoteUnwrittenName(const CalibratedCamera& camera, std::string_view source, std::vector<std::string>* notes) {
  if (camera.name.empty()) return;
  notes->push_back(std::string(source) + ": camera: the name \"" + camera.name +
                   "\" is not written: the format has no field for it");
}

std::string ProvenanceComment(const Provenance& provenance) {
  return "vstcal provenance: " + ProvenanceToJson(provenance).dump();
}

}  // namespace vstcal::io
