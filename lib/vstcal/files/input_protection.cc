#include "vstcal/files/input_protection.h"

#include <sys/stat.h>

#include <cerrno>

#include <mutex>
#include <optional>

#include "vstcal/core/error.h"

namespace vstcal {
namespace {

namespace fs = std::filesystem;

// A file as given, and what identifies it: (st_dev, st_ino) when it exists, else its absolute
// path with every existing symlink resolved.
struct NamedFile {
  fs::path given;
  std::optional<std::pair<dev_t, ino_t>> id;
  fs::path resolved;
};

NamedFile Identify(const fs::path& path) {
  NamedFile f{path, std::nullopt, {}};
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) f.id = std::make_pair(st.st_dev, st.st_ino);
  std::error_code ec;
  f.resolved = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) f.resolved = path.lexically_normal();
  return f;
}

// Two names of one file. An output that does not exist yet has no identity: it is the same file
// as another name only by its resolved path.
bool SameFile(const NamedFile& a, const NamedFile& b) {
  if (a.id && b.id) return *a.id == *b.id;
  return !a.id && !b.id && a.resolved == b.resolved;
}

[[noreturn]] void FailInputIsOutput(const fs::path& output, const fs::path& input) {
  throw InputError(output.string() + ": is the input " + input.string() +
                   " (the same file); write the output to another file: vstcal never overwrites its inputs");
}

struct Registry {
  std::mutex mutex;
  bool active = false;
  std::vector<NamedFile> inputs;
  std::vector<fs::path> outputs;  // declared; identified again at each check (they may appear)
};

Registry& TheRegistry() {
  static Registry registry;
  return registry;
}

std::vector<NamedFile> IdentifyAll(const std::vector<fs::path>& paths) {
  std::vector<NamedFile> files;
  for (const fs::path& p : paths) {
    if (!p.empty()) files.push_back(Identify(p));
  }
  return files;
}

// The two rules, for outputs already identified; `inputs` may be empty.
void Check(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (SameFile(outputs[k], outputs[i])) {
        throw InputError(outputs[i].given.string() + ": the same file is given for two outputs (" +
                         outputs[k].given.string() + " and " + outputs[i].given.string() +
                         "); give each output its own file name");
      }
    }
    for (const NamedFile& input : inputs) {
      if (SameFile(outputs[i], input)) FailInputIsOutput(outputs[i].given, input.given);
    }
  }
}

}  // namespace

InputProtection::InputProtection() {
  Registry& r = TheRegistry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  VSTCAL_CHECK(!r.active, "one InputProtection at a time");
  r.active = true;
}

InputProtection::~InputProtection() {
  Registry& r = TheRegistry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  r.active = false;
  r.inputs.clear();
  r.outputs.clear();
}

void DeclareOutputs(const std::vector<fs::path>& outputs) {
  Registry& r = TheRegistry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  Check(IdentifyAll(outputs), r.inputs);
  if (!r.active) return;
  for (const fs::path& p : outputs) {
    if (!p.empty()) r.outputs.push_back(p);
  }
}

void NoteInputFile(const fs::path& path) {
  Registry& r = TheRegistry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  if (!r.active) return;
  NamedFile input = Identify(path);
  for (const NamedFile& output : IdentifyAll(r.outputs)) {
    if (SameFile(output, input)) FailInputIsOutput(output.given, path);
  }
  r.inputs.push_back(std::move(input));
}

PathKind KindOfPath(const fs::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return errno == ENOENT || errno == ENOTDIR ? PathKind::kMissing : PathKind::kUnknown;
  if (S_ISREG(st.st_mode)) return PathKind::kRegularFile;
  return S_ISDIR(st.st_mode) ? PathKind::kDirectory : PathKind::kSpecial;
}

void CheckOutputs(const std::vector<fs::path>& outputs) {
  Registry& r = TheRegistry();
  const std::lock_guard<std::mutex> lock(r.mutex);
  Check(IdentifyAll(outputs), r.inputs);
}

}  // namespace vstcal
