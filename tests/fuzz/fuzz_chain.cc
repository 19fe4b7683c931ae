// vstcal/vst-chain@1 with the camera@1 file it references (docs/formats.md#vst-chain). The input
// is the chain's text, then a line "%%", then the camera file's text, which the harness writes to
// camera.json beside the chain (a chain names it {"file": "camera.json"}). What is read goes
// through a tiny Monte Carlo run (8 samples, one thread), and its report must hold only finite
// numbers.
#include <stdlib.h>

#include <fstream>

#include "harness.h"
#include "vstcal/errsim/chain_io.h"
#include "vstcal/errsim/report.h"

namespace {

// A private directory for camera.json, made once per process.
const std::filesystem::path& Directory() {
  static const std::filesystem::path dir = [] {
    std::string tmpl = (std::filesystem::temp_directory_path() / "vstcal-fuzz-chain-XXXXXX").string();
    vstcal::fuzz::Require(::mkdtemp(tmpl.data()) != nullptr, "cannot create a temporary directory");
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

}  // namespace

VSTCAL_FUZZ_TARGET(text) {
  using namespace vstcal;
  const size_t split = text.find("\n%%\n");
  std::ofstream(Directory() / "camera.json", std::ios::binary | std::ios::trunc)
      << (split == std::string::npos ? std::string() : text.substr(split + 4));
  const io::JsonDocument doc = io::JsonDocument::Parse(text.substr(0, split), "fuzz.json");
  errsim::ChainModel model = errsim::ChainFromJson(doc, Directory());
  errsim::SimulationOptions options;
  options.samples = 8;
  options.seed = model.seed;
  options.budget = false;
  options.threads = 1;
  model.samples = options.samples;
  const std::string digest = errsim::ChainDigest(model);
  const errsim::SimulationResult result = errsim::RunSimulation(errsim::MakeScenarios(model, false), options, digest);
  errsim::RunDescription run{"fuzz.json", digest, {}, {}, options};
  io::DumpJson(errsim::ReportToJson(model, result, run, fuzz::kProvenance));
}
