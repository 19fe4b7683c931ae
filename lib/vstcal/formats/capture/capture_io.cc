#include "vstcal/formats/capture/capture_io.h"

#include <cmath>

#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal {

std::string_view FinderName(ChessboardFinder finder) {
  return NameOf(kChessboardFinderNames, finder);
}

std::string_view RefinerName(CornerRefiner refiner) {
  return NameOf(kCornerRefinerNames, refiner);
}

OrderedJson CaptureToJson(const CaptureResult& result, const DetectRequest& request, const Provenance& provenance) {
  OrderedJson j = CorrespondencesToJson(result.correspondences, provenance);
  const OrderedJson provenance_json = j["provenance"];
  j.erase("provenance");
  OrderedJson capture;
  capture["target"] = request.target_file;
  capture["target_type"] = TargetTypeName(request.target.type);
  capture["detector"] = {{"finder", request.target.type == TargetType::kChessboard ? FinderName(request.detector.finder) : "-"},
                         {"refiner", RefinerName(request.detector.refiner)},
                         {"min_corners", request.detector.min_corners},
                         {"max_blur_px", request.detector.max_blur_px}};
  int found = 0, not_found = 0, rejected = 0;
  OrderedJson images = OrderedJson::array();
  for (const ImageRecord& r : result.images) {
    found += r.status == DetectionStatus::kFound;
    not_found += r.status == DetectionStatus::kNotFound;
    rejected += r.status == DetectionStatus::kRejected;
    OrderedJson image;
    image["image"] = r.image;
    image["status"] = DetectionStatusName(r.status);
    if (!r.view.empty()) image["view"] = r.view;
    if (!r.reason.empty()) image["reason"] = r.reason;
    image["corners"] = r.corners;
    image["blur_px"] = NumberOrNull(r.blur_px);
    images.push_back(std::move(image));
  }
  capture["counts"] = {{"images", result.images.size()}, {"found", found}, {"not_found", not_found}, {"rejected", rejected}};
  capture["images"] = std::move(images);
  j["capture"] = std::move(capture);
  j["provenance"] = provenance_json;
  return j;
}

}  // namespace vstcal
