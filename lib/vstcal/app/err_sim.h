// What each err-sim subcommand does, as library calls (docs/tools/err-sim.md): the tool's main only
// parses flags, calls one of these and writes the returned file. A C++ user gets the same results
// without the tool. Every size has a documented maximum (the k… constants below), refused with a
// one-line InputError naming the flag; conflicting requests are refused the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal::app {

inline constexpr uint64_t kMaxSamples = 1'000'000'000'000;  // run, linear: memory does not grow with it
inline constexpr uint64_t kMaxShards = 1'000'000;
inline constexpr unsigned kMaxThreads = 256;
inline constexpr size_t kMaxSweepPoints = 1001;
// A sweep keeps parameters × points × outputs values and writes parameters × outputs slopes; the
// random parameters include one disparity per test point, so both grow with the test points
// squared (1,000 points at the default 21 sweep points took 2.3 GB). At most this many
// parameters × (points + 1) × outputs: about 100 MB kept, seed 001's every parameter at 1001 points.
inline constexpr uint64_t kMaxSweepValues = 10'000'000;
inline constexpr size_t kMaxBootstrap = 10'000;
inline constexpr uint64_t kMaxSobolSamples = uint64_t{1} << 24;
inline constexpr double kMaxSobolBytes = 1 << 30;    // the evaluations Sobol's estimators keep: 8·N·(G + 2)·outputs
inline constexpr size_t kMaxLinearOutputs = 4000;     // linear propagation keeps an outputs² covariance

// The chain as selected on the command line.
struct ChainRequest {
  std::string chain;                // path as given (resolved against the working directory)
  std::vector<std::string> only;    // source keys; InputError with a suggestion for unknown keys
  std::vector<std::string> without;
  std::optional<uint64_t> samples;  // override the file's
  std::optional<uint64_t> seed;
  unsigned threads = 0;
};

// Reads the chain and applies only/without (refused: an unknown key, a source in both).
ChainModel LoadChain(const ChainRequest& request);

struct ErrSimDocument {
  OrderedJson json;  // the output file
  std::string text;      // the summary for stderr (empty for a shard)
  bool compact = false;  // write it on one line (a shard file: a machine's, whose size matters)

  // The file's text: indented (DumpJson), or on one line when compact.
  std::string Text() const;
};

struct RunRequest {
  ChainRequest chain;
  bool budget = true;
  std::optional<uint64_t> budget_samples;  // default: the run's samples; refused with budget = false
  uint64_t shard = 0, shards = 1;          // shards > 1: write a shard file for `merge`
};
// DegenerateError (exit code 3) when every sample of some test point is undefined (the message
// names the point and why its first sample is).
ErrSimDocument RunErrSim(const RunRequest& request, const Provenance& provenance, const Progress& progress = {});

ErrSimDocument MergeErrSim(const std::string& chain, const std::vector<std::string>& shard_files, const Provenance& provenance);

struct SweepRequest {
  ChainRequest chain;
  std::vector<std::string> parameters;  // names (empty: every non-constant parameter)
  size_t points = 21;
  std::optional<double> lo, hi;  // sweep range in the parameter's file unit (one parameter only)
};
ErrSimDocument SweepErrSim(const SweepRequest& request, const Provenance& provenance);

struct SobolRequest {
  ChainRequest chain;
  std::string sampling = "sobol";  // or "pseudo-random"
  size_t bootstrap = 200;
};
ErrSimDocument SobolErrSim(const SobolRequest& request, const Provenance& provenance);

ErrSimDocument LinearErrSim(const ChainRequest& request, const Provenance& provenance);

// The chain in the canonical vst-chain@1 layout (formats/chain_writer.h), to be written to `output`
// (camera file references are rebased onto its folder), with what err-sim makes of it on stderr:
// a fixed point of read → write.
ErrSimDocument NormalizeErrSim(const std::string& chain, const std::string& output, const Provenance& provenance);

}  // namespace vstcal::app
