#include "vstcal/formats/camera/peer_formats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {

void NoteUnwrittenName(const CalibratedCamera& camera, std::string_view source, std::vector<std::string>* notes) {
  if (camera.name.empty()) return;
  notes->push_back(std::string(source) + ": camera: the name \"" + camera.name +
                   "\" is not written: the format has no field for it");
}

std::string ProvenanceComment(const Provenance& provenance) {
  return "vstcal provenance: " + ProvenanceToJson(provenance).dump();
}

}  // namespace vstcal
