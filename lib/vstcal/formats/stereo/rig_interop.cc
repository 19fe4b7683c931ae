#include "vstcal/formats/stereo/rig_interop.h"

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/ros_camera_info.h"
#include "vstcal/json/reader_common.h"
#include "vstcal/stereo/rectify.h"

namespace vstcal {
namespace {

void NoteUnwritten(const StereoRig& rig, std::string_view source, bool rectification, std::vector<std::string>* notes) {
  if (rig.covariance) notes->push_back(std::string(source) + ": covariance: not written: the format has no field for it");
  if (rig.fit) notes->push_back(std::string(source) + ": fit: not written: the format has no field for it");
  if (rectification && rig.rectification) {
    notes->push_back(std::string(source) + ": rectification: not written: the format has no field for it");
  }
}

}  // namespace

StereoRig RigFromKalibr(const std::vector<KalibrCamera>& cameras, const std::string& name,
                        std::vector<std::string>* notes) {
  if (cameras.size() != 2) {
    FailField(name, cameras.size() > 2 ? "cam2" : "cam1",
              "a chain of " + std::to_string(cameras.size()) + " camera" + (cameras.size() > 1 ? "s" : "") +
                  ", and a vstcal/stereo@1 rig holds two",
              cameras.size() > 2 ? "keep cam0 and cam1 in a copy of the file (delete cam2 and the cameras after it)"
                                 : "convert it to a camera (.json names camera@1), or add cam1");
  }
  StereoRig rig;
  rig.length_unit = LengthUnit::kMetre;
  rig.method = "kalibr";
  rig.left = cameras[0].camera;
  rig.right = cameras[1].camera;
  rig.left.name = "left";
  rig.right.name = "right";
  rig.right_from_left = *cameras[1].cam_from_previous;
  CheckBaseline(rig.right_from_left, name + ": cam1.T_cn_cnm1");
  for (size_t i = 0; i < 2 && notes; ++i) {
    if (!cameras[i].rostopic.empty()) {
      notes->push_back(name + ": cam" + std::to_string(i) + ".rostopic: not kept: stereo@1 has no field for it");
    }
  }
  return rig;
}

ExportedCamera KalibrCamchainText(const StereoRig& rig, std::string_view source, const Provenance& provenance) {
  std::vector<KalibrCamera> cameras(2);
  cameras[0].camera = rig.left;
  cameras[1].camera = rig.right;
  const double to_metres = MetresPer(rig.length_unit);
  cameras[1].cam_from_previous = rig.right_from_left;
  if (rig.length_unit != LengthUnit::kMetre) cameras[1].cam_from_previous->t *= to_metres;
  ExportedCamera out = KalibrCamchainText(cameras, source, provenance);
  NoteUnwritten(rig, source, true, &out.notes);
  return out;
}

std::pair<ExportedCamera, ExportedCamera> RosStereoTexts(const StereoRig& rig, std::string_view source,
                                                         const Provenance& provenance) {
  const Rectification r = rig.rectification ? *rig.rectification : Rectify(rig, {}, source);
  RosCameraInfo left, right;
  left.camera = rig.left;
  right.camera = rig.right;
  left.rectification = r.left_rect_from_left;
  right.rectification = r.right_rect_from_right;
  left.projection = r.P_left;
  right.projection = r.P_right;
  if (rig.length_unit != LengthUnit::kMetre) {
    left.projection.col(3) *= MetresPer(rig.length_unit);
    right.projection.col(3) *= MetresPer(rig.length_unit);
  }
  std::pair<ExportedCamera, ExportedCamera> out{RosCameraInfoText(left, std::string(source) + ": left", provenance),
                                                RosCameraInfoText(right, std::string(source) + ": right", provenance)};
  NoteUnwritten(rig, source, false, &out.first.notes);
  return out;
}

}  // namespace vstcal
