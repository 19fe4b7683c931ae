// What the readers and writers of other tools' camera files (OpenCV FileStorage YAML, mrcal
// .cameramodel) share: their results, the refusal of skew, and the provenance comment.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// A camera read from another tool's file. `notes` say what was assumed or kept although the
// other tool treats it differently; tools print them, they are not errors.
struct ImportedCamera {
  CalibratedCamera camera;  // method names the source: "opencv", "mrcal"
  std::vector<std::string> notes;
  // The pose's rotation as the file wrote it (a .cameramodel's rotation vector), for writing it
  // back bit for bit (MrcalWriteOptions::rotation_vector).
  std::optional<Eigen::Vector3d> rotation_vector;
};

// A camera written for another tool. `notes` say what the format could not hold.
struct ExportedCamera {
  std::string text;
  std::vector<std::string> notes;
};

// Neither OpenCV's nor mrcal's file has a field for the camera's name ("left"): when there is
// one, a note says it is not written.
void NoteUnwrittenName(const CalibratedCamera& camera, std::string_view source, std::vector<std::string>* notes);

// "vstcal provenance: {...}" on one line (compact JSON, so that a newline in an argument stays
// escaped), for a comment at the top of a file that has no field for it.
std::string ProvenanceComment(const Provenance& provenance);

}  // namespace vstcal
