// vstcal/target@1 reader and writer (docs/formats.md#target): the description of one printed
// board that calib-capture target writes and detect and render read.
#pragma once

#include <filesystem>

#include "vstcal/capture/target.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// Reads and checks a target file; throws InputError "<file>: <field>: <what>; <fix>" (exit code 2)
// for a bad value, a field of another target type, or a target that fails CheckTarget.
Target ReadTarget(const std::filesystem::path& path);
Target TargetFromJson(const JsonDocument& doc);

// Fields in the documented order; `sheet` and `board_frame` are written for the reader of the
// file and never read.
OrderedJson TargetToJson(const Target& target, const Provenance& provenance);

}  // namespace vstcal
