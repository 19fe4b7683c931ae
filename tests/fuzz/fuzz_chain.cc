// vstcal/vst-chain@1 with the file it references (docs/formats.md#vst-chain): a camera@1 file, or
// the stereo@1 rig that gives both cameras and the right camera's pose and covariance. The input
// is the chain's text, then a line "%%", then the referenced file's text, which the harness writes
// to camera.json beside the chain (a chain names it {"file": "camera.json"} under cameras or
// under "rig"; the corpus has both). The canonical writer's
// output must be a fixed point (`err-sim normalize`), and what is read goes through a tiny Monte
// Carlo run (8 samples, one thread) whose report must hold only finite numbers.
#include <stdlib.h>

#include <filesystem>
#include <fstream>

#include "harness.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/formats/errsim/report_format.h"

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

vstcal::ChainSpec ChainRead(const std::string& chain_text) {
  return vstcal::ChainSpecFromJson(vstcal::JsonDocument::Parse(chain_text, "fuzz.json"), Directory());
}

std::string ChainPass(const std::string& chain_text) {
  return vstcal::DumpJson(vstcal::ChainSpecToJson(ChainRead(chain_text), vstcal::fuzz::kProvenance));
}

}  // namespace

VSTCAL_FUZZ_TARGET(chain, text) {
  using namespace vstcal;
  const size_t split = text.find("\n%%\n");
  std::ofstream(Directory() / "camera.json", std::ios::binary | std::ios::trunc)
      << (split == std::string::npos ? std::string() : text.substr(split + 4));
  const std::string chain_text = text.substr(0, split);
  ChainModel model = BuildChainModel(ChainRead(chain_text));
  fuzz::RequireFixedPoint(chain_text, ChainPass);
  SimulationOptions options;
  options.samples = 8;
  options.seed = model.seed;
  options.budget = false;
  options.threads = 1;
  model.samples = options.samples;
  RunDescription run{"fuzz.json", ChainDigest(model), {}, {}, options};
  const SimulationResult result = RunSimulation(MakeScenarios(model, false), options, run.digest);
  DumpJson(ReportToJson(ChainEvaluator(model), result, run, fuzz::kProvenance));
}
