// reproj-report --html as a person sees it: the page rendered by headless Chromium (Debian's
// chromium) with no console message at all (a fetch the page's Content-Security-Policy blocks is
// one), every image loaded by the browser itself, a screenshot saved, and every number in the page
// read back from the rendered DOM and compared with the JSON report written by the same run.
#include <opencv2/imgcodecs.hpp>

#include "cli_fixture.h"

namespace vstcal::cli_test {
namespace {

constexpr const char* kChromium = "/usr/bin/chromium";

class CliReprojReportHtml : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    Synth("in/volume.json", Override(Remove(DefaultSynthArgs(), "--no-test-points", false), "--noise", "0.5"));
  }

  // Chromium's DOM of a page after its load event, and its log on stderr.
  CommandResult Render(const std::string& page, const std::vector<std::string>& extra = {}) const {
    std::vector<std::string> argv = {kChromium, "--headless", "--disable-gpu", "--no-sandbox", "--no-first-run",
                                     "--user-data-dir=" + Path("chromium-profile").string(), "--enable-logging=stderr",
                                     "--v=0", "--virtual-time-budget=3000"};
    argv.insert(argv.end(), extra.begin(), extra.end());
    argv.push_back("file://" + fs::absolute(Path(page)).string());
    return RunCommand(argv, dir());
  }

  // The value of attribute `name` of every element that has one, in document order (std::regex
  // recurses once per character and overflows the stack on megabytes of base64).
  static std::vector<std::string> Attributes(const std::string& html, const std::string& name) {
    std::vector<std::string> values;
    const std::string open = " " + name + "=\"";
    for (size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
      const size_t begin = at + open.size();
      values.push_back(html.substr(begin, html.find('"', begin) - begin));
    }
    return values;
  }

  static std::vector<std::string> ConsoleLines(const std::string& log) {
    std::vector<std::string> lines;
    std::istringstream in(log);
    for (std::string line; std::getline(in, line);) {
      if (line.find(":CONSOLE") != std::string::npos) lines.push_back(line);
    }
    return lines;
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
  // Every picture is inline: a fetch would need a src that is not a data: URI.
  const std::vector<std::string> sources = Attributes(dom.out, "src");
  for (const std::string& start : sources) {
    EXPECT_TRUE(start.rfind("data:image/svg+xml;base64,", 0) == 0 || start.rfind("data:image/png;base64,", 0) == 0)
        << start.substr(0, 60);
  }
  // Histogram, per view, depth, test points; a heat map and an overlay per camera; the refined
  // camera's projection uncertainty.
  EXPECT_EQ(sources.size(), 4u + 2 * 2 + 1);

  // 2. Every number shown is the JSON's: the exact value it carries, and the text shown rounds it.
  const std::string marker = " data-key=\"";
  size_t numbers = 0;
  for (size_t at = dom.out.find(marker); at != std::string::npos; at = dom.out.find(marker, at + 1), ++numbers) {
    const size_t key_begin = at + marker.size(), key_end = dom.out.find('"', key_begin);
    const std::string key = dom.out.substr(key_begin, key_end - key_begin);
    const std::string value_open = "\" data-value=\"";
    ASSERT_EQ(dom.out.compare(key_end, value_open.size(), value_open), 0) << key;
    const size_t value_begin = key_end + value_open.size(), value_end = dom.out.find('"', value_begin);
    const std::string value = dom.out.substr(value_begin, value_end - value_begin);
    ASSERT_EQ(dom.out[value_end + 1], '>') << key;
    const std::string shown = dom.out.substr(value_end + 2, dom.out.find('<', value_end) - value_end - 2);
    const Json& expected = report.at(Json::json_pointer(key));
    ASSERT_TRUE(expected.is_number()) << key;
    EXPECT_EQ(std::stod(value), expected.get<double>()) << key;
    EXPECT_NEAR(std::stod(shown), expected.get<double>(), 5.001e-4) << key << " shown as " << shown;
  }
  EXPECT_GT(numbers, 150u);  // overall, views, test points, differences of two cameras

  // 3. The browser decodes every image: the same page with a check appended (the copy's policy
  // allows that one inline script and still no fetch), reporting into the DOM.
  std::string page = ReadText("out/report.html");
  const std::string policy = "default-src 'none';";
  ASSERT_NE(page.find(policy), std::string::npos);
  page.replace(page.find(policy), policy.size(), "default-src 'none'; script-src 'unsafe-inline';");
  page.replace(page.rfind("</body>"), 7,
               "<script>window.addEventListener('load', () => { const bad = [...document.images].filter(i => "
               "!i.complete || i.naturalWidth === 0).length; document.body.setAttribute('data-images', "
               "document.images.length + ' loaded, ' + bad + ' broken'); });</script></body>");
  WriteText("check.html", page);
  const CommandResult checked = Render("check.html", {"--dump-dom"});
  EXPECT_NE(checked.out.find("data-images=\"9 loaded, 0 broken\""), std::string::npos) << checked.out.substr(0, 400);
  EXPECT_TRUE(ConsoleLines(checked.err).empty()) << ConsoleLines(checked.err).front();

  // 4. A screenshot, kept in the build tree for a person to look at.
  const fs::path shot = fs::path(VSTCAL_TOOLS_DIR).parent_path() / "test-artifacts" / "reproj-report.png";
  fs::create_directories(shot.parent_path());
  const CommandResult screenshot = Render("out/report.html", {"--window-size=1000,2400", "--screenshot=" + shot.string()});
  ASSERT_EQ(screenshot.exit_code, 0) << screenshot.err;
  const cv::Mat png = cv::imread(shot.string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(png.empty());
  EXPECT_EQ(png.cols, 1000);
  double lo = 0, hi = 0;
  cv::minMaxLoc(png, &lo, &hi);
  EXPECT_LT(lo, 60);  // text and charts drawn, not a blank page
}

TEST_F(CliReprojReportHtml, SameInputsGiveTheSameBytes) {
  // Report and page twice from the same inputs and arguments: bit-identical (no time stamp, Qhull
  // without random perturbation, gnuplot and PNG output deterministic).
  const std::vector<std::string> args = {"in/volume.truth.json", "in/volume.json", "-o", "out/r.json", "--html", "out/r.html"};
  ASSERT_EQ(Run("reproj-report", args).exit_code, kOk);
  const std::string json = ReadText("out/r.json"), html = ReadText("out/r.html");
  fs::remove(Path("out/r.json"));
  fs::remove(Path("out/r.html"));
  ASSERT_EQ(Run("reproj-report", args).exit_code, kOk);
  EXPECT_TRUE(ReadText("out/r.json") == json);
  EXPECT_TRUE(ReadText("out/r.html") == html);
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
