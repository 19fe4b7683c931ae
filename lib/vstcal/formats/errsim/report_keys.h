// Where err-sim's outputs (errsim/outputs.h: kMeasures, kTotals) sit in its files
// (docs/formats.md#err-sim-report, #err-sim-sweep), derived from the tables: the writers
// (report_format.cc, sensitivity_format.cc) put them there and the pages (pages/errsim_*.cc) read
// them there, so no key is spelled twice.
#pragma once

#include <string>
#include <string_view>

#include "vstcal/errsim/outputs.h"
#include "vstcal/json/json_pointer.h"

namespace vstcal {

// The formats of err-sim's files: run and merge write the report, sweep, sobol and linear the
// sensitivity files (formats/errsim/sensitivity_format.h).
inline constexpr std::string_view kReportFormat = "vstcal/err-sim-report@3";
// The version before the budget's shares became shares of the whole: its per-point statistics,
// all err-sim check reads, are the same.
inline constexpr std::string_view kReportFormatV2 = "vstcal/err-sim-report@2";
inline constexpr std::string_view kSweepFormat = "vstcal/err-sim-sweep@2";
inline constexpr std::string_view kSobolFormat = "vstcal/err-sim-sobol@2";
inline constexpr std::string_view kLinearFormat = "vstcal/err-sim-linear@2";

// The JSON pointer, relative to a test point (no leading '/'), of measure m's statistics (of
// `eye`): <group>[/<eye>]/<name> — "image/left/pixel_px", "misregistration/linear". A decision's
// statistic is a rate object {<name>_rate, standard_error} at <group>[/<eye>] — "occlusion/left".
inline std::string MeasurePointer(ErrorMeasure m, int eye = 0) {
  const MeasureDecl& d = Declaration(m);
  std::string pointer(d.group);
  if (d.scope == OutputScope::kPerEye) pointer.append("/").append(kEyeNames[eye]);
  if (d.unit != OutputUnit::kDecision) pointer.append("/").append(d.name);
  return pointer;
}

// The key of a decision's rate in its rate object: "<name>_rate" ("wrong_rate").
inline std::string RateKey(ErrorMeasure m) { return std::string(Declaration(m).name).append(kRateSuffix); }

// A total's key ("image_rms_px"), and the key of a budget row's share of its measure's mean square
// ("share_of_image_ms").
inline std::string TotalKey(Total t) { return std::string(Declaration(t).key); }
inline std::string ShareKey(Total t) { return std::string("share_of_").append(Declaration(t).measure).append("_ms"); }
// The budget's name of a total's measure ("image"): its key under "whole", "ranking", "dominant_term".
inline std::string BudgetMeasureKey(Total t) { return std::string(Declaration(t).measure); }
// Under "totals" beside kTotals: the error-free chain's misperception (errsim/budget.h).
inline constexpr std::string_view kSystematicMisperceptionKey = "systematic_misperception_rms";

// err-sim's files' own keys, beside the outputs' above (docs/formats.md#err-sim-report,
// #err-sim-sensitivity): the writers (report_format.cc, sensitivity_format.cc) put them there and
// the readers (report_reader.cc, pages/errsim_*.cc) find them there.
namespace errsim_key {
// Every file's header (format, chain, chain_digest, length_unit; the run report keeps only and
// without under sources, the sensitivity files at the top) and the run report's document.
inline constexpr char kFormat[] = "format";
inline constexpr char kChain[] = "chain";
inline constexpr char kChainDigest[] = "chain_digest";
inline constexpr char kLengthUnit[] = "length_unit";
inline constexpr char kSamples[] = "samples";  // also the budget's samples a scenario, and a point's undefined samples
inline constexpr char kBudgetSamples[] = "budget_samples";
inline constexpr char kSeed[] = "seed";
inline constexpr char kSources[] = "sources";  // {active, only, without}: source keys
inline constexpr char kActive[] = "active";
inline constexpr char kOnly[] = "only";
inline constexpr char kWithout[] = "without";
inline constexpr char kUndefinedSamples[] = "undefined_samples";
inline constexpr char kTestPoints[] = "test_points";
inline constexpr char kTotals[] = "totals";  // kTotals' keys and kSystematicMisperceptionKey
inline constexpr char kBudget[] = "budget";  // null when no budget was asked for
inline constexpr char kProvenance[] = "provenance";
// A test point: its name, where it is, its undefined samples {samples, rate}, and its measures at
// MeasurePointer; the misperception's group starts with the systematic part {offset, <terms>},
// the occlusion's with its surface_behind.
inline constexpr char kName[] = "name";
inline constexpr char kWorld[] = "world";
inline constexpr char kUndefined[] = "undefined";
inline constexpr char kRate[] = "rate";
inline constexpr char kSystematic[] = "systematic";
inline constexpr char kOffset[] = "offset";
inline constexpr char kSurfaceBehind[] = "surface_behind";
// A measure's statistics object (null with no defined sample); the percentiles only for a headline
// measure. A decision's rate object is {RateKey, standard_error}.
inline constexpr char kMean[] = "mean";
inline constexpr char kRms[] = "rms";
inline constexpr char kStandardDeviation[] = "standard_deviation";
inline constexpr char kMeanStandardError[] = "mean_standard_error";
inline constexpr char kMax[] = "max";
inline constexpr char kP50[] = "p50";
inline constexpr char kP95[] = "p95";
inline constexpr char kP99[] = "p99";
inline constexpr char kPercentilesOutOfRange[] = "percentiles_out_of_range";
inline constexpr char kStandardError[] = "standard_error";
// The budget: {samples, whole, ranked_by, ranking, entries}. whole and ranking are keyed by
// BudgetMeasureKey; an entry is {source, ShareKey…, alone, halved, correction, terms, dominant_term,
// origin}, a term {term, ShareKey…, alone, origin}; alone and halved hold kTotals' keys.
inline constexpr char kWhole[] = "whole";
inline constexpr char kMeanSquare[] = "mean_square";
inline constexpr char kPartsMeanSquare[] = "parts_mean_square";
inline constexpr char kRemainderMeanSquare[] = "remainder_mean_square";
inline constexpr char kRemainderShare[] = "remainder_share";
inline constexpr char kNone[] = "none";
inline constexpr char kRankedBy[] = "ranked_by";
inline constexpr char kRanking[] = "ranking";
inline constexpr char kEntries[] = "entries";
inline constexpr char kSource[] = "source";
inline constexpr char kAlone[] = "alone";
inline constexpr char kHalved[] = "halved";
inline constexpr char kCorrection[] = "correction";
inline constexpr char kTerms[] = "terms";
inline constexpr char kTerm[] = "term";
inline constexpr char kDominantTerm[] = "dominant_term";
// Where a distribution came from: [{kind: "measured", file, format} | {kind: "assumed"}, …].
inline constexpr char kOrigin[] = "origin";
inline constexpr char kKind[] = "kind";
inline constexpr char kMeasured[] = "measured";
inline constexpr char kAssumed[] = "assumed";
inline constexpr char kFile[] = "file";
inline constexpr char kOriginFormat[] = "format";
// The sensitivity files. sweep: outputs (the vector outputs' names), parameters [{name, source,
// unit, values, kTotals' keys…, slope_per_unit}]. sobol: samples, sampling, seed, evaluations,
// groups, outputs [{name, mean, variance, indices {<group>: {first, total}}}], an index
// {value, standard_error, interval [lo, hi]}. linear: samples, seed, derivatives,
// undefined_samples, outputs [{name, linear_mean, …, linear_sigma_by_source}], disagreements.
inline constexpr char kOutputs[] = "outputs";
inline constexpr char kParameters[] = "parameters";
inline constexpr char kUnit[] = "unit";
inline constexpr char kValues[] = "values";
inline constexpr char kSlopePerUnit[] = "slope_per_unit";
inline constexpr char kSampling[] = "sampling";
inline constexpr char kEvaluations[] = "evaluations";
inline constexpr char kGroups[] = "groups";
inline constexpr char kVariance[] = "variance";
inline constexpr char kIndices[] = "indices";
inline constexpr char kFirst[] = "first";
inline constexpr char kTotal[] = "total";
inline constexpr char kValue[] = "value";
inline constexpr char kInterval[] = "interval";
inline constexpr char kDerivatives[] = "derivatives";
inline constexpr char kLinearMean[] = "linear_mean";
inline constexpr char kMonteCarloMean[] = "monte_carlo_mean";
inline constexpr char kLinearSigma[] = "linear_sigma";
inline constexpr char kMonteCarloSigma[] = "monte_carlo_sigma";
inline constexpr char kSigmaStandardError[] = "sigma_standard_error";
inline constexpr char kSigmaRelativeDifference[] = "sigma_relative_difference";
inline constexpr char kMeanDisagrees[] = "mean_disagrees";
inline constexpr char kSigmaDisagrees[] = "sigma_disagrees";
inline constexpr char kLinearSigmaBySource[] = "linear_sigma_by_source";
inline constexpr char kDisagreements[] = "disagreements";
}  // namespace errsim_key

}  // namespace vstcal
