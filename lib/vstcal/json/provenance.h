// Provenance recorded in every output file: which tool, which version, which arguments, which
// seed (DESIGN.md "Provenance"). No time stamp: the same run gives the same bytes.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/json/json_writer.h"

namespace vstcal {

struct Provenance {
  std::string tool;
  std::vector<std::string> args;  // argv[1..]
  std::optional<uint64_t> seed;
};

Provenance MakeProvenance(std::string tool, int argc, const char* const* argv, std::optional<uint64_t> seed = {});
OrderedJson ProvenanceToJson(const Provenance& provenance);

}  // namespace vstcal
