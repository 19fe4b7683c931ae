// err-sim run --html as a person sees it (browser_fixture.h): the page of a short run of the shipped
// seed 001 chain (and of a sweep) renders offline with no console message, every image decodes, every number shown
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

  const CommandResult dom = Render("out/run.html", {"--dump-dom"});
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  EXPECT_TRUE(ConsoleLines(dom.err).empty()) << ConsoleLines(dom.err).front();
  // Image, misregistration and misperception distributions; the budget of each ranked measure.
  EXPECT_EQ(ExpectInlinePictures(dom.out), 3u + 2);

  // Whole chain (6), per point and eye (6 statistics), per point misregistration (7) and
  // misperception (7), per source and ranked measure (5): every one the JSON's.
  const size_t sources = report["budget"]["entries"].size();
  EXPECT_EQ(ExpectNumbersOf(report, dom.out), 6 + points * (2 * 6 + 7 + 7) + 2 * sources * 5);
  // The budget rows follow the report's ranking, and each shows its source's halved column.
  const std::vector<std::string> keys = Attributes(dom.out, "data-key");
  std::vector<std::string> halved;
  for (const std::string& key : keys) {
    if (key.find("/halved/misregistration_rms") != std::string::npos) halved.push_back(key);
  }
  ASSERT_EQ(halved.size(), sources);
  for (size_t i = 0; i < sources; ++i) {
    const std::string entry = halved[i].substr(0, halved[i].find("/halved"));
    EXPECT_EQ(report.at(Json::json_pointer(entry + "/source")), report["budget"]["ranking"]["misregistration"][i]) << i;
  }

  EXPECT_EQ(ImagesLoaded("out/run.html"), "5 loaded, 0 broken");
  ExpectScreenshot("out/run.html", "err-sim.png", 1000, 2400);
}

TEST_F(CliErrSimHtml, SweepPageShowsTheCurvesAndTheSteepestSlopes) {
  ASSERT_TRUE(fs::exists(kChromium)) << "scripts/setup installs chromium";
  const CommandResult r = Run("err-sim", {"sweep", kChain, "-o", "out/sweep.json", "--html", "out/sweep.html", "--parameter",
                                          "tracking.latency,camera_intrinsic.left.cx,camera_intrinsic.right.cx", "--points", "5", "-q"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json sweep = ReadJson("out/sweep.json");
  ASSERT_EQ(sweep["parameters"].size(), 3u);
  const CommandResult dom = Render("out/sweep.html", {"--dump-dom"});
  ASSERT_EQ(dom.exit_code, 0) << dom.err;
  EXPECT_TRUE(ConsoleLines(dom.err).empty()) << ConsoleLines(dom.err).front();
  EXPECT_EQ(ExpectInlinePictures(dom.out), 2u * 2);  // two sources, image and 3-D curves each
  // Range, both measures at both ends and the steepest slope of each parameter: the JSON's.
  EXPECT_EQ(ExpectNumbersOf(sweep, dom.out), 3u * 7);
  size_t slopes = 0;
  for (const std::string& key : Attributes(dom.out, "data-key")) {
    if (key.find("/slope_per_unit/") == std::string::npos) continue;
    ++slopes;
    const Json& all = sweep.at(Json::json_pointer(key.substr(0, key.rfind('/'))));
    double steepest = 0;
    for (const Json& v : all) steepest = std::max(steepest, std::abs(v.get<double>()));
    EXPECT_EQ(std::abs(sweep.at(Json::json_pointer(key)).get<double>()), steepest) << key;
  }
  EXPECT_EQ(slopes, 3u);
  EXPECT_EQ(ImagesLoaded("out/sweep.html"), "4 loaded, 0 broken");
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

}  // namespace
}  // namespace vstcal::cli_test
