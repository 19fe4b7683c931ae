// mrcal .cameramodel: the Python-literal parser, the reader and the writer's fixed point
// (docs/formats.md#mrcal).
#include "harness.h"
#include "vstcal/io/mrcal_cameramodel.h"

VSTCAL_FUZZ_TARGET(text) {
  using namespace vstcal;
  io::MrcalCameramodelFromText(text, "fuzz.cameramodel", std::nullopt);
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    const io::ImportedCamera in = io::MrcalCameramodelFromText(s, "fuzz.cameramodel", std::nullopt);
    return io::MrcalCameramodelText(in.camera, "fuzz.cameramodel", {std::nullopt, std::nullopt, in.rotation_vector},
                                    fuzz::kProvenance)
        .text;
  });
}
