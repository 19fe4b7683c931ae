// mrcal .cameramodel: the Python-literal parser, the reader and the writer's fixed point
// (docs/formats.md#mrcal).
#include "harness.h"
#include "vstcal/formats/camera/mrcal_cameramodel.h"

VSTCAL_FUZZ_TARGET(cameramodel, text) {
  using namespace vstcal;
  MrcalCameramodelFromText(text, "fuzz.cameramodel", std::nullopt);
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    const ImportedCamera in = MrcalCameramodelFromText(s, "fuzz.cameramodel", std::nullopt);
    return MrcalCameramodelText(in.camera, "fuzz.cameramodel", {std::nullopt, std::nullopt, in.rotation_vector},
                                    fuzz::kProvenance)
        .text;
  });
}
