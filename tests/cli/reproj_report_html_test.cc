// reproj-report --html as a person sees it: the page rendered by headless Chromium (Debian's
// chromium) with no console message at all (a fetch the page's Content-Security-Policy blocks is
// one), every image loaded by the browser itself, a screenshot saved, and every number in the page
// read back from the rendered DOM and compared with the JSON report written by the same run.
#include <opencv2/imgcodecs.hpp>

#include "browser_fixture.h"

namespace vstcal::cli_test {
namespace {

class CliReprojReportHtml : public BrowserTest {
 protected:
  void SetUp() override {
    BrowserTest::SetUp();
    Synth("in/volume.json", Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--noise", "0.5"));
  }
};

TEST_F(CliReprojReportHtml, RendersOfflineWithEveryImageAndTheJsonsNumbers) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  ASSERT_EQ(Run("calib-dlt", {"in/volume.json", "--refine", "-o", "in/cam.json", "-q"}).exit_code, kOk);
  const CommandResult r = Run("reproj-report", {"in/cam.json", "in/volume.truth.json", "in/volume.json", "-o",
                                                "out/report.json", "--html", "out/report.html"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/report.json");

  // 1. The page as written: no console message (a blocked fetch, a script error) while it loads.
  const CommandResult dom = Render("out/report.html", {"--dump-dom"});
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  EXPECT_TRUE(ConsoleLines(dom.err).empty()) << ConsoleLines(dom.err).front();
  // Histogram, per view, depth, test points; a heat map and an overlay per camera; the refined
  // camera's projection uncertainty.
  EXPECT_EQ(ExpectInlinePictures(dom.out), 4u + 2 * 2 + 1);

  // 2. Every number shown is the JSON's: the exact value it carries, and the text shown rounds it.
  EXPECT_GT(ExpectNumbersOf(report, dom.out), 150u);  // overall, views, test points, differences of two cameras

  // 3. The browser decodes every image.
  EXPECT_EQ(ImagesLoaded("out/report.html"), "9 loaded, 0 broken");

  // 4. A screenshot, kept in the build tree for a person to look at.
  EXPECT_EQ(TablesWiderThanThePage("out/report.html", 1000), "none");
  ExpectScreenshot("out/report.html", "reproj-report.png", 1000, 2400);
}

TEST_F(CliReprojReportHtml, SameInputsGiveTheSameBytes) {
  // Report and page twice from the same inputs and arguments: bit-identical (no time stamp, Qhull
  // without random perturbation, gnuplot and PNG output deterministic).
  EXPECT_TRUE(SameBytesTwice("reproj-report", {"in/volume.truth.json", "in/volume.json", "-o", "out/r.json", "--html", "out/r.html"},
                             {"out/r.json", "out/r.html"}));
}

TEST_F(CliReprojReportHtml, OverlayOnTheNamedImage) {
  // A view that names its image: the overlay is drawn on it (a grey 640×480 picture here).
  Json corr = ReadJson("in/volume.json");
  corr["views"][1]["image"] = "views/plane-01.png";
  WriteJson("in/named.json", corr);
  fs::create_directories(Path("in/views"));
  ASSERT_TRUE(cv::imwrite(Path("in/views/plane-01.png").string(), cv::Mat(480, 640, CV_8UC1, cv::Scalar(90))));
  const CommandResult r = Run("reproj-report", {"in/volume.truth.json", "in/named.json", "-o", "out/r.json", "--html", "out/r.html"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  EXPECT_NE(ReadText("out/r.html").find("view plane-01 on its image views/plane-01.png; 20 residuals"), std::string::npos);
  EXPECT_EQ(ReadJson("out/r.json")["correspondences"]["images"][1], "views/plane-01.png");
}

TEST_F(CliReprojReportHtml, NamedImageMissingNotAnImageOrOfAnotherSize) {
  Json corr = ReadJson("in/volume.json");
  corr["views"][0]["image"] = "views/missing.png";
  WriteJson("in/missing.json", corr);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/volume.truth.json", "in/missing.json", "-o", "out/r.json", "--html", "out/r.html"}),
                        "reproj-report", kBadInput, "in/missing.json: views[0].image: ", {"not found", "blank canvas"}));
  EXPECT_TRUE(OutDirEmpty());  // not even the JSON report
  fs::create_directories(Path("in/views"));
  ASSERT_TRUE(cv::imwrite(Path("in/views/small.png").string(), cv::Mat(240, 320, CV_8UC1, cv::Scalar(90))));
  corr["views"][0]["image"] = "views/small.png";
  WriteJson("in/small.json", corr);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/volume.truth.json", "in/small.json", "-o", "out/r.json", "--html", "out/r.html"}),
                        "reproj-report", kBadInput, "in/small.json: views[0].image: ", {"is 320x240 px but image_size is 640x480"}));
  EXPECT_TRUE(OutDirEmpty());
  WriteText("in/views/text.png", "not a picture\n");
  corr["views"][0]["image"] = "views/text.png";
  WriteJson("in/text.json", corr);
  EXPECT_TRUE(FailsWith(Run("reproj-report", {"in/volume.truth.json", "in/text.json", "-o", "out/r.json", "--html", "out/r.html"}),
                        "reproj-report", kBadInput, "in/text.json: views[0].image: ", {"not an image", "give a PNG or JPEG"}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
