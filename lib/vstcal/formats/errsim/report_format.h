// vstcal/err-sim-report@3 (docs/formats.md#err-sim-report): the report of a complete run — per test
// point and eye the image misregistration, the 3-D misregistration and the misperception with the
// systematic part on its own, the occlusion decisions, and the error budget ranked for each
// measure — as JSON and as the text summary err-sim prints. Every statistic of no defined sample
// is null; no non-finite number is ever written.
#pragma once

#include <string>
#include <string_view>

#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/formats/errsim/report_keys.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {


OrderedJson ReportToJson(const ChainEvaluator& chain, const SimulationResult& result, const RunDescription& run,
                             const Provenance& provenance);
std::string ReportText(const ChainEvaluator& chain, const SimulationResult& result, const RunDescription& run);

}  // namespace vstcal
