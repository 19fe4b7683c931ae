#include "vstcal/app/outcome.h"

#include <set>
#include <system_error>

#include "vstcal/core/error.h"
#include "vstcal/json/json_writer.h"

namespace vstcal::app {

namespace fs = std::filesystem;

void WriteOutcome(const Outcome& outputs) {
  std::vector<fs::path> created;
  std::set<fs::path> folders;
  for (const fs::path& folder : outputs.folders) {
    if (!folder.empty()) folders.insert(folder);
  }
  auto remove_created = [&] {
    std::error_code ec;
    for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, ec);  // only removes empty folders
  };
  for (const fs::path& folder : folders) {
    std::error_code ec;
    if (fs::is_directory(folder, ec)) continue;
    if (fs::exists(folder, ec)) {
      remove_created();
      throw InputError(folder.string() + ": exists and is not a folder; give an output folder");
    }
    if (folder.has_parent_path() && !fs::is_directory(folder.parent_path(), ec)) {
      remove_created();
      throw InputError(folder.string() + ": cannot create: folder " + folder.parent_path().string() + " does not exist; create it first");
    }
    if (!fs::create_directory(folder, ec) || ec) {
      remove_created();
      throw InputError(folder.string() + ": cannot create the folder (" + ec.message() + "); check the path and permissions");
    }
    created.push_back(folder);
  }
  try {
    WriteFilesAtomically(outputs.files);
  } catch (...) {
    remove_created();
    throw;
  }
}

int ExitStatus(const Outcome& outcome) {
  return static_cast<int>(outcome.check_failed ? ExitCode::kCheckFailed : ExitCode::kOk);
}

}  // namespace vstcal::app
