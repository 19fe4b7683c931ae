// The "format" field that opens every vstcal file: schema name and major version.
#pragma once

#include <string_view>

#include "vstcal/json/json_reader.h"

namespace vstcal {

// Fails with a message that says what the file is instead (another vstcal schema, another major
// version, or something else) when root.format is not `expected` (e.g. "vstcal/camera@1").
void CheckFormat(const JsonNode& root, std::string_view expected);

}  // namespace vstcal
