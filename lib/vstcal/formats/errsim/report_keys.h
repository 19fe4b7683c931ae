// Where err-sim's outputs (errsim/outputs.h: kMeasures, kTotals) sit in its files
// (docs/formats.md#err-sim-report, #err-sim-sweep), derived from the tables: the writers
// (report_format.cc, sensitivity_format.cc) put them there and the pages (pages/errsim_*.cc) read
// them there, so no key is spelled twice.
#pragma once

#include <string>
#include <string_view>

#include "vstcal/errsim/outputs.h"

namespace vstcal {

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
inline std::string RateKey(ErrorMeasure m) { return std::string(Declaration(m).name).append("_rate"); }

// A total's key ("image_rms_px"), and the key of a budget row's share of its measure's mean square
// ("share_of_image_ms").
inline std::string TotalKey(Total t) { return std::string(Declaration(t).key); }
inline std::string ShareKey(Total t) { return std::string("share_of_").append(Declaration(t).measure).append("_ms"); }
// The budget's name of a total's measure ("image"): its key under "whole", "ranking", "dominant_term".
inline std::string BudgetMeasureKey(Total t) { return std::string(Declaration(t).measure); }
// Under "totals" beside kTotals: the error-free chain's misperception (errsim/budget.h).
inline constexpr std::string_view kSystematicMisperceptionKey = "systematic_misperception_rms";

}  // namespace vstcal
