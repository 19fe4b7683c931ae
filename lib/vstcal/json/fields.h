// Field readers that every JSON format shares, on top of json_reader.h: an image size, a length
// unit, a rigid transform, and the strict-keys rule of formats that refuse unknown keys. Each
// fails with the one-line "<file>: <field>: <what>; <fix>" of JsonNode::Fail (exit code 2).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "vstcal/core/image_size.h"
#include "vstcal/core/units.h"
#include "vstcal/geometry/rigid3.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {

// image_size [width, height]: two positive integers (px).
ImageSize ReadImageSize(const JsonNode& node);

// length_unit: one of kLengthUnitNames ("mm", "cm", "m", "in").
LengthUnit ReadLengthUnit(const JsonNode& node);

// A transform {"R": 3×3, "t": [3]}: R must be a rotation to 1e-6; one that is not a rotation to
// 1e-14 is replaced by the nearest rotation (a rotation to rounding is kept bit for bit).
Rigid3d ReadRigid(const JsonNode& node);

// Fails on any key of an object not in `allowed`, naming it as `what` and suggesting the closest
// allowed key ("sources.trackin: unknown error source "trackin"; did you mean "tracking"? …"):
// for formats where a mistyped key would otherwise silently mean nothing.
void ExpectKeys(const JsonNode& node, const std::vector<std::string_view>& allowed, const std::string& what);

}  // namespace vstcal
