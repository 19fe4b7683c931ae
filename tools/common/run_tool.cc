#include "common/run_tool.h"

#include <cstdio>
#include <iostream>
#include <string_view>

#include <glog/logging.h>

#include "vstcal/core/error.h"
#include "vstcal/core/version.h"
#include "vstcal/files/input_protection.h"

namespace vstcal::tools {
namespace {

// Messages quote file names and values from the input (a view name, a "format" string), which may
// hold a newline; escape control characters so that a message is always exactly one line.
std::string OneLine(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace

int RunTool(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  const std::string tool = app.get_name();
  // Ceres logs through glog to stderr; a tool's stderr holds only its own warnings and its one-line
  // error (solver outcomes come back in result structs and are reported from there).
  FLAGS_minloglevel = google::GLOG_FATAL;
  app.set_version_flag("--version", tool + " " + kVersion, "print the version and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": error: " << OneLine(e.what()) << "; see " << tool << " --help\n";
    return static_cast<int>(ExitCode::kBadInput);
  }
  try {
    const InputProtection protection;  // no output may be an input (files/input_protection.h)
    return body();
  } catch (const Error& e) {
    if (e.code() == ExitCode::kInternal) {
      std::cerr << tool << ": internal error: " << OneLine(e.what()) << " (please report this)\n";
    } else {
      std::cerr << tool << ": error: " << OneLine(e.what()) << "\n";
    }
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << OneLine(e.what()) << " (please report this)\n";
    return static_cast<int>(ExitCode::kInternal);
  }
}

}  // namespace vstcal::tools
