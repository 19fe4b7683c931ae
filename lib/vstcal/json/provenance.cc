#include "vstcal/json/provenance.h"

#include "vstcal/core/version.h"

namespace vstcal {

Provenance MakeProvenance(std::string tool, int argc, const char* const* argv, std::optional<uint64_t> seed) {
  Provenance p;
  p.tool = std::move(tool);
  for (int i = 1; i < argc; ++i) p.args.emplace_back(argv[i]);
  p.seed = seed;
  return p;
}

OrderedJson ProvenanceToJson(const Provenance& p) {
  OrderedJson j;
  j["tool"] = p.tool;
  j["version"] = kVersion;
  j["args"] = p.args;
  j["seed"] = p.seed ? OrderedJson(*p.seed) : OrderedJson(nullptr);
  return j;
}

}  // namespace vstcal
