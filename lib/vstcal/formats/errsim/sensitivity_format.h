// vstcal/err-sim-sweep@2, -sobol@2 and -linear@2 (docs/formats.md#err-sim-sensitivity): the outputs
// of `err-sim sweep`, `sobol` and `linear`, as JSON and as the text summaries err-sim prints. Every
// file starts with format, chain, chain_digest, length_unit, only, without and ends with
// provenance; no non-finite number is written (null instead).
#pragma once

#include <string>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/sensitivity/linear_propagation.h"
#include "vstcal/sensitivity/oat_sweep.h"
#include "vstcal/sensitivity/sobol_indices.h"

namespace vstcal {

struct TextAndJson {
  OrderedJson json;
  std::string text;
};

// One swept parameter: θ's slot index and the sweep over VectorModel's outputs (internal units).
struct ParameterSweep {
  size_t parameter;
  SweepResult result;
};
TextAndJson SweepOutput(const ChainModel& model, const RunDescription& run, const std::vector<ParameterSweep>& sweeps,
                        const Provenance& provenance);

TextAndJson SobolOutput(const ChainModel& model, const RunDescription& run, const std::string& sampling,
                        const SobolResult& result, const Provenance& provenance);

TextAndJson LinearOutput(const ChainModel& model, const RunDescription& run, const LinearPropagation& linear,
                         const MonteCarloSummary& monte_carlo, const Provenance& provenance);

}  // namespace vstcal
