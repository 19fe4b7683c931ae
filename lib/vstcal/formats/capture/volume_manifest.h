// Which template position each image of a calibration volume shows (seed 000 §4.1: the template
// moved along its normal between the near and far planes): a vstcal/volume-manifest@1 file
// (docs/formats.md#volume-manifest), or a pattern that reads the offset from each file name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "vstcal/core/units.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

struct ManifestImage {
  std::string image;    // path as written in the manifest (relative to the manifest's folder)
  std::filesystem::path path;  // the file: `image` resolved against the manifest's folder
  double plane_offset = 0;     // the template's offset along its normal, in `length_unit`
};

struct VolumeManifest {
  LengthUnit length_unit = LengthUnit::kMillimetre;
  std::vector<ManifestImage> images;
};

// Reads and checks a manifest: at least one image, every image named once and existing, every
// offset finite. Throws InputError "<file>: images[3].image: …; …".
VolumeManifest ReadVolumeManifest(const std::filesystem::path& path);
VolumeManifest VolumeManifestFromJson(const JsonDocument& doc, const std::filesystem::path& folder);

OrderedJson VolumeManifestToJson(const VolumeManifest& manifest, const Provenance& provenance);

// The plane offset in a file name: `pattern` is an ECMAScript regular expression searched in the
// file's name (not its folder) whose first group is the number, e.g. "z(-?[0-9.]+)mm". Throws
// InputError naming `flag` when the pattern is invalid, has no group, or the name does not match.
double OffsetFromName(const std::filesystem::path& image, const std::string& pattern, const std::string& flag);

}  // namespace vstcal
