// A Monte Carlo summary as JSON, format "vstcal/mc-summary@2": the partial state of one shard (or
// a whole run), written so that reading it back and merging gives the same bits as never having
// written it (doubles in shortest round-trip form, docs/conventions.md#numbers-in-files).
//
//   {"format": "vstcal/mc-summary@2", "run_id", "total_samples", "block_size",
//    "histogram": {"min_exponent", "max_exponent", "sub_bins_log2"}, "outputs": [names],
//    "percentile_outputs": [indices] or "all", "higher_moments": whether M₃, M₄ are kept,
//    "undefined_samples",
//    "nodes": [[level, index, [moments per output]], …],    (the block tree's nodes, mc_summary.h)
//    "histograms": [[[first_bin, count, count, …], …] per histogram]}  (runs of non-empty bins)
//   moments = [count, mean, m2, m3, m4, min, max] ([count, mean, m2, min, max] without the higher
//   moments); an empty one is [0].
#pragma once

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/sensitivity/mc_summary.h"

namespace vstcal {

inline constexpr const char* kSummaryFormat = "vstcal/mc-summary@2";

OrderedJson SummaryToJson(const MonteCarloSummary& summary);
// InputError "<file>: <field>: <what>; <fix>" for anything malformed or inconsistent.
MonteCarloSummary SummaryFromJson(const JsonNode& root);

}  // namespace vstcal
