// An HTML report as a person sees it, for the CLI tests of every tool with --html: the page
// rendered by headless Chromium (Debian's chromium), its console, whether the browser decodes
// every image, the numbers of the rendered DOM against the JSON report, and a screenshot.
#pragma once

#include <string>
#include <vector>

#include "cli_fixture.h"

namespace vstcal::cli_test {

inline constexpr const char* kChromium = "/usr/bin/chromium";

class BrowserTest : public CliTest {
 protected:
  // Chromium's run on a page until its load event (a 3 s virtual-time budget), its log on stderr;
  // `extra` flags, e.g. --dump-dom (the DOM on stdout) and --screenshot=FILE (both in one run).
  CommandResult Render(const std::string& page, const std::vector<std::string>& extra = {}) const;

  // The value of attribute `name` of every element that has one, in document order.
  static std::vector<std::string> Attributes(const std::string& html, const std::string& name);
  // The lines of a Chromium log that are console messages (a blocked fetch, a script error).
  static std::vector<std::string> ConsoleLines(const std::string& log);

  // Expects every src of `dom` to be an inline SVG or PNG (a fetch would need another src) and
  // returns how many there are.
  static size_t ExpectInlinePictures(const std::string& dom);

  // Checks every data-key="POINTER" data-value="V">SHOWN cell of `dom`: V equals the number at
  // POINTER in `report` and SHOWN rounds it to 4 decimals. Returns how many cells it checked.
  static size_t ExpectNumbersOf(const Json& report, const std::string& dom);

  // A page as a person sees it, from one Chromium run (each run costs seconds: one per page, not
  // one per question).
  struct PageView {
    std::string dom;          // the DOM once the page has loaded
    std::string images;       // "N loaded, B broken": the images the browser decoded, or could not
    std::string wide_tables;  // the tables that do not fit the page's column, or "none" (below)
    std::string result;       // the value of the caller's JavaScript expression, if one was given
  };

  // Loads `page` (relative to dir()) in a `width`×`height` window and saves a screenshot as
  // build/test-artifacts/<shot>, expected to have something drawn on it (not blank). The page must
  // hold no script of its own (its policy allows none); what is loaded is a copy with one inline
  // script appended (its policy then allows that script and still no fetch), which reports on the
  // load event. Expects no console message (a blocked fetch, a script error) while it loads.
  //
  // wide_tables: each table whose right edge passes the right edge of the body's content box (the
  // page's column), as "CAPTION: right edge R px, page P px" joined by "; ". A table in a scrolling
  // box counts by its own edge, so a table that fits only by scrolling is reported too.
  PageView View(const std::string& page, const std::string& shot, int width, int height,
                const std::string& expression = "") const;
};

}  // namespace vstcal::cli_test
