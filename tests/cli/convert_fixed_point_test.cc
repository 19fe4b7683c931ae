// Round trips are fixed points (docs/reliability.md#round-trips): a camera converted to its own
// format gives a file that, converted once more, is the same bytes — for the cameras every tool
// writes (calib-synth's truth, calib-dlt's own P, calib-tsai's with covariance and views) in each
// format. R and P used to move in their last bits on every pass of a camera@1 file.
#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

class CliConvertFixedPoint : public CliTest {
 protected:
  // One pass: in/pass.EXT → out/pass.EXT, always with the same arguments (so that the provenance
  // is the same); returns the output's text and moves it to in/ for the next pass.
  std::string Pass(const std::string& ext) {
    const CommandResult r = Run("calib-convert", {"in/pass." + ext, "-o", "out/pass." + ext});
    EXPECT_EQ(r.exit_code, kOk) << r.err;
    const std::string text = ReadText("out/pass." + ext);
    fs::rename(Path("out/pass." + ext), Path("in/pass." + ext));
    return text;
  }
};

TEST_F(CliConvertFixedPoint, ConvertedAgainIsTheSameBytes) {
  Synth("in/volume.json", Override(DefaultSynthArgs(), "--noise", "0.3"));
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "-o", "in/dlt.json"}).exit_code, kOk);
  ASSERT_EQ(Run("calib-tsai", {"in/volume.json", "-o", "in/tsai.json", "--distortion", "k1"}).exit_code, kOk);
  Synth("in/views.json", {"--rig", "planar-views", "--image-size", "640x480", "--fx", "500", "--views", "4",
                          "--grid", "6x5", "--spacing", "30", "--distance", "400", "--noise", "0.2"});
  ASSERT_EQ(Run("calib-tsai", {"in/views.json", "-o", "in/views-tsai.json"}).exit_code, kOk);

  for (const std::string camera : {"volume.truth", "dlt", "tsai", "views-tsai"}) {
    for (const std::string ext : {"json", "yaml", "cameramodel"}) {
      if (ext == "yaml" && camera == "dlt") continue;  // the DLT's skew: OpenCV has none (refused, tested elsewhere)
      if (ext == "cameramodel" && camera == "dlt") continue;
      // The camera in the format, as calib-convert writes it from camera@1.
      const CommandResult first = Run("calib-convert", {"in/" + camera + ".json", "-o", "in/pass." + ext});
      ASSERT_EQ(first.exit_code, kOk) << camera << " " << ext << ": " << first.err;
      const std::string once = Pass(ext);
      EXPECT_EQ(Pass(ext), once) << camera << " → " << ext << ": the second pass changed the file";
    }
  }
}

}  // namespace
}  // namespace vstcal::cli_test
