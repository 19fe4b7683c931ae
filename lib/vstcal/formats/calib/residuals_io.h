// vstcal/residuals@1: per-point residuals of a fit, for plots and reports (docs/formats.md).
#pragma once

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/fit.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"

namespace vstcal {

// Each view's points as [X, Y, Z, u, v, du, dv] with (du, dv) = predicted − measured (null
// when the point projects behind the camera), plus the test points.
OrderedJson ResidualsToJson(const Correspondences& c, const Fit& fit, const Provenance& provenance);

}  // namespace vstcal
