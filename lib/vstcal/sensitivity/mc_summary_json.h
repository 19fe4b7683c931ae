// A Monte Carlo summary as JSON, format "vstcal/mc-summary@1": the partial state of one shard (or
// a whole run), written so that reading it back and merging gives the same bits as never having
// written it (doubles in shortest round-trip form, docs/conventions.md#numbers-in-files).
//
//   {"format": "vstcal/mc-summary@1", "run_id", "total_samples", "block_size",
//    "histogram": {"min_magnitude", "max_magnitude", "bins_per_decade"}, "outputs": [names],
//    "undefined_samples", "folded_blocks": p,
//    "folded": [moments per output],                 (blocks [0, p) folded in order)
//    "pending": [{"block": b, "moments": [moments per output]}],
//    "histograms": [[[bin, count], ...] per output]}  (non-empty bins only)
//   moments = [count, mean, m2, m3, m4, min, max]; an empty one is [0, 0, 0, 0, 0, 0, 0].
#pragma once

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/sensitivity/mc_summary.h"

namespace vstcal::sensitivity {

inline constexpr const char* kSummaryFormat = "vstcal/mc-summary@1";

io::OrderedJson SummaryToJson(const MonteCarloSummary& summary);
// InputError "<file>: <field>: <what>; <fix>" for anything malformed or inconsistent.
MonteCarloSummary SummaryFromJson(const io::JsonNode& root);

}  // namespace vstcal::sensitivity
