#include "vstcal/formats/calib/dlt_io.h"

namespace vstcal {

std::string_view DltSolverName(DltOptions::Solver solver) {
  return NameOf(DltOptions::kSolverNames, solver);
}

OrderedJson DltDiagnosticsToJson(const DltResult& d, const std::optional<Eq13Decomposition>& eq13,
                                 const DltOptions& options) {
  OrderedJson j;
  j["solver"] = DltSolverName(options.solver);
  j["normalized_system"] = {{"sigma_11", d.sigma_11}, {"sigma_12", d.sigma_12}, {"frobenius_norm", d.frobenius},
                            {"conditioning", d.conditioning}};
  j["normalized_extents"] = d.extents;
  j["thresholds"] = {{"min_extent_ratio", options.min_extent_ratio},
                     {"warn_extent_ratio", options.warn_extent_ratio},
                     {"min_conditioning", options.min_conditioning}};
  if (eq13) {
    const SkewForm& f = eq13->intrinsics;
    j["seed001_eq13"] = {{"rho", eq13->rho}, {"fu", f.fu}, {"fv", f.fv}, {"u0", f.u0}, {"v0", f.v0},
                         {"skew_angle_deg", RadToDeg(f.theta_rad)}};
  }
  return j;
}

}  // namespace vstcal
