// err-sim run --html as a person sees it (browser_fixture.h): the page of a short run of the shipped
// seed 001 chain (and of a sweep, Sobol indices, a linear comparison) renders offline with no console message, every image decodes, every number shown
// is the JSON report's at the pointer it names; the same seed gives the same bytes; a page that
// cannot be written leaves nothing behind.
#include <algorithm>
#include <cmath>

#include "browser_fixture.h"

namespace vstcal::cli_test {
namespace {

using CliErrSimHtml = BrowserTest;

const std::string kChain = std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json";

std::vector<std::string> ShortRun(const std::string& json, const std::string& html) {
  return {"run", kChain, "-o", json, "--html", html, "--samples", "400", "--budget-samples", "200", "-q"};
}

TEST_F(CliErrSimHtml, RendersOfflineWithEveryImageAndTheJsonsNumbers) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  const CommandResult r = Run("err-sim", ShortRun("out/run.json", "out/run.html"));
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json report = ReadJson("out/run.json");
  const size_t points = report["test_points"].size();
  ASSERT_EQ(points, 5u);

  const PageView view = View("out/run.html", "err-sim.png", 1000, 2400);
  const std::string& dom = view.dom;
  // Image, misregistration and misperception distributions; the budget of each ranked measure
  // (the image misregistration first: the default ranking).
  EXPECT_EQ(ExpectInlinePictures(dom), 3u + 3);

  // Whole chain (6), per point and eye (6 statistics), per point misregistration (7) and
  // misperception (7), per source and ranked measure (5), and per ranked measure the row of
  // interactions and means in common (its share and the one beside it) and the whole chain's (its
  // RMS and the one beside it, 4): every one the JSON's. Three ranked measures: the image's, the
  // 3-D misregistration's and the misperception's.
  // Each term of a source with several, under it in each ranked measure: its share, alone RMS and
  // the share beside it (3).
  const size_t sources = report["budget"]["entries"].size();
  size_t terms = 0;
  for (const Json& e : report["budget"]["entries"]) terms += e["terms"].size() > 1 ? e["terms"].size() : 0;
  EXPECT_GT(terms, 10u);
  EXPECT_EQ(ExpectNumbersOf(report, dom), 6 + points * (2 * 6 + 7 + 7) + 3 * sources * 5 + 3 * 4 + 3 * 3 * terms);
  // The budget rows follow the report's rankings — the image's (the default), then the 3-D
  // misregistration's, then the misperception's — and each shows its source's halved columns: the
  // image's in every table (its own, then beside the others), the 3-D one in the first two.
  const std::vector<std::string> keys = Attributes(dom, "data-key");
  auto halved = [&](const std::string& rms) {
    std::vector<std::string> rows;
    for (const std::string& key : keys) {
      if (key.find("/halved/" + rms) != std::string::npos) rows.push_back(key.substr(0, key.find("/halved")));
    }
    return rows;
  };
  const std::vector<std::string> image = halved("image_rms_px"), misregistration = halved("misregistration_rms");
  ASSERT_EQ(image.size(), 3 * sources);
  ASSERT_EQ(misregistration.size(), 2 * sources);
  EXPECT_EQ(report["budget"]["ranked_by"], "image");
  for (size_t i = 0; i < sources; ++i) {
    EXPECT_EQ(report.at(Json::json_pointer(image[i] + "/source")), report["budget"]["ranking"]["image"][i]) << i;
    EXPECT_EQ(report.at(Json::json_pointer(misregistration[i] + "/source")), report["budget"]["ranking"]["image"][i]) << i;
    EXPECT_EQ(report.at(Json::json_pointer(misregistration[sources + i] + "/source")), report["budget"]["ranking"]["misregistration"][i]) << i;
    EXPECT_EQ(report.at(Json::json_pointer(image[2 * sources + i] + "/source")), report["budget"]["ranking"]["misperception"][i]) << i;
  }

  // Where each row's distributions came from (issue 21 item 4): seed 001 types every σ, so every
  // source and term row of the three ranked tables says "assumed".
  size_t assumed = 0;
  for (size_t at = 0; (at = dom.find("<td class=\"origin\" style=\"text-align:left\">assumed</td>", at)) != std::string::npos; ++at) ++assumed;
  EXPECT_EQ(assumed, 3 * (sources + terms));
  for (const Json& e : report["budget"]["entries"]) EXPECT_EQ(e["origin"], Json::parse(R"([{"kind": "assumed"}])")) << e["source"];

  EXPECT_EQ(view.images, "6 loaded, 0 broken");  // three distributions, three budgets
  EXPECT_EQ(view.wide_tables, "none");
}

TEST_F(CliErrSimHtml, SweepPageShowsTheCurvesAndTheSteepestSlopes) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  const CommandResult r = Run("err-sim", {"sweep", kChain, "-o", "out/sweep.json", "--html", "out/sweep.html", "--parameter",
                                          "tracking.latency,camera_intrinsic.left.cx,camera_intrinsic.right.cx", "--points", "5", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json sweep = ReadJson("out/sweep.json");
  ASSERT_EQ(sweep["parameters"].size(), 3u);
  const PageView view = View("out/sweep.html", "err-sim-sweep.png", 1000, 1600);
  const std::string& dom = view.dom;
  EXPECT_EQ(ExpectInlinePictures(dom), 2u * 2);  // two sources, image and 3-D curves each
  // Range, both measures at both ends and the steepest slope of each parameter: the JSON's.
  EXPECT_EQ(ExpectNumbersOf(sweep, dom), 3u * 7);
  size_t slopes = 0;
  for (const std::string& key : Attributes(dom, "data-key")) {
    if (key.find("/slope_per_unit/") == std::string::npos) continue;
    ++slopes;
    const Json& all = sweep.at(Json::json_pointer(key.substr(0, key.rfind('/'))));
    double steepest = 0;
    for (const Json& v : all) steepest = std::max(steepest, std::abs(v.get<double>()));
    EXPECT_EQ(std::abs(sweep.at(Json::json_pointer(key)).get<double>()), steepest) << key;
  }
  EXPECT_EQ(slopes, 3u);
  EXPECT_EQ(view.images, "4 loaded, 0 broken");
  // The table of the longest parameter names fits the 1000 px window without scrolling.
  EXPECT_EQ(view.wide_tables, "none");
}

TEST_F(CliErrSimHtml, SameSeedGivesTheSameBytes) {
  ASSERT_EQ(Run("err-sim", ShortRun("out/a.json", "out/a.html")).exit_code, kOk);
  std::vector<std::string> args = ShortRun("out/b.json", "out/b.html");
  args.insert(args.end(), {"--threads", "1"});  // the first used every core
  ASSERT_EQ(Run("err-sim", args).exit_code, kOk);
  EXPECT_TRUE(ReadText("out/a.html") == ReadText("out/b.html"));
  // Another seed: other numbers, so another page.
  args = ShortRun("out/c.json", "out/c.html");
  args.insert(args.end(), {"--seed", "99"});
  ASSERT_EQ(Run("err-sim", args).exit_code, kOk);
  EXPECT_FALSE(ReadText("out/a.html") == ReadText("out/c.html"));
}

TEST_F(CliErrSimHtml, PageThatCannotBeWrittenLeavesNothing) {
  EXPECT_TRUE(FailsWith(Run("err-sim", ShortRun("out/r.json", "out/missing/r.html")), "err-sim", kBadInput,
                        "out/missing/r.html: ", {"does not exist"}));
  EXPECT_TRUE(OutDirEmpty());
  // The page onto the chain it reads: refused before any work, the chain untouched.
  fs::copy_file(kChain, Path("in/chain.json"));
  const std::string chain = ReadText("in/chain.json");
  std::vector<std::string> args = ShortRun("out/r.json", "in/chain.json");
  args[1] = "in/chain.json";
  EXPECT_EQ(Run("err-sim", args).exit_code, kBadInput);
  EXPECT_TRUE(ReadText("in/chain.json") == chain);
  EXPECT_TRUE(OutDirEmpty());
  // A shard file is no report: --html goes to merge.
  args = ShortRun("out/r.json", "out/r.html");
  args.insert(args.end(), {"--shard", "0/2"});
  EXPECT_TRUE(FailsWith(Run("err-sim", args), "err-sim", kBadInput, "--html: ", {"give --html to `err-sim merge`"}));
  EXPECT_TRUE(OutDirEmpty());
}

// Rows of the linear page's "differs" column that name a disagreement.
size_t DifferingRows(const std::string& dom) {
  size_t n = 0;
  for (const char* cell : {"<td>mean</td>", "<td>σ</td>", "<td>mean, σ</td>"}) {
    for (size_t at = dom.find(cell); at != std::string::npos; at = dom.find(cell, at + 1)) ++n;
  }
  return n;
}

TEST_F(CliErrSimHtml, SobolPageShowsEachSourcesIndicesWithTheirIntervals) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  const CommandResult r = Run("err-sim", {"sobol", kChain, "-o", "out/sobol.json", "--html", "out/sobol.html", "--samples", "64",
                                          "--bootstrap", "20", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json sobol = ReadJson("out/sobol.json");
  const size_t groups = sobol["groups"].size(), outputs = sobol["outputs"].size();
  ASSERT_EQ(groups, 7u);
  ASSERT_EQ(outputs, 5u * 14);
  const PageView view = View("out/sobol.html", "err-sim-sobol.png", 1000, 1600);
  const std::string& dom = view.dom;
  // A chart per test point for the image error of each eye and the linear misregistration and misperception.
  const size_t charted = 5 * 4;
  EXPECT_EQ(ExpectInlinePictures(dom), charted);
  // The run (3); each charted output's first and total index of every source with both interval
  // ends (6); every output's mean, variance and both indices of every source: all the JSON's.
  EXPECT_EQ(ExpectNumbersOf(sobol, dom), 3 + charted * groups * 6 + outputs * (2 + 2 * groups));
  // The interval cells are those of the charted outputs, and each source's of every one of them.
  size_t lower_ends = 0;
  for (const std::string& key : Attributes(dom, "data-key")) {
    if (!key.ends_with("/first/interval/0")) continue;
    ++lower_ends;
    const std::string name = sobol.at(Json::json_pointer(key.substr(0, key.find("/indices")) + "/name")).get<std::string>();
    EXPECT_TRUE(name.ends_with(".pixel_px") || name.ends_with(".linear")) << name;
  }
  EXPECT_EQ(lower_ends, charted * groups);
  EXPECT_EQ(view.images, std::to_string(charted) + " loaded, 0 broken");
  EXPECT_EQ(view.wide_tables, "none");
}

TEST_F(CliErrSimHtml, LinearPageShowsFirstOrderAgainstMonteCarlo) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  const CommandResult r =
      Run("err-sim", {"linear", kChain, "-o", "out/linear.json", "--html", "out/linear.html", "--samples", "200", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json linear = ReadJson("out/linear.json");
  const size_t outputs = linear["outputs"].size(), sources = linear["outputs"][0]["linear_sigma_by_source"].size();
  ASSERT_EQ(outputs, 5u * 10);
  ASSERT_EQ(sources, 7u);
  const PageView view = View("out/linear.html", "err-sim-linear.png", 1000, 1600);
  const std::string& dom = view.dom;
  // σ linear against Monte Carlo for the pixel and for the length outputs; the relative differences.
  EXPECT_EQ(ExpectInlinePictures(dom), 3u);
  // The run (4); per output both means, the mean's standard error, both σ, the σ's standard error,
  // the relative difference and the σ from each source.
  EXPECT_EQ(ExpectNumbersOf(linear, dom), 4 + outputs * (7 + sources));
  // As many rows say "differs" as the file counts disagreements.
  EXPECT_EQ(DifferingRows(dom), linear["disagreements"].get<size_t>());
  EXPECT_EQ(view.images, "3 loaded, 0 broken");
  EXPECT_EQ(view.wide_tables, "none");
}

TEST_F(CliErrSimHtml, SensitivityPagesAreAllOrNothingAndNormalizeHasNone) {
  EXPECT_TRUE(FailsWith(Run("err-sim", {"sobol", kChain, "-o", "out/s.json", "--html", "out/missing/s.html", "--samples", "8", "-q"}),
                        "err-sim", kBadInput, "out/missing/s.html: ", {"does not exist"}));
  EXPECT_TRUE(OutDirEmpty());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"linear", kChain, "-o", "out/l.json", "--html", "out/l.json", "--samples", "8", "-q"}),
                        "err-sim", kBadInput, "", {}));
  EXPECT_TRUE(OutDirEmpty());
  EXPECT_TRUE(FailsWith(Run("err-sim", {"normalize", kChain, "-o", "out/n.json", "--html", "out/n.html"}), "err-sim", kBadInput,
                        "--html: ", {"no page", "give --html to run, merge, sweep, sobol or linear"}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
