#include "vstcal/formats/calib/dlt_io.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vstcal/core/error.h"

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

OrderedJson DltUncertaintyToJson(const DltUncertainty& u, const ParameterCovariance& covariance,
                                 const Rigid3d& camera_from_world) {
  const auto sigma = [&](const std::string& name) {
    const auto i = covariance.Find(name);
    VSTCAL_CHECK(i.has_value(), "the DLT covariance names every decomposed parameter");
    const auto k = static_cast<Eigen::Index>(*i);
    return std::sqrt(std::max(0.0, covariance.matrix(k, k)));
  };
  const Eigen::Matrix3d centre = CameraCentreCovariance(covariance, camera_from_world);
  OrderedJson j;
  j["sigma_px"] = u.sigma_px;
  j["dof"] = u.dof;
  j["sigma_from"] = "the DLT camera's reprojection residuals, over 2N - 11 degrees of freedom";
  j["P_covariance"] = {{"order", "P row-major: P[0][0], P[0][1], ..., P[2][3]"},
                       {"gauge", "|P[2][0:3]| = 1, positive depth (rank 11: no variance across the gauge)"},
                       {"matrix", MatrixToJson(u.P_covariance)}};
  j["sigma"] = {{"fx", sigma("fx")},
                {"fy", sigma("fy")},
                {"cx", sigma("cx")},
                {"cy", sigma("cy")},
                {"s", sigma("s")},
                {"rotation_deg", {RadToDeg(sigma("camera_from_world.rx")), RadToDeg(sigma("camera_from_world.ry")),
                                  RadToDeg(sigma("camera_from_world.rz"))}},
                {"camera_centre", {std::sqrt(centre(0, 0)), std::sqrt(centre(1, 1)), std::sqrt(centre(2, 2))}}};
  return j;
}

}  // namespace vstcal
