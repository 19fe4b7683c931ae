// vstcal/volume-manifest@1 (docs/formats.md#volume-manifest): the reader and the writer's fixed
// point. The reader requires every named image to exist, so the images the seeds name are created,
// empty, in a private folder the manifest is read against.
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "harness.h"
#include "vstcal/formats/capture/volume_manifest.h"
#include "vstcal/json/json_writer.h"

namespace {

// The folder and its three empty images, removed when the process ends.
struct ImageFolder {
  std::filesystem::path path;
  ImageFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "vstcal-fuzz-manifest-XXXXXX").string();
    vstcal::fuzz::Require(mkdtemp(pattern.data()) != nullptr, "mkdtemp");
    path = pattern;
    for (const char* name : {"plane-00.png", "plane-01.png", "plane-02.png"}) std::ofstream(path / name);
  }
  ~ImageFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
};

const std::filesystem::path& Folder() {
  static const ImageFolder folder;
  return folder.path;
}

vstcal::VolumeManifest VolumeManifestRead(const std::string& text) {
  using namespace vstcal;
  return VolumeManifestFromJson(JsonDocument::Parse(text, "fuzz.json"), Folder());
}

std::string VolumeManifestPass(const std::string& text) {
  return vstcal::DumpJson(vstcal::VolumeManifestToJson(VolumeManifestRead(text), vstcal::fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(volume_manifest, text) {
  const vstcal::VolumeManifest manifest = VolumeManifestRead(text);
  vstcal::fuzz::Require(!manifest.images.empty(), "a manifest read has images");
  vstcal::fuzz::RequireFixedPoint(text, VolumeManifestPass);
}
