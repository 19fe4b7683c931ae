#include "vstcal/formats/stereo/stereo_peer_formats.h"

#include <opencv2/core.hpp>

#include "vstcal/camera/opencv_mat.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/scene/epipolar.h"

namespace vstcal {
namespace {

cv::Mat Roi(const std::array<int, 4>& roi) { return (cv::Mat_<int>(1, 4) << roi[0], roi[1], roi[2], roi[3]); }

// What neither peer's files hold.
void NotePeerUnwritten(const StereoRig& rig, std::string_view source, std::vector<std::string>* notes) {
  if (rig.covariance) notes->push_back(std::string(source) + ": covariance: not written: the format has no field for it");
  if (rig.fit) notes->push_back(std::string(source) + ": fit: not written: the format has no field for it");
}

}  // namespace

ExportedCamera OpenCvStereoYamlText(const StereoRig& rig, std::string_view source, const Provenance& provenance) {
  const ImageSize size = rig.left.camera.image_size;
  if (!(rig.right.camera.image_size == size)) {
    throw InputError(std::string(source) + ": right.image_size: differs from the left camera's (" +
                     std::to_string(size.width) + "×" + std::to_string(size.height) +
                     "); OpenCV's stereo functions take one image size for both cameras: export each camera with "
                     "calib-convert instead");
  }
  RefuseSkew(rig.left.camera, std::string(source) + ": left", "OpenCV");
  RefuseSkew(rig.right.camera, std::string(source) + ": right", "OpenCV");
  // M1, D1, M2, D2 are calibrateCamera's and stereoCalibrate's; cv::fisheye::stereoCalibrate's
  // file has no agreed layout.
  for (const auto& [camera, side] : {std::pair{&rig.left.camera, ": left"}, std::pair{&rig.right.camera, ": right"}}) {
    RefuseNonOpenCvModel(*camera, std::string(source) + side, "OpenCV's stereo YAML (M1, D1, M2, D2 are plumb-bob)",
                         "write each camera as OpenCV YAML (distortion_model: fisheye)");
  }
  cv::FileStorage fs(".yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  fs.writeComment(ProvenanceComment(provenance));
  fs.writeComment("right_from_left: x_right = R x_left + T, T in " + std::string(LengthUnitName(rig.length_unit)));
  fs << "image_width" << size.width << "image_height" << size.height;
  fs << "M1" << ToCvMat(rig.left.camera.K()) << "D1" << OpenCvDistortionMat(rig.left.camera);
  fs << "M2" << ToCvMat(rig.right.camera.K()) << "D2" << OpenCvDistortionMat(rig.right.camera);
  fs << "R" << ToCvMat(rig.right_from_left.R) << "T" << ToCvMat(rig.right_from_left.t);
  fs << "E" << ToCvMat(EssentialMatrix(rig.right_from_left)) << "F" << ToCvMat(FundamentalMatrix(rig));
  if (const auto& r = rig.rectification) {
    fs << "R1" << ToCvMat(r->left_rect_from_left) << "R2" << ToCvMat(r->right_rect_from_right);
    fs << "P1" << ToCvMat(r->P_left) << "P2" << ToCvMat(r->P_right) << "Q" << ToCvMat(r->Q);
    fs << "validRoi1" << Roi(r->valid_roi_left) << "validRoi2" << Roi(r->valid_roi_right);
  }
  ExportedCamera out;
  out.text = fs.releaseAndGetString();
  NotePeerUnwritten(rig, source, &out.notes);
  return out;
}

std::pair<ExportedCamera, ExportedCamera> MrcalStereoTexts(const StereoRig& rig, std::string_view source,
                                                          const MrcalWriteOptions& options, const Provenance& provenance) {
  // The left camera is mrcal's reference (all-zero extrinsics); the right one's rt_cam_ref is
  // right_from_left. The names "left" and "right" have no field there: the file names say it.
  CalibratedCamera left = rig.left, right = rig.right;
  left.name.clear();
  right.name.clear();
  left.camera_from_world.reset();
  right.camera_from_world = rig.right_from_left;
  std::pair<ExportedCamera, ExportedCamera> out{MrcalCameramodelText(left, std::string(source) + ": left", options, provenance),
                                                MrcalCameramodelText(right, std::string(source) + ": right", options, provenance)};
  NotePeerUnwritten(rig, source, &out.first.notes);
  return out;
}

}  // namespace vstcal
