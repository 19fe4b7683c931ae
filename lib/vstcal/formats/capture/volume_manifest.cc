#include "vstcal/formats/capture/volume_manifest.h"

#include <cmath>
#include <regex>
#include <set>

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/json/fields.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr std::string_view kManifestFormat = "vstcal/volume-manifest@1";
constexpr size_t kMaxImages = 100000;

}  // namespace

VolumeManifest VolumeManifestFromJson(const JsonDocument& doc, const std::filesystem::path& folder) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, kManifestFormat);
  VolumeManifest m;
  m.length_unit = ReadLengthUnit(root.at("length_unit"));
  const JsonNode images = root.at("images");
  const size_t n = images.ArraySize();
  if (n == 0) images.Fail("no images", "list each image with its plane_offset");
  if (n > kMaxImages) images.Fail(std::to_string(n) + " images, more than " + std::to_string(kMaxImages), "split the capture");
  std::set<std::filesystem::path> seen;
  for (size_t i = 0; i < n; ++i) {
    const JsonNode entry = images.at(i);
    entry.ExpectObject();
    ManifestImage image;
    const JsonNode name = entry.at("image");
    image.image = name.String();
    if (image.image.empty()) name.Fail("empty image name", "give the image's file name");
    image.path = std::filesystem::path(image.image).is_absolute() ? std::filesystem::path(image.image) : folder / image.image;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(image.path, ec)) {
      name.Fail(image.path.string() + ": no such image file", "correct the name, or remove the entry");
    }
    const std::filesystem::path canonical = std::filesystem::weakly_canonical(image.path, ec);
    if (!seen.insert(ec ? image.path : canonical).second) {
      name.Fail("\"" + image.image + "\" is listed twice", "list each image once");
    }
    image.plane_offset = entry.at("plane_offset").Number();
    m.images.push_back(std::move(image));
  }
  return m;
}

VolumeManifest ReadVolumeManifest(const std::filesystem::path& path) {
  return VolumeManifestFromJson(JsonDocument::Load(path), path.parent_path());
}

OrderedJson VolumeManifestToJson(const VolumeManifest& m, const Provenance& provenance) {
  OrderedJson j;
  j["format"] = kManifestFormat;
  j["length_unit"] = LengthUnitName(m.length_unit);
  OrderedJson images = OrderedJson::array();
  for (const ManifestImage& image : m.images) images.push_back({{"image", image.image}, {"plane_offset", image.plane_offset}});
  j["images"] = std::move(images);
  j["provenance"] = ProvenanceToJson(provenance);
  return j;
}

double OffsetFromName(const std::filesystem::path& image, const std::string& pattern, const std::string& flag) {
  if (pattern.size() > 100) throw InputError(flag + ": the pattern is longer than 100 characters; give a short one, e.g. \"z(-?[0-9.]+)\"");
  std::regex re;
  try {
    re = std::regex(pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw InputError(flag + ": \"" + pattern + "\" is not a valid regular expression (" + e.what() + "); e.g. \"z(-?[0-9.]+)\"");
  }
  if (re.mark_count() < 1) throw InputError(flag + ": \"" + pattern + "\" has no group ( … ) around the offset; e.g. \"z(-?[0-9.]+)\"");
  const std::string name = image.filename().string();
  std::smatch match;
  if (!std::regex_search(name, match, re) || !match[1].matched) {
    throw InputError(flag + ": the file name \"" + name + "\" does not match \"" + pattern +
                     "\"; rename the image or fix the pattern (its first group is the plane offset)");
  }
  const std::string text = match[1].str();
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value)) {
    throw InputError(flag + ": in \"" + name + "\" the group matched \"" + text + "\", not a number; make the group match the offset only");
  }
  return value;
}

}  // namespace vstcal
