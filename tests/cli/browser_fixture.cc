#include "browser_fixture.h"

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace vstcal::cli_test {

CommandResult BrowserTest::Render(const std::string& page, const std::vector<std::string>& extra) const {
  std::vector<std::string> argv = {kChromium, "--headless", "--disable-gpu", "--no-sandbox", "--no-first-run",
                                   "--user-data-dir=" + Path("chromium-profile").string(), "--enable-logging=stderr",
                                   "--v=0", "--virtual-time-budget=3000"};
  argv.insert(argv.end(), extra.begin(), extra.end());
  argv.push_back("file://" + fs::absolute(Path(page)).string());
  return RunCommand(argv, dir());
}

// A plain scan, not std::regex: that recurses once per character and overflows the stack on
// megabytes of base64.
std::vector<std::string> BrowserTest::Attributes(const std::string& html, const std::string& name) {
  std::vector<std::string> values;
  const std::string open = " " + name + "=\"";
  for (size_t at = html.find(open); at != std::string::npos; at = html.find(open, at + 1)) {
    const size_t begin = at + open.size();
    values.push_back(html.substr(begin, html.find('"', begin) - begin));
  }
  return values;
}

std::vector<std::string> BrowserTest::ConsoleLines(const std::string& log) {
  std::vector<std::string> lines;
  std::istringstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.find(":CONSOLE") != std::string::npos) lines.push_back(line);
  }
  return lines;
}

size_t BrowserTest::ExpectInlinePictures(const std::string& dom) {
  const std::vector<std::string> sources = Attributes(dom, "src");
  for (const std::string& start : sources) {
    EXPECT_TRUE(start.rfind("data:image/svg+xml;base64,", 0) == 0 || start.rfind("data:image/png;base64,", 0) == 0)
        << start.substr(0, 60);
  }
  return sources.size();
}

// Half a unit in the last digit a number is shown with ("15.82" → 0.005, "1.5e-05" → 5e-7, "12"
// → 0.5), slightly widened for the binary value the text was printed from: how far a correctly
// rounded text may lie from its value.
static double HalfLastDigit(const std::string& shown) {
  const size_t e = shown.find_first_of("eE");
  const std::string mantissa = shown.substr(0, e);
  const size_t dot = mantissa.find('.');
  const int decimals = dot == std::string::npos ? 0 : static_cast<int>(mantissa.size() - dot - 1);
  const int exponent = e == std::string::npos ? 0 : std::stoi(shown.substr(e + 1));
  return 0.5 * std::pow(10.0, exponent - decimals) * (1 + 1e-9);
}

size_t BrowserTest::ExpectNumbersOf(const Json& report, const std::string& dom) {
  const std::string marker = " data-key=\"", value_open = "\" data-value=\"";
  size_t numbers = 0;
  for (size_t at = dom.find(marker); at != std::string::npos; at = dom.find(marker, at + 1), ++numbers) {
    const size_t key_begin = at + marker.size(), key_end = dom.find('"', key_begin);
    const std::string key = dom.substr(key_begin, key_end - key_begin);
    EXPECT_EQ(dom.compare(key_end, value_open.size(), value_open), 0) << key;
    const size_t value_begin = key_end + value_open.size(), value_end = dom.find('"', value_begin);
    const std::string value = dom.substr(value_begin, value_end - value_begin);
    EXPECT_EQ(dom[value_end + 1], '>') << key;
    const std::string shown = dom.substr(value_end + 2, dom.find('<', value_end) - value_end - 2);
    const Json::json_pointer pointer(key);
    if (!report.contains(pointer) || !report.at(pointer).is_number()) {
      ADD_FAILURE() << key << " is not a number of the report";
      continue;
    }
    const double expected = report.at(pointer).get<double>();
    EXPECT_EQ(std::stod(value), expected) << key;
    EXPECT_NEAR(std::stod(shown), expected, HalfLastDigit(shown)) << key << " shown as " << shown;
  }
  return numbers;
}

// The page's policy allows no script; the copy allows inline ones and still no fetch.
BrowserTest::PageView BrowserTest::View(const std::string& page, const std::string& shot, int width, int height,
                                        const std::string& expression) const {
  PageView view;
  std::string text = ReadText(page);
  EXPECT_EQ(text.find("<script"), std::string::npos) << page << " holds a script";
  const std::string policy = "default-src 'none';";
  const size_t at = text.find(policy);
  if (at == std::string::npos) {
    ADD_FAILURE() << page << " has no Content-Security-Policy";
    return view;
  }
  text.replace(at, policy.size(), "default-src 'none'; script-src 'unsafe-inline';");
  // The body's content box: its border box less its padding (the page's margins lie outside it).
  const std::string images =
      "document.images.length + ' loaded, ' + [...document.images].filter(i => !i.complete || i.naturalWidth === 0)"
      ".length + ' broken'";
  const std::string wide =
      "(() => { const b = document.body.getBoundingClientRect(), st = getComputedStyle(document.body); "
      "const limit = Math.min(b.right - parseFloat(st.paddingRight), document.documentElement.clientWidth); "
      "const wide = [...document.querySelectorAll('table')].map(t => [t, t.getBoundingClientRect().left + "
      "t.scrollWidth]).filter(([t, right]) => right > limit + 0.5).map(([t, right]) => (t.caption ? "
      "t.caption.textContent : 'a table') + ': right edge ' + Math.round(right) + ' px, page ' + Math.round(limit) + ' px'); "
      "return wide.length ? wide.join('; ') : 'none'; })()";
  text.replace(text.rfind("</body>"), 7,
               "<script>window.addEventListener('load', () => { const b = document.body; b.setAttribute('data-images', (" +
                   images + ")); b.setAttribute('data-wide', (" + wide + ")); b.setAttribute('data-result', (" +
                   (expression.empty() ? std::string("''") : expression) + ")); });</script></body>");
  WriteText("view.html", text);

  const fs::path artifact = fs::path(VSTCAL_TOOLS_DIR).parent_path() / "test-artifacts" / shot;
  fs::create_directories(artifact.parent_path());
  const CommandResult run = Render("view.html", {"--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                                 "--screenshot=" + artifact.string(), "--dump-dom"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const std::vector<std::string> console = ConsoleLines(run.err);
  EXPECT_TRUE(console.empty()) << console.front();
  view.dom = run.out;
  const auto only = [&](const char* name) {
    const std::vector<std::string> values = Attributes(run.out, name);
    return values.size() == 1 ? values[0] : std::string("no ") + name + ": " + run.out.substr(0, 400);
  };
  view.images = only("data-images");
  view.wide_tables = only("data-wide");
  view.result = only("data-result");

  const cv::Mat png = cv::imread(artifact.string(), cv::IMREAD_GRAYSCALE);
  EXPECT_FALSE(png.empty()) << artifact;
  if (!png.empty()) {
    EXPECT_EQ(png.cols, width);
    double lo = 0, hi = 0;
    cv::minMaxLoc(png, &lo, &hi);
    EXPECT_LT(lo, 60);  // text and charts drawn, not a blank page
  }
  return view;
}

}  // namespace vstcal::cli_test
