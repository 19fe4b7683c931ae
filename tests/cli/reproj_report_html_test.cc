// reproj-report --html as a person sees it: the page rendered by headless Chromium (Debian's
// chromium) with no console message at all (a fetch the page's Content-Security-Policy blocks is
// one), every image loaded by the browser itself, a screenshot saved, and every number in the page
// read back from the rendered DOM and compared with the JSON report written by the same run.
#include <opencv2/imgcodecs.hpp>

#include <algorithm>

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

  // 1. The page, loaded once (View): no script of its own and no console message (a blocked fetch,
  // a script error) while it loads. Residual vectors on every view (issue 24): one plot per view and
  // camera, in the views table's order (the largest RMS first, from the JSON here), each laid out on
  // the page with its dots and one vector per measured point drawn (the SVG paths' subpaths, and a
  // bounding box that is not empty: the browser drew them). A screenshot is kept in the build tree
  // for a person to look at.
  const PageView view = View(
      "out/report.html", "reproj-report.png", 1000, 2400,
      "[...document.querySelectorAll('div.small-multiples')].map(d => d.dataset.camera + ':' + "
      "[...d.querySelectorAll('figure.view-residuals')].map(f => { const r = f.querySelector('svg').getBoundingClientRect(); "
      "const vectors = [...f.querySelectorAll('path.vectors')]; const dots = f.querySelector('path.points'); "
      "const subpaths = vectors.reduce((n, p) => n + (p.getAttribute('d').match(/M/g) || []).length, 0); "
      "const drawn = r.width > 100 && r.height > 50 && dots.getBBox().width > 0 && vectors.every(p => p.getBBox().width + p.getBBox().height > 0) && "
      "subpaths == f.dataset.drawn && (dots.getAttribute('d').match(/M/g) || []).length == f.dataset.drawn; "
      "return f.dataset.view + (drawn ? '' : ' NOT DRAWN') + ' ' + f.dataset.drawn; }).join(',')).join(';')");
  const std::string& dom = view.dom;
  // Histogram, per view, depth, test points; a heat map and an overlay per camera; the refined
  // camera's projection uncertainty.
  EXPECT_EQ(ExpectInlinePictures(dom), 4u + 2 * 2 + 1);

  // 2. Every number shown is the JSON's: the exact value it carries, and the text shown rounds it.
  EXPECT_GT(ExpectNumbersOf(report, dom), 150u);  // overall, views, test points, differences of two cameras

  // 3. The browser decodes every image.
  EXPECT_EQ(view.images, "9 loaded, 0 broken");

  // 4. The residual plots, as the browser laid them out (the expression given to View).
  std::string expected;
  for (size_t k = 0; k < report["cameras"].size(); ++k) {
    const Json& views = report["cameras"][k]["views"];
    std::vector<size_t> order(views.size());
    for (size_t v = 0; v < order.size(); ++v) order[v] = v;
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
      return views[a]["error_px"]["rms"].get<double>() > views[b]["error_px"]["rms"].get<double>();
    });
    expected += (k ? ";" : "") + std::to_string(k) + ":";
    for (size_t i = 0; i < order.size(); ++i) {
      expected += (i ? "," : "") + views[order[i]]["name"].get<std::string>() + " " + std::to_string(views[order[i]]["error_px"]["n"].get<size_t>());
    }
  }
  EXPECT_EQ(view.result, expected);
  EXPECT_EQ(report["cameras"][0]["views"].size(), 3u);  // three planes: three plots a camera

  // 5. Every table fits the page's column in a 1000 px window.
  EXPECT_EQ(view.wide_tables, "none");
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
