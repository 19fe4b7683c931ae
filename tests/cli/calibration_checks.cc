#include "calibration_checks.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

namespace vstcal::cli_test {

std::vector<std::string> DistortedVolumeArgs() {
  std::vector<std::string> args = DefaultSynthArgs();
  for (const auto& [flag, value] :
       std::vector<std::pair<std::string, std::string>>{{"--grid", "9x7"},
                                                        {"--spacing", "60"},
                                                        {"--interval", "100"},
                                                        {"--camera-distance", "900"},
                                                        {"--tilt-deg", "15"},
                                                        {"--noise", "0.5"},
                                                        {"--distortion", "-0.15,0.05,0,0,0"}}) {
    args = Override(args, flag, value);
  }
  return args;
}

std::vector<std::string> PlanarArgs() {
  return {"--rig",      "planar-views", "--image-size", "640x480", "--fx",         "600",
          "--grid",     "9x7",          "--spacing",    "30",      "--views",      "8",
          "--distance", "500",          "--noise",      "0.5",     "--distortion", "-0.15,0.05,0,0,0"};
}

double LensParameter(const Json& camera, const std::string& name) {
  const Json& K = camera.at("K");
  if (name == "fx") return K.at(0).at(0).get<double>();
  if (name == "fy") return K.at(1).at(1).get<double>();
  if (name == "cx") return K.at(0).at(2).get<double>();
  if (name == "cy") return K.at(1).at(2).get<double>();
  if (name == "s") return K.at(0).at(1).get<double>();
  const Json& d = camera.at("distortion");
  return d.contains(name) ? d.at(name).get<double>() : 0.0;
}

std::optional<size_t> CovarianceIndex(const Json& camera, const std::string& name) {
  const Json& names = camera.at("covariance").at("parameters");
  for (size_t i = 0; i < names.size(); ++i) {
    if (names.at(i) == name) return i;
  }
  return std::nullopt;
}

double Sigma(const Json& camera, const std::string& name) {
  if (const auto i = CovarianceIndex(camera, name)) {
    return std::sqrt(camera.at("covariance").at("matrix").at(*i).at(*i).get<double>());
  }
  // A pose tangent "<pose>.<axis>" of a pose block (planar views).
  const size_t dot = name.rfind('.');
  const std::vector<std::string> axes = {"rx", "ry", "rz", "tx", "ty", "tz"};
  const auto axis = std::find(axes.begin(), axes.end(), name.substr(dot + 1));
  if (dot != std::string::npos && axis != axes.end() && camera.at("covariance").contains("poses")) {
    for (const Json& block : camera.at("covariance").at("poses")) {
      if (block.at("pose") != name.substr(0, dot)) continue;
      const size_t k = static_cast<size_t>(axis - axes.begin());
      return std::sqrt(block.at("matrix").at(k).at(k).get<double>());
    }
  }
  ADD_FAILURE() << "the covariance does not name " << name;
  return std::nan("");
}

::testing::AssertionResult CovarianceIsWellFormed(const Json& camera) {
  if (!camera.contains("covariance")) return ::testing::AssertionFailure() << "no \"covariance\" block";
  const Json& names = camera.at("covariance").at("parameters");
  const Json& m = camera.at("covariance").at("matrix");
  const size_t n = names.size();
  if (n == 0) return ::testing::AssertionFailure() << "no parameters";
  std::set<std::string> unique;
  for (const Json& name : names) unique.insert(name.get<std::string>());
  if (unique.size() != n) return ::testing::AssertionFailure() << "repeated parameter names: " << names.dump();
  if (m.size() != n) return ::testing::AssertionFailure() << m.size() << " rows for " << n << " parameters";
  for (size_t r = 0; r < n; ++r) {
    if (m.at(r).size() != n)
      return ::testing::AssertionFailure() << "row " << r << " has " << m.at(r).size() << " entries";
  }
  for (size_t r = 0; r < n; ++r) {
    const double vr = m.at(r).at(r).get<double>();
    if (!(vr > 0)) return ::testing::AssertionFailure() << "variance of " << names.at(r) << " is " << vr;
    for (size_t c = 0; c < r; ++c) {
      const double a = m.at(r).at(c).get<double>(), b = m.at(c).at(r).get<double>();
      if (a != b)
        return ::testing::AssertionFailure() << "not symmetric at (" << r << ", " << c << "): " << a << " vs " << b;
      const double correlation = a / std::sqrt(vr * m.at(c).at(c).get<double>());
      if (!(std::abs(correlation) <= 1.0 + 1e-12)) {
        return ::testing::AssertionFailure()
               << "correlation of " << names.at(r) << " and " << names.at(c) << " is " << correlation;
      }
    }
  }
  // Pose blocks (planar views): a 6×6 covariance each, and 6 rows of covariances with the named
  // parameters, within [−1, 1] as correlations.
  if (!camera.at("covariance").contains("poses")) return ::testing::AssertionSuccess();
  for (const Json& block : camera.at("covariance").at("poses")) {
    const Json& p = block.at("matrix");
    const Json& w = block.at("with_parameters");
    if (p.size() != 6 || w.size() != 6) return ::testing::AssertionFailure() << block.at("pose") << ": not 6 rows";
    for (size_t r = 0; r < 6; ++r) {
      const double vr = p.at(r).at(r).get<double>();
      if (!(vr > 0)) return ::testing::AssertionFailure() << block.at("pose") << ": variance " << r << " is " << vr;
      for (size_t c = 0; c < r; ++c) {
        if (p.at(r).at(c) != p.at(c).at(r)) return ::testing::AssertionFailure() << block.at("pose") << ": not symmetric";
      }
      if (w.at(r).size() != n) return ::testing::AssertionFailure() << block.at("pose") << ": with_parameters row " << r;
      for (size_t c = 0; c < n; ++c) {
        const double correlation = w.at(r).at(c).get<double>() / std::sqrt(vr * m.at(c).at(c).get<double>());
        if (!(std::abs(correlation) <= 1.0 + 1e-12)) {
          return ::testing::AssertionFailure() << block.at("pose") << " and " << names.at(c) << ": correlation " << correlation;
        }
      }
    }
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult WithinSigmas(const Json& estimate, const Json& truth, const std::vector<std::string>& names,
                                        double k) {
  auto failure = ::testing::AssertionFailure();
  bool ok = true;
  for (const std::string& name : names) {
    const double error = LensParameter(estimate, name) - LensParameter(truth, name);
    const double sigma = Sigma(estimate, name);
    if (!(std::abs(error) < k * sigma)) {
      ok = false;
      failure << name << ": error " << error << " = " << error / sigma << " sigma (sigma " << sigma << ")\n";
    }
  }
  if (ok) return ::testing::AssertionSuccess();
  return failure;
}

double RotationDifferenceDeg(const Json& a, const Json& b) {
  Eigen::Matrix3d Ra, Rb;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      Ra(r, c) = a.at("R").at(r).at(c).get<double>();
      Rb(r, c) = b.at("R").at(r).at(c).get<double>();
    }
  }
  return Eigen::AngleAxisd(Ra.transpose() * Rb).angle() * 180.0 / M_PI;
}

}  // namespace vstcal::cli_test
