// Kalibr camchain.yaml: the reader (any number of cameras) and the writer's fixed point, and a chain
// of two as a stereo rig (docs/formats.md#kalibr-camchain).
#include "harness.h"
#include "vstcal/formats/camera/kalibr_camchain.h"
#include "vstcal/formats/stereo/rig_interop.h"

VSTCAL_FUZZ_TARGET(kalibr_camchain, text) {
  using namespace vstcal;
  std::vector<std::string> notes;
  const std::vector<KalibrCamera> chain = KalibrCamchainFromText(text, "fuzz.yaml", &notes);
  fuzz::RequireFixedPoint(text, [](const std::string& s) {
    std::vector<std::string> n;
    return KalibrCamchainText(KalibrCamchainFromText(s, "fuzz.yaml", &n), "fuzz.yaml", fuzz::kProvenance).text;
  });
  if (chain.size() == 2) {
    fuzz::RequireFixedPoint(text, [](const std::string& s) {
      std::vector<std::string> n;
      const StereoRig rig = RigFromKalibr(KalibrCamchainFromText(s, "fuzz.yaml", &n), "fuzz.yaml");
      return KalibrCamchainText(rig, "fuzz.yaml", fuzz::kProvenance).text;
    });
  }
}
