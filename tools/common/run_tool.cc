#include "common/run_tool.h"

#include <iostream>

#include "vstcal/core/error.h"

namespace vstcal::tools {

int RunTool(CLI::App& app, int argc, char** argv, const std::function<int()>& body) {
  const std::string tool = app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::CallForVersion& e) {
    std::cout << e.what() << "\n";
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << tool << ": error: " << e.what() << "; see " << tool << " --help\n";
    return static_cast<int>(ExitCode::kBadInput);
  }
  try {
    return body();
  } catch (const Error& e) {
    std::cerr << tool << ": error: " << e.what() << "\n";
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::cerr << tool << ": internal error: " << e.what() << " (please report this)\n";
    return static_cast<int>(ExitCode::kInternal);
  }
}

}  // namespace vstcal::tools
