// OpenCV FileStorage YAML: the reader (cv::FileStorage behind a nesting check) and the writer's
// fixed point (docs/formats.md#opencv-yaml).
#include "harness.h"
#include "vstcal/formats/camera/opencv_yaml.h"

VSTCAL_FUZZ_TARGET(opencv_yaml, text) {
  using namespace vstcal;
  OpenCvYamlFromText(text, "fuzz.yaml", LengthUnit::kMillimetre);
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    const ImportedCamera in = OpenCvYamlFromText(s, "fuzz.yaml", LengthUnit::kMillimetre);
    return OpenCvYamlText(in.camera, "fuzz.yaml", fuzz::kProvenance).text;
  });
}
