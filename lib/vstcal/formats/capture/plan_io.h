// The capture plan's files: vstcal/capture-plan@1 (docs/formats.md#capture-plan) and its text
// form (--format text).
#pragma once

#include <string>

#include "vstcal/capture/plan.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

OrderedJson CapturePlanToJson(const CapturePlan& plan, const Provenance& provenance);
std::string CapturePlanText(const CapturePlan& plan);

}  // namespace vstcal
