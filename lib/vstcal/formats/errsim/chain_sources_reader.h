// What chain_reader.cc and chain_sources_reader.cc share: the chain file's "sources" object is
// read in a file of its own (it is half of the format).
#pragma once

#include <string>
#include <string_view>

#include "vstcal/formats/errsim/chain_spec.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"

namespace vstcal::chain_reading {

// Built by appending: GCC 12's -Wrestrict misfires on "literal" + std::string.
inline std::string Quoted(std::string_view s) { return std::string("\"").append(s).append("\""); }
inline std::string Number(double v) { return ShortestDecimal(v); }

// Reads sources (the file's "sources" object) into spec's terms, correlations and measured
// references; spec's frames, cameras and references must already be read.
void ReadSources(const JsonNode& sources, ChainSpec* spec);

}  // namespace vstcal::chain_reading
