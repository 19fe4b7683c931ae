// err-sim's totals and error budget (docs/math/vst-chain.md#budget): per scenario the RMS of the
// image misregistration, of the 3-D misregistration and of the misperception (relative to the
// error-free chain's systematic one); per active source its contribution alone, the whole chain
// with it halved, and its share of each mean square, ranked for each measure (by default by the
// image misregistration: what the user sees).
#pragma once

#include <string>
#include <vector>

#include "vstcal/errsim/chain_model.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/sensitivity/mc_summary.h"

namespace vstcal {

// Aggregates of one scenario; NaN (null in files) where undefined: a test point without a defined
// sample, or no occlusion points.
struct ScenarioTotals {
  double image_rms_px;          // √(mean over test points and eyes of RMS(|q̂ − q|)²)
  double misregistration_rms;   // √(mean over test points of RMS(misregistration linear)²)
  double misperception_rms;     // the same for the misperception, relative to the systematic one
  double wrong_occlusion_rate;  // mean over occlusion points and eyes
};
// `summary` holds the outputs of ErrorOutputs(model, set).
ScenarioTotals Totals(const ChainModel& model, const MonteCarloSummary& summary, OutputSet set);

// √(mean over test points of the systematic misperception's linear term²).
double SystematicMisperceptionRms(const ChainEvaluator& chain);

// One term of a source alone (simulation.h's TermGroup), its shares of the whole chain's mean
// square. The terms of a source need not add to the source's part: what they leave out is the
// interaction and the means in common within the source.
struct TermPart {
  std::string name;  // "display.screen_shift"
  ScenarioTotals alone;
  double share_of_image_ms = 0, share_of_misregistration_ms = 0, share_of_misperception_ms = 0;
  std::vector<DistributionOrigin> origins = {};  // where its distributions came from (OriginsOf)
};

struct BudgetEntry {
  Source source;
  ScenarioTotals alone, halved;
  std::vector<TermPart> terms;  // in kTerms order; one when the source has one active term
  // Its alone mean square over the whole chain's (docs/math/sensitivity.md#shares-of-the-whole).
  // NaN where some total is undefined or the whole is zero to rounding.
  double share_of_image_ms = 0;
  double share_of_misregistration_ms = 0;
  double share_of_misperception_ms = 0;
  std::vector<DistributionOrigin> origins = {};  // of all its terms
};

// One measure's whole: the whole chain's mean square, the sum of the sources' alone mean squares,
// and what they leave out — the remainder, whole − Σ parts: for independent sources and a chain
// linear to first order Σ_{i≠j} μ_i·μ_j (means in common), plus the interactions of a nonlinear
// chain. The shares and the remainder's share add to 1.
struct WholeOfMeasure {
  double mean_square = 0;        // of the "all" scenario
  double parts_mean_square = 0;  // Σ over sources of the alone mean square
  double remainder_mean_square = 0;
  double remainder_share = 0;    // NaN when undefined or none
  // The whole is zero to rounding (≤ 1e-9 of the measure's scale, squared): no shares, "none".
  bool none = false;
};

struct ErrorBudget {
  WholeOfMeasure image, misregistration, misperception;
  std::vector<BudgetEntry> entries;            // in source order
  std::vector<size_t> by_misregistration;      // entry indices, largest share first (ties: image share)
  std::vector<size_t> by_misperception;        // entry indices, largest share first
  // The default ranking (issue 21 item 3): by what the user sees, the image misregistration's
  // share (ties: the 3-D share); the 3-D and misperception rankings stand beside it.
  std::vector<size_t> by_image;
};
ErrorBudget Budget(const ChainModel& model, const SimulationResult& result);

// The index of the term of `e` with the largest share by `share` (the first on ties, NaN last).
size_t DominantTerm(const BudgetEntry& e, double TermPart::*share);

}  // namespace vstcal
