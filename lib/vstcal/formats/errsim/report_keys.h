// Where err-sim's per-point measures (errsim/outputs.h, kMeasures) sit in a vstcal/err-sim-report@3
// file (docs/formats.md#err-sim-report), derived from the table: the writer (report_format.cc)
// puts them there and the pages (pages/errsim_*.cc) read them there, so no key is spelled twice.
#pragma once

#include <string>

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

}  // namespace vstcal
