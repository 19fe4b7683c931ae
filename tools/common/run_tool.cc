#include "common/run_tool.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <vector>
#include <string_view>

#include <glog/logging.h>

#include "vstcal/core/error.h"
#include "vstcal/core/option_name.h"
#include "vstcal/core/suggest.h"
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

// What a tool printed on stdout (a table, a comparison) is its output: when it could not be written
// (a full disk, a closed pipe, > /dev/full) the run failed, however well the rest went. Buffered
// text is written at the latest here, so the check sees every write.
std::string StdoutProblem() {
  errno = 0;  // before the flush: std::cout's sync buffer flushes stdout, where a write fails first
  std::cout.flush();
  const bool failed = std::fflush(stdout) != 0 || std::ferror(stdout) || std::cout.fail();
  if (!failed) return {};
  return "standard output: cannot write (" + std::string(errno ? std::strerror(errno) : "write error") +
         "); the output is lost: check the disk space, or write it to a file";
}

int CheckStdout(const std::string& tool, int code) {
  const std::string problem = StdoutProblem();
  if (problem.empty()) return code;
  std::cerr << tool << ": error: " << problem << "\n";
  return code == 0 ? static_cast<int>(ExitCode::kBadInput) : code;
}

// The long flags of `app` and of the subcommands the command line chose (all of them when it chose
// none), as "--name".
void CollectFlags(const CLI::App& app, bool all_subcommands, std::vector<std::string>* flags) {
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& name : option->get_lnames()) flags->push_back("--" + name);
  }
  std::vector<const CLI::App*> chosen;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (all_subcommands || sub->parsed()) chosen.push_back(sub);
  }
  for (const CLI::App* sub : chosen) CollectFlags(*sub, all_subcommands, flags);
}

// " (did you mean --depth?)" for the first unknown flag of an ExtrasError's message that is close to
// a known one; empty otherwise.
std::string DidYouMean(const CLI::App& app, const std::string& message) {
  std::vector<std::string> flags;
  bool any_chosen = false;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) any_chosen = any_chosen || sub->parsed();
  CollectFlags(app, !any_chosen, &flags);
  const std::vector<std::string_view> candidates(flags.begin(), flags.end());
  const size_t colon = message.find(": ");
  std::istringstream words(colon == std::string::npos ? message : message.substr(colon + 2));
  for (std::string word; words >> word;) {
    if (word.size() < 3 || word.rfind("--", 0) != 0) continue;
    word = word.substr(0, word.find('='));
    if (const auto match = ClosestMatch(word, candidates)) return " (did you mean " + std::string(*match) + "?)";
  }
  return {};
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
    return CheckStdout(tool, 0);
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return CheckStdout(tool, 0);
  } catch (const CLI::ExtrasError& e) {
    std::cerr << tool << ": error: " << OneLine(e.what()) << DidYouMean(app, e.what()) << "; see " << tool << " --help\n";
    return static_cast<int>(ExitCode::kBadInput);
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": error: " << OneLine(e.what()) << "; see " << tool << " --help\n";
    return static_cast<int>(ExitCode::kBadInput);
  }
  try {
    const InputProtection protection;  // no output may be an input (files/input_protection.h)
    return CheckStdout(tool, body());
  } catch (const Error& e) {
    if (dynamic_cast<const InternalError*>(&e) != nullptr) {
      std::cerr << tool << ": internal error: " << OneLine(ForUser(e.what())) << " (please report this)\n";
    } else {
      std::cerr << tool << ": error: " << OneLine(ForUser(e.what())) << "\n";
    }
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << OneLine(e.what()) << " (please report this)\n";
    return static_cast<int>(ExitCode::kInternal);
  }
}

std::string ForUser(std::string_view text) { return RenderOptionNames(text, OptionAsFlag); }

void PrintToStdout(const std::string& text) {
  std::fputs(text.c_str(), stdout);
  if (std::string problem = StdoutProblem(); !problem.empty()) throw InputError(problem);
}

std::string InvokedAs(int argc, char** argv, std::initializer_list<std::string> names) {
  if (argc > 0 && argv[0] != nullptr) {
    const std::string invoked = std::filesystem::path(argv[0]).filename().string();
    for (const std::string& n : names) {
      if (n == invoked) return n;
    }
  }
  return *names.begin();
}

}  // namespace vstcal::tools
