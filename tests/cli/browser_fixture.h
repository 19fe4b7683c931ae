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
  // `extra` flags, e.g. --dump-dom (the DOM on stdout) or --screenshot=FILE.
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

  // "N loaded, B broken": the images of `page` (relative to dir()) once the browser has loaded it,
  // from a copy with one inline script appended (its policy allows that script and still no fetch).
  // Expects no console message while that copy loads.
  std::string ImagesLoaded(const std::string& page) const;

  // The tables of `page` that do not fit the page, rendered in a `width`-pixel window: each whose
  // right edge passes the right edge of the body's content box (the page's column), as
  // "CAPTION: right edge R px, page P px" joined by "; ", or "none". A table in a scrolling box counts by its
  // own edge, so a table that fits only by scrolling is reported too. Expects no console message.
  std::string TablesWiderThanThePage(const std::string& page, int width) const;

  // Saves a `width`×`height` screenshot of `page` as build/test-artifacts/<name> and expects a page
  // with something drawn on it (not blank).
  void ExpectScreenshot(const std::string& page, const std::string& name, int width, int height) const;

  // The value of the JavaScript `expression` once `page` has loaded (its load event), read back from
  // a copy of the page that runs it; `flags` go to Chromium (e.g. a window size). Expects no console
  // message.
  std::string EvaluateOnLoad(const std::string& page, const std::string& expression,
                             const std::vector<std::string>& flags = {}) const;
};

}  // namespace vstcal::cli_test
