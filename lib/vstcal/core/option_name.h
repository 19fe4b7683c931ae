// A request's option named in a library message. The library serves several front ends — the
// tools' flags, the Python module's keyword arguments — so it never spells one of them: it writes
// Opt("tilt_deg"), and each front end renders that as its user typed it (the tools as "--tilt-deg"
// in RunTool, Python as "tilt_deg"). docs/architecture.md#conventions.
#pragma once

#include <string>
#include <string_view>

// The marked name as a string literal, for messages built from literals (and format strings):
//   throw InputError(VSTCAL_OPT("tilt_deg") ": must lie within ±80°");
#define VSTCAL_OPT(name) "\u2039" name "\u203a"

namespace vstcal {

// The marked name, "‹tilt_deg›": snake_case, the option's neutral name.
std::string Opt(std::string_view name);

// `message` with every marked name replaced by rename(name); the rest unchanged.
std::string RenderOptionNames(std::string_view message, std::string (*rename)(std::string_view name));

// The two renderings: the command line's flag ("--tilt-deg") and the keyword argument ("tilt_deg").
std::string OptionAsFlag(std::string_view name);
std::string OptionAsKeyword(std::string_view name);

}  // namespace vstcal
