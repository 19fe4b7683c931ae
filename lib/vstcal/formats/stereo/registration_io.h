// Binocular registration's input, vstcal/tracks@1, and output, vstcal/registration@1
// (docs/formats.md#tracks, docs/formats.md#registration).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/stereo/registration.h"
#include "vstcal/stereo/registration_accuracy.h"
#include "vstcal/scene/tracks.h"

namespace vstcal {

// Reads and validates tracks; throws InputError "<file>: <field>: <what>; <fix>". Beyond types:
// at least 4 embedded points; point and frame names non-empty and unique; every frame has one
// entry per embedded point in "left" (and in "right" when present), each [u, v] inside its image
// or null (not tracked); right pixels need image_size.right.
Tracks ReadTracks(const std::filesystem::path& path);
Tracks TracksFromJson(const JsonDocument& doc);
OrderedJson TracksToJson(const Tracks& tracks, const Provenance& provenance);

// What a registration run was, for its output file.
struct RegistrationRun {
  std::string rig, tracks;  // file names as given
  RegistrationOptions options;
};

// The vstcal/registration@1 object: per frame the poses, the fit, the virtual points in both
// images and, for frames with truth, the accuracy; then a summary.
OrderedJson RegistrationToJson(const RegistrationRun& run, const StereoRig& rig, const Tracks& tracks,
                               const std::vector<FrameRegistration>& frames, const Provenance& provenance);

}  // namespace vstcal
