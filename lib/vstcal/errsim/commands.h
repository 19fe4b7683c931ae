// What each err-sim subcommand does, as library calls (docs/tools/err-sim.md): the tool's main only
// parses flags, calls one of these and writes the returned files. A C++ user gets the same results
// without the tool.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal::errsim {

// The chain as selected on the command line.
struct ChainRequest {
  std::string chain;                // path as given (resolved against the working directory)
  std::vector<std::string> only;    // source keys; InputError with a suggestion for unknown keys
  std::vector<std::string> without;
  std::optional<uint64_t> samples;  // override the file's
  std::optional<uint64_t> seed;
  unsigned threads = 0;
};

// Reads the chain and applies only/without, naming the flag in messages about unknown keys.
ChainModel LoadChain(const ChainRequest& request);

struct Outcome {
  io::OrderedJson json;  // the output file
  std::string text;      // the summary for stderr (empty for a shard)
};

struct RunRequest {
  ChainRequest chain;
  bool budget = true;
  std::optional<uint64_t> budget_samples;  // default: the run's samples
  uint64_t shard = 0, shards = 1;          // shards > 1: write a shard file for `merge`
};
Outcome RunErrSim(const RunRequest& request, const io::Provenance& provenance, const Progress& progress = {});

// Merges shard files of one run into its report; the chain must be the one the shards ran.
Outcome MergeErrSim(const std::string& chain, const std::vector<std::string>& shard_files, const io::Provenance& provenance);

struct SweepRequest {
  ChainRequest chain;
  std::vector<std::string> parameters;  // names (empty: every non-constant parameter)
  size_t points = 21;
  std::optional<double> lo, hi;  // sweep range in the parameter's file unit (default: ±3σ or the support)
};
Outcome SweepErrSim(const SweepRequest& request, const io::Provenance& provenance);

struct SobolRequest {
  ChainRequest chain;
  std::string sampling = "sobol";  // or "pseudo-random"
  size_t bootstrap = 200;
};
Outcome SobolErrSim(const SobolRequest& request, const io::Provenance& provenance);

Outcome LinearErrSim(const ChainRequest& request, const io::Provenance& provenance);

}  // namespace vstcal::errsim
