// The report page's building blocks: base64 against RFC 4648's test vectors, gnuplot string
// quoting that no name can break out of; err-sim's page of undefined statistics.
#include <gtest/gtest.h>

#include "vstcal/core/error.h"
#include "vstcal/pages/errsim_html.h"
#include "vstcal/pages/gnuplot.h"
#include "vstcal/pages/html.h"
#include "vstcal/pages/html_page.h"
#include "vstcal/pages/view_residuals.h"

#include <regex>

namespace vstcal {
namespace {

TEST(Base64, Rfc4648TestVectors) {  // RFC 4648 §10
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  const unsigned char high[] = {0xfb, 0xff, 0xfe};
  EXPECT_EQ(Base64(high, 3), "+//+");
}

TEST(GnuplotQuoted, NamesCannotEndTheStringOrTheLine) {
  EXPECT_EQ(GnuplotQuoted("plane-00"), "\"plane-00\"");
  EXPECT_EQ(GnuplotQuoted("a\"; system(\"rm\")"), "\"a\\\"; system(\\\"rm\\\")\"");
  EXPECT_EQ(GnuplotQuoted("back\\slash"), "\"back\\\\slash\"");
  EXPECT_EQ(GnuplotQuoted("two\nlines"), "\"two lines\"");
}

TEST(RunGnuplot, DrawsAnSvgAndReportsItsErrors) {
  const std::string svg = RunGnuplot("set terminal svg size 200,100\nset output\n$d << EOD\n0 0\n1 1\nEOD\nplot $d with lines notitle\n");
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  try {
    RunGnuplot("set terminal svg\nset output\nplot nosuchfunction(x)\n");
    FAIL() << "gnuplot's error was not reported";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot failed: "), std::string::npos) << e.what();
  }
}

// The per-view residual plots stay bounded (issue 24): 60 views of 600 points give the 48 views of
// largest RMS (view 59 first: its RMS is the largest), each with one point in ⌈600 / 250⌉ = 3, i.e.
// 200 vectors, and the cuts said; the whole under 48 × 200 × 60 bytes.
TEST(ViewResidualPlots, WorstFirstCappedAndDecimated) {
  ReprojReport r;
  r.correspondences.image_size = {640, 480};
  CameraReport cam;
  cam.overall.error_px = ErrorStats{36000, 1, 1, 1, 1, 1};
  for (int v = 0; v < 60; ++v) {
    ViewReport view;
    view.name = "v" + std::to_string(v);
    for (int p = 0; p < 600; ++p) {
      PointError e;
      e.measured = Eigen::Vector2d(10 + p % 600, 20 + v);
      e.predicted = e.measured + Eigen::Vector2d(0.6, 0.8);
      e.error_px = 1;
      view.points.push_back(e);
    }
    view.error_px = ErrorStats{600, 1, 0.5 + v / 100.0, 1, 1, 1};
    cam.views.push_back(view);
  }
  r.cameras.push_back(cam);
  const std::string html = ViewResidualPlots(r, 0);
  const std::regex figure("<figure class=\"view-residuals\" data-view=\"(v[0-9]+)\" data-drawn=\"([0-9]+)\"");
  std::vector<std::string> names;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), figure); it != std::sregex_iterator(); ++it) {
    names.push_back((*it)[1]);
    EXPECT_EQ((*it)[2], "200");
  }
  ASSERT_EQ(names.size(), kMaxViewPlots);
  EXPECT_EQ(names.front(), "v59");
  EXPECT_EQ(names.back(), "v12");  // 59 … 12: the 48 largest
  EXPECT_NE(html.find("The 48 largest-RMS views of 60 are drawn"), std::string::npos);
  EXPECT_NE(html.find("(one point in 3)"), std::string::npos);
  EXPECT_LT(html.size(), 48u * 200 * 60);
  // A vector is the residual times the overlay's scale: 2 % of the 800 px diagonal over p95 = 1 px
  // is 16, rounded down to 10: (0.6, 0.8) px → l6.0 8.0.
  EXPECT_NE(html.find("M10.5 79.5l6.0 8.0"), std::string::npos);
}

TEST(ErrSimReportHtml, UndefinedStatisticsAndNoBudgetAreDashesNotNumbers) {
  // A report as err-sim writes it for a test point whose right eye has no defined sample, without
  // a budget (--no-budget): nulls are shown as dashes, never as a number, and no chart fails.
  const OrderedJson stats = {{"mean", 2.0}, {"rms", 2.5}, {"standard_deviation", 1.5}, {"mean_standard_error", 0.1},
                                 {"max", 9.0},  {"p50", 1.75}, {"p95", 5.0}, {"p99", 8.0}};
  OrderedJson point = {{"name", "a<b"}, {"undefined", {{"samples", 10}, {"rate", 0.5}}}};
  point["image"] = {{"left", {{"pixel_px", stats}}}, {"right", {{"pixel_px", nullptr}}}};
  point["misregistration"] = {{"linear", stats}};
  point["misperception"] = {{"systematic", {{"linear", 3.0}}}, {"linear", nullptr}};
  const OrderedJson report = {
      {"format", "vstcal/err-sim-report@3"}, {"chain", "c.json"}, {"length_unit", "mm"}, {"samples", 20}, {"seed", 1},
      {"sources", {{"active", {"tracking"}}}}, {"undefined_samples", 10},
      {"test_points", {point}},
      {"totals", {{"image_rms_px", 2.5}, {"misregistration_rms", 2.5}, {"misperception_rms", nullptr},
                  {"wrong_occlusion_rate", nullptr}, {"systematic_misperception_rms", 3.0}}},
      {"budget", nullptr}};
  const std::string page = ErrSimHtml(report);
  EXPECT_NE(page.find("Not computed: the run was asked for no budget"), std::string::npos);
  // Two charts drawn; the misperception, of no defined value, said so instead.
  EXPECT_NE(page.find("misperception per test point: no defined value to draw."), std::string::npos);
  size_t charts = 0;
  for (size_t at = page.find("data:image/svg+xml;base64,"); at != std::string::npos; at = page.find("data:image/svg", at + 1)) ++charts;
  EXPECT_EQ(charts, 2u);
  EXPECT_NE(page.find("a&lt;b"), std::string::npos);  // names escaped
  EXPECT_EQ(page.find("data-key=\"/test_points/0/image/right"), std::string::npos);
  EXPECT_EQ(page.find("data-key=\"/totals/misperception_rms"), std::string::npos);
  EXPECT_NE(page.find("data-key=\"/test_points/0/image/left/pixel_px/p95\" data-value=\"5.0\">5.0000<"), std::string::npos);
  EXPECT_NE(page.find("data-key=\"/undefined_samples\" data-value=\"10\">10<"), std::string::npos);
  EXPECT_THROW(ErrSimHtml({{"format", "vstcal/err-sim-shard@2"}}), InternalError);  // a shard has no page
}

}  // namespace
}  // namespace vstcal
