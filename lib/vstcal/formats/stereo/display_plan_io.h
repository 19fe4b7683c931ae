// vstcal/stereo-plan@1: the output of `calib-stereo plan` (docs/formats.md#stereo-plan).
#pragma once

#include "vstcal/core/units.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/stereo/display_plan.h"

namespace vstcal {

OrderedJson DisplayPlanToJson(const DisplayPlanInput& input, const DisplayPlan& plan, LengthUnit unit,
                              const Provenance& provenance);

}  // namespace vstcal
