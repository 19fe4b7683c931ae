#include "vstcal/image/codecs.h"

#include <dlfcn.h>

#include <cstdlib>

#include "vstcal/core/error.h"
#include "vstcal/image/codecs_table.h"
#include "vstcal_codecs_path.h"

namespace vstcal {
namespace {

// A plugin that does not load is a fault of the installation, not a bug: exit 1 like an internal
// error (docs/conventions.md#exit-codes), but without asking the user to report it — the message
// says how to fix it.
Error InstallationError(const std::string& message) { return Error(ExitCode::kInternal, message); }

// Loaded once, kept for the life of the process (RTLD_NODELETE: OpenCV's backends keep threads).
const CodecsTable& Table() {
  static const CodecsTable* const table = [] {
    const char* given = std::getenv("VSTCAL_CODECS_PLUGIN");
    const std::string path = given != nullptr && *given != '\0' ? given : kCodecsPluginPath;
    void* plugin = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (plugin == nullptr) {
      const char* why = dlerror();
      throw InstallationError("the image codecs plugin " + path + " does not load (" + (why ? why : "no reason given") +
                              "); rebuild with scripts/build, or name it with VSTCAL_CODECS_PLUGIN");
    }
    using Get = const CodecsTable* (*)();
    const auto get = reinterpret_cast<Get>(dlsym(plugin, "vstcal_codecs_table"));
    const CodecsTable* found = get != nullptr ? get() : nullptr;
    if (found == nullptr || found->version != CodecsTable::kVersion) {
      throw InstallationError("the image codecs plugin " + path + " is not this build's; rebuild with scripts/build");
    }
    return found;
  }();
  return *table;
}

}  // namespace

cv::Mat DecodeGrayImage(const cv::Mat& encoded) {
  cv::Mat gray;
  if (!Table().decode_gray(encoded, &gray)) gray.release();
  return gray;
}

std::vector<unsigned char> PngBytes(const cv::Mat& image, const char* what) {
  std::vector<unsigned char> png;
  if (!Table().encode_png(image, &png)) throw InternalError(std::string("PNG encoding of ") + what + " failed");
  return png;
}

VideoSource::~VideoSource() {
  if (video_ != nullptr) Table().video_close(video_);
}

bool VideoSource::OpenCamera(int index) {
  if (video_ != nullptr) Table().video_close(video_);
  video_ = Table().video_open_camera(index);
  return video_ != nullptr;
}

bool VideoSource::OpenFile(const std::string& path, int api) {
  if (video_ != nullptr) Table().video_close(video_);
  video_ = Table().video_open_file(path.c_str(), api);
  return video_ != nullptr;
}

bool VideoSource::Grab() { return video_ != nullptr && Table().video_grab(video_); }

bool VideoSource::Read(cv::Mat* frame) { return video_ != nullptr && Table().video_read(video_, frame); }

double VideoSource::Get(int property) const { return video_ != nullptr ? Table().video_get(video_, property) : 0; }

}  // namespace vstcal
