// vstcal/correspondences@1 reader and writer (docs/formats.md#correspondences).
#pragma once

#include <filesystem>

#include "vstcal/scene/correspondences.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// Reads and validates every field; throws InputError naming file, field and fix. Checks beyond
// types: pixels inside the image, Z = 0 for planar views, unique view names, non-empty views.
Correspondences ReadCorrespondences(const std::filesystem::path& path);
Correspondences CorrespondencesFromJson(const JsonDocument& doc);

OrderedJson CorrespondencesToJson(const Correspondences& c, const Provenance& provenance);

}  // namespace vstcal
