// CLI tests of calib-tsai: Tsai's two-stage method on volumes (non-coplanar and coplanar), Zhang's
// method on planar views, the maximum-likelihood refinement with its covariance, outliers and
// projection uncertainty — checked against calib-synth's truth within the σ the tool reports —
// and every bad input or flag: its documented exit code, one line naming what is wrong, and no
// output file.
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <ostream>
#include <sstream>

#include "calibration_checks.h"
#include "cli_fixture.h"
#include "vstcal/random/philox.h"

namespace vstcal::cli_test {
namespace {

constexpr std::string_view kTool = "calib-tsai";

// One plane of DistortedVolumeArgs(), tilted 30° (coplanar data).
std::vector<std::string> PlaneArgs() {
  return Override(Override(DistortedVolumeArgs(), "--far", "0"), "--tilt-deg", "30");
}

// Keeps the first n items of a JSON array.
void Truncate(Json& array, size_t n) {
  Json kept = Json::array();
  for (size_t i = 0; i < n; ++i) kept.push_back(array.at(i));
  array = std::move(kept);
}

const std::vector<std::string> kIntrinsics = {"fx", "fy", "cx", "cy"};
const std::vector<std::string> kDefaultTerms = {"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"};

class CliCalibTsai : public CliTest {
 protected:
  // Runs calib-tsai CORNERS -o out/camera.json [args]; the run must succeed. Returns the camera.
  Json Calibrate(const std::string& corners, std::vector<std::string> args = {}) {
    args.insert(args.begin(), {corners, "-o", "out/camera.json"});
    last_ = Run(kTool, args);
    EXPECT_EQ(last_.exit_code, kOk) << last_.err;
    EXPECT_EQ(last_.out, "");
    if (last_.exit_code != kOk) throw std::runtime_error("calib-tsai failed: " + last_.err);
    return ReadJson("out/camera.json");
  }

  CommandResult last_;
};

// ---------------------------------------------------------------------------------------------
// The summary shows every lens parameter ± σ, the held ones with their reason, and the worst views
// (issue 24): each figure read back against the camera file the same run wrote.

TEST_F(CliCalibTsai, SummaryListsEveryParameterWithItsSigmaAndTheWorstViews) {
  Synth("in/views.json", PlanarArgs());
  const Json camera = Calibrate("in/views.json");
  const Json& K = camera.at("K");
  const std::map<std::string, double> values = {
      {"fx", K[0][0]}, {"fy", K[1][1]}, {"cx", K[0][2]}, {"cy", K[1][2]},
      {"k1", camera.at("distortion").at("k1")}, {"k2", camera.at("distortion").at("k2")},
      {"p1", camera.at("distortion").at("p1")}, {"p2", camera.at("distortion").at("p2")}};
  std::map<std::string, std::string> lines;  // parameter → the rest of its summary line
  std::istringstream err(last_.err);
  for (std::string line; std::getline(err, line);) {
    std::istringstream words(line);
    std::string first;
    words >> first;
    std::string rest;
    std::getline(words, rest);
    lines[first] = rest;
  }
  for (const auto& [name, value] : values) {
    ASSERT_TRUE(lines.count(name)) << name << " missing from:\n" << last_.err;
    std::istringstream words(lines[name]);
    double estimate = 0, sigma = 0;
    words >> estimate >> sigma;
    EXPECT_NEAR(estimate, value, 1e-7 * std::max(1.0, std::abs(value))) << name;
    EXPECT_NEAR(sigma, Sigma(camera, name), 1e-3 * Sigma(camera, name)) << name;
    EXPECT_NE(lines[name].find('['), std::string::npos) << name << ": no 3-sigma interval";
  }
  EXPECT_NE(lines["s"].find("held: "), std::string::npos) << lines["s"];
  EXPECT_NE(lines["k3"].find("held: "), std::string::npos) << lines["k3"];
  // The worst view by RMS in the file comes first.
  const Json& views = camera.at("fit").at("views");
  size_t worst = 0;
  for (size_t v = 1; v < views.size(); ++v) {
    if (views[v].at("rms_px").get<double>() > views[worst].at("rms_px").get<double>()) worst = v;
  }
  const std::string prefix = "  worst views by RMS: " + views[worst].at("name").get<std::string>() + " ";
  EXPECT_NE(last_.err.find(prefix), std::string::npos) << last_.err;
}

// ---------------------------------------------------------------------------------------------
// Volumes: Tsai's method, then the refinement.

TEST_F(CliCalibTsai, VolumeIsNonCoplanarAndRefinedToTheTruthWithinFiveSigma) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json camera = Calibrate("in/volume.json");
  const Json truth = ReadJson("in/volume.truth.json");
  EXPECT_EQ(camera.at("format"), "vstcal/camera@1");
  EXPECT_EQ(camera.at("method"), "tsai+refine");
  EXPECT_EQ(camera.at("tsai").at("variant"), "non-coplanar");
  EXPECT_EQ(camera.at("refinement").at("status"), "converged");
  EXPECT_EQ(camera.at("refinement").at("free_intrinsics"), Json(kDefaultTerms));
  EXPECT_EQ(camera.at("distortion").at("model"), "radial-tangential");
  // k3 is not estimated by default: zero, not Tsai's κ₁ conversion frozen (tsai.conversion.k3).
  EXPECT_EQ(camera.at("distortion").at("k3"), 0.0);
  EXPECT_NE(camera.at("tsai").at("conversion").at("k3"), 0.0);
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  EXPECT_TRUE(WithinSigmas(camera, truth, kDefaultTerms, 5));
  // σ̂ estimates the pixel noise: its relative standard deviation is 1/√(2 dof).
  const double dof = camera.at("refinement").at("dof").get<double>();
  EXPECT_EQ(dof, 2 * 315 - 14);
  EXPECT_NEAR(camera.at("refinement").at("sigma_px").get<double>(), kVolumeNoisePx,
              5 * kVolumeNoisePx / std::sqrt(2 * dof));
  // The pose too: the rotation error within 5σ of the largest rotation-tangent σ (radians).
  double sigma_rot = 0;
  for (const char* axis : {"rx", "ry", "rz"})
    sigma_rot = std::max(sigma_rot, Sigma(camera, std::string("camera_from_world.") + axis));
  EXPECT_LT(RotationDifferenceDeg(camera.at("camera_from_world"), truth.at("camera_from_world")),
            5 * std::sqrt(3.0) * sigma_rot * 180 / M_PI);
  EXPECT_TRUE(camera.at("refinement").at("outliers").empty());
  EXPECT_NE(last_.err.find("calib-tsai: in/volume.json: 315 points in 5 views, method tsai+refine"), std::string::npos)
      << last_.err;
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
}

TEST_F(CliCalibTsai, NonCoplanarVariantForcedGivesTheSameCamera) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json automatic = Calibrate("in/volume.json");
  const Json forced = Calibrate("in/volume.json", {"--variant", "non-coplanar"});
  EXPECT_EQ(forced.at("tsai").at("variant"), "non-coplanar");
  EXPECT_EQ(forced.at("K"), automatic.at("K"));
  EXPECT_EQ(forced.at("covariance"), automatic.at("covariance"));
}

TEST_F(CliCalibTsai, NoRefineWritesTsaisClosedForm) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json camera = Calibrate("in/volume.json", {"--no-refine"});
  EXPECT_EQ(camera.at("method"), "tsai");
  EXPECT_FALSE(camera.contains("refinement"));
  EXPECT_FALSE(camera.contains("covariance"));
  EXPECT_FALSE(camera.contains("projection_uncertainty"));
  // Tsai's camera: principal point at the image centre, zero skew, κ₁ converted to k1, k2, k3.
  const Json& tsai = camera.at("tsai");
  EXPECT_EQ(camera.at("K")[0][2], 319.5);
  EXPECT_EQ(camera.at("K")[1][2], 239.5);
  EXPECT_EQ(camera.at("K")[0][1], 0.0);
  EXPECT_EQ(camera.at("K")[1][1], tsai.at("f_px"));
  EXPECT_EQ(camera.at("distortion").at("k1"), tsai.at("conversion").at("k1"));
  EXPECT_EQ(camera.at("distortion").at("k3"), tsai.at("conversion").at("k3"));
  // Tsai's one-term model cannot follow the lens exactly: a few percent on f, not more.
  EXPECT_NEAR(tsai.at("f_px").get<double>(), 600, 0.03 * 600);
  EXPECT_GT(tsai.at("f_sigma_px").get<double>(), 0);
  EXPECT_NEAR(tsai.at("sx").get<double>(), 1.0, 0.02);
  EXPECT_GT(tsai.at("kappa1_per_px2").get<double>(), 0);  // k1 < 0 (barrel) is κ₁ > 0 in Tsai's inverse form
}

TEST_F(CliCalibTsai, PrincipalPointGivenIsUsedByTsaisStages) {
  // A camera whose principal point is off the image centre: Tsai's stages take it as given.
  Synth("in/volume.json", Override(Override(DistortedVolumeArgs(), "--cx", "331.25"), "--cy", "229.75"));
  const Json camera = Calibrate("in/volume.json", {"--no-refine", "--principal-point", "331.25,229.75"});
  EXPECT_EQ(camera.at("tsai").at("principal_point"), Json::array({331.25, 229.75}));
  EXPECT_EQ(camera.at("K")[0][2], 331.25);
  EXPECT_EQ(camera.at("K")[1][2], 229.75);
  // Then refined, the principal point moves within the noise of the truth.
  const Json refined = Calibrate("in/volume.json", {"--principal-point", "331.25,229.75"});
  EXPECT_TRUE(WithinSigmas(refined, ReadJson("in/volume.truth.json"), kIntrinsics, 5));
}

TEST_F(CliCalibTsai, SinglePlaneIsCoplanarWithoutRefinement) {
  Synth("in/plane.json", PlaneArgs());
  const Json camera = Calibrate("in/plane.json", {"--no-refine"});
  EXPECT_EQ(camera.at("method"), "tsai");
  EXPECT_EQ(camera.at("tsai").at("variant"), "coplanar");
  EXPECT_EQ(camera.at("tsai").at("sx"), 1.0);  // fixed in the coplanar variant (--sx)
  EXPECT_EQ(camera.at("K")[0][0], camera.at("K")[1][1]);
  // f within 5 of its standard errors. The lens's k2 is beyond Tsai's κ₁, but on noise-free data
  // that model error moves f by 0.05 px, 2 % of its σ (3.2 px here).
  const double f_sigma = camera.at("tsai").at("f_sigma_px").get<double>();
  EXPECT_GT(f_sigma, 0);
  EXPECT_LT(std::abs(camera.at("tsai").at("f_px").get<double>() - 600), 5 * f_sigma);
  // --variant coplanar says the same.
  EXPECT_EQ(Calibrate("in/plane.json", {"--no-refine", "--variant", "coplanar"}).at("K"), camera.at("K"));
}

// One plane, --free-principal-point no: refined with Tsai's sx and principal point held (the
// truth's principal point is the image centre, where Tsai assumes it): fx/fy stays 1, the file
// says what was held and why and that every σ is conditional on it, fx and fy are one parameter
// (correlation 1) and the estimate lies within 5σ of the truth.
TEST_F(CliCalibTsai, SinglePlaneIsRefinedHoldingSxAndThePrincipalPoint) {
  Synth("in/plane.json", PlaneArgs());
  const Json camera = Calibrate("in/plane.json", {"--free-principal-point", "no"});
  const Json truth = ReadJson("in/plane.truth.json");
  EXPECT_EQ(camera.at("method"), "tsai+refine");
  EXPECT_EQ(camera.at("tsai").at("variant"), "coplanar");
  EXPECT_EQ(camera.at("K")[0][0], camera.at("K")[1][1]);
  EXPECT_EQ(camera.at("K")[0][2], 319.5);
  EXPECT_EQ(camera.at("K")[1][2], 239.5);
  const Json& refinement = camera.at("refinement");
  EXPECT_EQ(refinement.at("free_intrinsics"), Json({"fx", "fy", "k1", "k2", "p1", "p2"}));
  std::map<std::string, Json> held;
  for (const Json& h : refinement.at("held")) held[h.at("parameter")] = h;
  ASSERT_TRUE(held.count("fx/fy") && held.count("cx") && held.count("cy")) << refinement.at("held").dump();
  EXPECT_EQ(held["fx/fy"].at("value"), 1.0);
  EXPECT_NE(held["fx/fy"].at("because").get<std::string>().find("one plane: Tsai's coplanar sx"), std::string::npos);
  EXPECT_EQ(held["cx"].at("value"), 319.5);
  EXPECT_NE(held["cy"].at("because").get<std::string>().find("as asked; the sigmas are conditional on it"),
            std::string::npos);
  EXPECT_EQ(refinement.at("one_plane").at("principal_point"), "held");
  EXPECT_EQ(refinement.at("covariance_conditional_on"), Json({"fx/fy", "cx", "cy", "s", "k3"}));
  EXPECT_EQ(refinement.at("priors"), Json::array());
  EXPECT_NE(last_.err.find("  sigmas are conditional on the held fx/fy = 1, cx = 319.5, cy = 239.5, s = 0, k3 = 0\n"),
            std::string::npos)
      << last_.err;
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  EXPECT_FALSE(CovarianceIndex(camera, "cx").has_value());
  const Json& m = camera.at("covariance").at("matrix");
  EXPECT_NEAR(m[0][1].get<double>() / std::sqrt(m[0][0].get<double>() * m[1][1].get<double>()), 1.0, 1e-12);
  EXPECT_TRUE(WithinSigmas(camera, truth, {"fx", "fy", "k1", "k2"}, 5));
}

// One plane by default: the principal point under a prior at the image centre, σ 5 % of the
// 640×480 diagonal (40 px). It is estimated, in the covariance, within 5σ of the truth (the image
// centre here), and the file and the summary state the prior; the σ's are conditional only on
// what stays held (the aspect, s and k3).
TEST_F(CliCalibTsai, SinglePlaneEstimatesThePrincipalPointUnderAPrior) {
  Synth("in/plane.json", PlaneArgs());
  const Json camera = Calibrate("in/plane.json");
  const Json& refinement = camera.at("refinement");
  EXPECT_EQ(refinement.at("free_intrinsics"), Json({"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2"}));
  const Json& one_plane = refinement.at("one_plane");
  EXPECT_EQ(one_plane.at("principal_point"), "prior");
  EXPECT_EQ(one_plane.at("mode"), "prior");
  EXPECT_EQ(one_plane.at("prior_px"), Json({319.5, 239.5}));
  EXPECT_EQ(one_plane.at("prior_sigma_px"), 0.05 * 800);
  const double posterior = one_plane.at("posterior_sigma_px")[0].get<double>();
  EXPECT_GT(posterior, 0);
  EXPECT_LE(posterior, 40.0);
  ASSERT_EQ(refinement.at("priors").size(), 2u);
  EXPECT_EQ(refinement.at("priors")[0].at("parameter"), "cx");
  EXPECT_EQ(refinement.at("priors")[0].at("value"), 319.5);
  EXPECT_EQ(refinement.at("priors")[1].at("sigma"), 40.0);
  EXPECT_EQ(refinement.at("covariance_conditional_on"), Json({"fx/fy", "s", "k3"}));
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  const auto cx = CovarianceIndex(camera, "cx");
  ASSERT_TRUE(cx.has_value());
  EXPECT_NEAR(std::sqrt(camera.at("covariance").at("matrix")[*cx][*cx].get<double>()), posterior, 1e-9 * posterior);
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/plane.truth.json"), {"fx", "fy", "cx", "cy", "k1", "k2"}, 5));
  EXPECT_NE(last_.err.find("  priors (their uncertainty is in every sigma): cx = 319.5 +- 40, cy = 239.5 +- 40\n"),
            std::string::npos)
      << last_.err;
  // A wider prior: the file records it.
  const Json wide = Calibrate("in/plane.json", {"--principal-point-sigma", "0.1"});
  EXPECT_EQ(wide.at("refinement").at("one_plane").at("prior_sigma_px"), 0.1 * 800);
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/plane.json", "-o", "out/camera.json", "--free-principal-point", "no",
                                    "--principal-point-sigma", "0.1"}),
                        kTool, kBadInput, "--principal-point-sigma: ", {"applies to --free-principal-point prior only"}));
}

// --prior: the user's own prior on the principal point replaces the one-plane rule. The file
// records it as the priors and the one-plane decision, the posterior σ is at most the prior's, and
// the estimate lies within 5σ of the truth. On a volume, a prior on k3 narrows k3's σ to at most
// the prior's.
TEST_F(CliCalibTsai, PriorsGivenOnTheCommandLineAreThePosteriorsPriors) {
  Synth("in/plane.json", PlaneArgs());
  const Json camera = Calibrate("in/plane.json", {"--prior", "cx=319.5,10", "--prior", "cy=239.5,10"});
  const Json& refinement = camera.at("refinement");
  ASSERT_EQ(refinement.at("priors").size(), 2u);
  EXPECT_EQ(refinement.at("priors")[1].at("parameter"), "cy");
  EXPECT_EQ(refinement.at("priors")[1].at("sigma"), 10.0);
  EXPECT_NE(refinement.at("priors")[0].at("because").get<std::string>().find("stated by the user"), std::string::npos);
  const Json& one_plane = refinement.at("one_plane");
  EXPECT_EQ(one_plane.at("mode"), "prior");
  EXPECT_EQ(one_plane.at("prior_sigma_px"), 10.0);
  const auto cx = CovarianceIndex(camera, "cx");
  ASSERT_TRUE(cx.has_value());
  const double sigma = std::sqrt(camera.at("covariance").at("matrix")[*cx][*cx].get<double>());
  EXPECT_GT(sigma, 0);
  EXPECT_LE(sigma, 10.0);
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/plane.truth.json"), {"fx", "fy", "cx", "cy", "k1", "k2"}, 5));
  EXPECT_NE(last_.err.find("cx = 319.5 +- 10, cy = 239.5 +- 10"), std::string::npos) << last_.err;

  Synth("in/volume.json", DistortedVolumeArgs());
  const Json volume = Calibrate("in/volume.json", {"--distortion", "k1,k2,p1,p2,k3", "--prior", "k3=0,0.001"});
  const auto k3 = CovarianceIndex(volume, "k3");
  ASSERT_TRUE(k3.has_value());
  EXPECT_LE(std::sqrt(volume.at("covariance").at("matrix")[*k3][*k3].get<double>()), 0.001);
  EXPECT_EQ(volume.at("refinement").at("priors")[0].at("parameter"), "k3");
}

// --hold: held at the closed-form start, listed as held with the reason, and the σ's conditional
// on them (the principal point has no row in the covariance).
TEST_F(CliCalibTsai, HoldKeepsParametersAndSaysTheSigmasAreConditional) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json camera = Calibrate("in/volume.json", {"--hold", "cx,cy"});
  const Json& refinement = camera.at("refinement");
  std::map<std::string, Json> held;
  for (const Json& h : refinement.at("held")) held[h.at("parameter")] = h;
  ASSERT_TRUE(held.count("cx") && held.count("cy")) << refinement.at("held").dump();
  EXPECT_NE(held["cx"].at("because").get<std::string>().find("held at the start's value, as asked"), std::string::npos);
  EXPECT_EQ(held["cx"].at("value"), camera.at("tsai").at("principal_point")[0]);
  const Json& conditional = refinement.at("covariance_conditional_on");
  EXPECT_NE(std::find(conditional.begin(), conditional.end(), "cx"), conditional.end()) << conditional.dump();
  EXPECT_FALSE(CovarianceIndex(camera, "cx").has_value());
  EXPECT_TRUE(CovarianceIndex(camera, "fx").has_value());
}

// The fisheye model on an ordinary lens (85° across, 1280 × 720): the start is chosen from the data
// (docs/math/fisheye.md#start), so the refinement reaches the truth of calib-synth's pinhole camera
// (the Kannala–Brandt k's then stand for the tan of a rectilinear lens) instead of stopping at a
// 1,600 px RMS from a 180° fisheye's guess. A wide fisheye's solve: tests/unit/fisheye_calibration_test.cc.
std::vector<std::string> NarrowPlanarArgs() {
  return {"--image-size", "1280x720", "--fx", "700", "--rig", "planar-views", "--seed", "4", "--noise", "0.3"};
}

TEST_F(CliCalibTsai, KannalaBrandtOnANarrowLensReachesTheTruth) {
  Synth("in/narrow.json", NarrowPlanarArgs());
  const Json camera = Calibrate("in/narrow.json", {"--lens-model", "kannala-brandt"});
  EXPECT_EQ(camera.at("distortion").at("model"), "kannala-brandt");
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/narrow.truth.json"), kIntrinsics, 5));
  EXPECT_LT(camera.at("fit").at("rms_px").get<double>(), 0.6);  // √2 · 0.3 px per point
  // The start's decision is in the file and the summary (docs/formats.md#camera-fisheye-start).
  const Json& start = camera.at("fisheye_start");
  const std::string chosen = start.at("chosen").get<std::string>();
  double cheapest = std::numeric_limits<double>::infinity();
  for (const Json& x : start.at("candidates")) {
    if (!x.at("rms_px").is_null()) cheapest = std::min(cheapest, x.at("rms_px").get<double>());
  }
  EXPECT_EQ(start.at("rms_px").get<double>(), cheapest) << start.dump();
  EXPECT_NE(last_.err.find("  fisheye start: " + chosen + ", "), std::string::npos) << last_.err;
  // A Brown–Conrady solve makes no such choice.
  EXPECT_FALSE(Calibrate("in/narrow.json").contains("fisheye_start"));
}

// A refinement that stops short (the iteration limit) or ends far beyond any corner noise (RMS over
// 5 % of the image diagonal: a wrong minimum or wrong data) writes nothing and exits 3.
TEST_F(CliCalibTsai, UnconvergedOrImplausibleRefinementWritesNothing) {
  Synth("in/narrow.json", NarrowPlanarArgs());
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/narrow.json", "-o", "out/camera.json", "--lens-model", "kannala-brandt",
                                    "--max-iterations", "1"}),
                        kTool, kDegenerate, "in/narrow.json: ", {"did not converge in 1 iterations"}));
  EXPECT_TRUE(OutDirEmpty());
  Synth("in/noisy.json", Override(NarrowPlanarArgs(), "--noise", "100"));
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/noisy.json", "-o", "out/camera.json"}), kTool, kDegenerate, "in/noisy.json: ",
                        {"more than 5 % of the image diagonal (73.43 px)", "check that the lens model suits the lens"}));
  EXPECT_TRUE(OutDirEmpty());
  // Unrefined, Zhang's closed form is held to the same bound (it would be written as solved).
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/noisy.json", "-o", "out/camera.json", "--no-refine"}), kTool, kDegenerate,
                        "in/noisy.json: ",
                        {"the zhang camera reprojects at an RMS of 165.2 px, more than 5 % of the image diagonal (73.43 px)"}));
  EXPECT_TRUE(OutDirEmpty());
}

// --lens-model names a model of the variant; an unknown name is refused before anything is
// written.
TEST_F(CliCalibTsai, UnknownLensModelIsRefused) {
  Synth("in/views.json", PlanarArgs());
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/views.json", "-o", "out/camera.json", "--lens-model", "fisheye9"}), kTool,
                        kBadInput, "--lens-model: ", {"unknown lens model \"fisheye9\"", "kannala-brandt"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibTsai, BadPriorsAndHoldsAreRefusedBeforeAnythingIsWritten) {
  Synth("in/plane.json", PlaneArgs());
  const auto fails = [&](std::vector<std::string> extra, const std::string& start, std::vector<std::string> parts) {
    std::vector<std::string> args = {"in/plane.json", "-o", "out/camera.json"};
    args.insert(args.end(), extra.begin(), extra.end());
    return FailsWith(Run(kTool, args), kTool, kBadInput, start, parts);
  };
  EXPECT_TRUE(fails({"--prior", "cx=319.5,0"}, "--prior cx: ", {"the sigma must be > 0", "--hold cx"}));
  EXPECT_TRUE(fails({"--prior", "cx=319.5,-2"}, "--prior cx: ", {"the sigma must be > 0"}));
  EXPECT_TRUE(fails({"--prior", "cx=319.5"}, "--prior: ", {"is not NAME=VALUE,SIGMA", "e.g. cx=639.5,32"}));
  EXPECT_TRUE(fails({"--prior", "cx=abc,2"}, "--prior cx: ", {"the value \"abc\" is not a finite number"}));
  EXPECT_TRUE(fails({"--prior", "kx=0,1"}, "refinement prior on \"kx\": ", {"has no such parameter"}));
  EXPECT_TRUE(fails({"--prior", "k3=0,1"}, "refinement prior on \"k3\": ", {"does not estimate k3"}));
  EXPECT_TRUE(fails({"--prior", "k1=0,1", "--prior", "k1=0,2"}, "refinement prior on \"k1\": ", {"given twice"}));
  EXPECT_TRUE(fails({"--hold", "cx"}, "--hold: ", {"cx is held only with cy", "hold cx,cy"}));
  EXPECT_TRUE(fails({"--hold", "zz"}, "--hold: ", {"\"zz\" is not an estimated lens parameter"}));
  EXPECT_TRUE(fails({"--hold", "s", "--skew"}, "--hold: ", {"--skew frees it"}));
  EXPECT_TRUE(fails({"--hold", "k1", "--prior", "k1=0,1"}, "--hold: ", {"also has a --prior"}));
  EXPECT_TRUE(fails({"--prior", "cx=319.5,5", "--free-principal-point", "no"}, "--free-principal-point: ",
                    {"already has a --prior or --hold"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibTsai, FreePrincipalPointAppliesToOnePlaneOnly) {
  Synth("in/volume.json", DistortedVolumeArgs());
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--free-principal-point", "yes"}), kTool,
                        kBadInput, "--free-principal-point: ",
                        {"applies to one plane (Tsai's coplanar variant) only", "remove it"}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--free-principal-point", "maybe"}), kTool,
                        kBadInput, "--free-principal-point: ", {"maybe not in {no,yes,prior}"}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--free-principal-point", "yes", "--no-refine"}),
                        kTool, kBadInput, "", {"--no-refine excludes --free-principal-point"}));
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/volume.json", "-o", "out/camera.json", "--principal-point-sigma", "0.1"}), kTool,
                        kBadInput, "--principal-point-sigma: ", {"the points are not coplanar", "drop it"}));
  EXPECT_TRUE(OutDirEmpty());
}

// ---------------------------------------------------------------------------------------------
// Planar views: Zhang's method, one pose per view.

TEST_F(CliCalibTsai, PlanarViewsByZhangWithinFiveSigma) {
  Synth("in/views.json", PlanarArgs());
  const Json camera = Calibrate("in/views.json");
  const Json truth = ReadJson("in/views.truth.json");
  EXPECT_EQ(camera.at("method"), "zhang+refine");
  EXPECT_FALSE(camera.contains("camera_from_world"));
  EXPECT_FALSE(camera.contains("tsai"));
  ASSERT_EQ(camera.at("views").size(), truth.at("views").size());
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  EXPECT_TRUE(WithinSigmas(camera, truth, kDefaultTerms, 5));
  // The intrinsics are named; each view's pose is a block of its own (linear in the views).
  EXPECT_EQ(camera.at("covariance").at("parameters"), Json(kDefaultTerms));
  const Json& poses = camera.at("covariance").at("poses");
  ASSERT_EQ(poses.size(), truth.at("views").size());
  EXPECT_EQ(poses.at(0).at("pose"), "views[0].camera_from_board");
  EXPECT_EQ(poses.back().at("pose"), "views[" + std::to_string(truth.at("views").size() - 1) + "].camera_from_board");
  for (size_t v = 0; v < truth.at("views").size(); ++v) {
    EXPECT_EQ(camera.at("views")[v].at("name"), truth.at("views")[v].at("name"));
    const std::string pose = "views[" + std::to_string(v) + "].camera_from_board.";
    const double sigma_rot =
        std::max({Sigma(camera, pose + "rx"), Sigma(camera, pose + "ry"), Sigma(camera, pose + "rz")});
    EXPECT_LT(RotationDifferenceDeg(camera.at("views")[v].at("camera_from_board"),
                                    truth.at("views")[v].at("camera_from_board")),
              5 * std::sqrt(3.0) * sigma_rot * 180 / M_PI)
        << "view " << v;
  }
}

// The same board in inches (30 mm = 1.181… in): calib-synth writes "length_unit": "in", calib-tsai
// reads it, and its camera agrees with the truth and says the unit.
TEST_F(CliCalibTsai, PlanarViewsInInches) {
  std::vector<std::string> args = Override(Override(PlanarArgs(), "--spacing", "1.2"), "--distance", "20");
  args.insert(args.end(), {"--length-unit", "in"});
  EXPECT_EQ(Synth("in/inches.json", args).at("length_unit"), "in");
  const Json camera = Calibrate("in/inches.json");
  EXPECT_EQ(camera.at("length_unit"), "in");
  EXPECT_TRUE(CovarianceIsWellFormed(camera));
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/inches.truth.json"), kDefaultTerms, 5));
}

TEST_F(CliCalibTsai, ShortPlanarViewIsSkippedWithAWarningNamingIt) {
  Json doc = Synth("in/views.json", PlanarArgs());
  const size_t views = doc.at("views").size();
  Truncate(doc["views"][3]["points"], 4);  // 4 points: below 6
  WriteJson("in/short.json", doc);
  const Json camera = Calibrate("in/short.json");
  EXPECT_NE(last_.err.find("calib-tsai: warning: view \"view-03\" skipped: 4 points, fewer than 6\n"),
            std::string::npos)
      << last_.err;
  ASSERT_EQ(camera.at("views").size(), views - 1);
  for (const Json& v : camera.at("views")) EXPECT_NE(v.at("name"), "view-03");
  EXPECT_EQ(camera.at("covariance").at("poses").size(), views - 1);
  EXPECT_TRUE(WithinSigmas(camera, ReadJson("in/views.truth.json"), kDefaultTerms, 5));
}

TEST_F(CliCalibTsai, VolumeFlagsAreRefusedForPlanarViews) {
  Synth("in/views.json", PlanarArgs());
  for (const std::vector<std::string>& flag : std::vector<std::vector<std::string>>{
           {"--variant", "coplanar"}, {"--principal-point", "320,240"}, {"--sx", "1.1"}, {"--free-principal-point", "no"},
           {"--principal-point-sigma", "0.1"}}) {
    std::vector<std::string> args = {"in/views.json", "-o", "out/camera.json"};
    args.insert(args.end(), flag.begin(), flag.end());
    EXPECT_TRUE(FailsWith(Run(kTool, args), kTool, kBadInput, flag[0] + ": ", {"applies to rig \"volume\" only"}));
  }
  EXPECT_TRUE(OutDirEmpty());
}

// ---------------------------------------------------------------------------------------------
// The refinement's options.

TEST_F(CliCalibTsai, DistortionTermsByName) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json truth = ReadJson("in/volume.truth.json");
  const Json k1k2 = Calibrate("in/volume.json", {"--distortion", "k1,k2"});
  EXPECT_EQ(k1k2.at("refinement").at("free_intrinsics"), Json({"fx", "fy", "cx", "cy", "k1", "k2"}));
  const Json& names = k1k2.at("covariance").at("parameters");
  EXPECT_EQ(std::vector<Json>(names.begin(), names.begin() + 7),
            (std::vector<Json>{"fx", "fy", "cx", "cy", "k1", "k2", "camera_from_world.rx"}));
  EXPECT_EQ(names.size(), 6u + 6u);
  for (const char* fixed : {"p1", "p2", "k3"}) EXPECT_EQ(k1k2.at("distortion").at(fixed), 0.0) << fixed;
  EXPECT_TRUE(WithinSigmas(k1k2, truth, {"fx", "fy", "cx", "cy", "k1", "k2"}, 5));

  // k3 on request (the truth has k3 = 0, so it must come out within its σ of zero).
  const Json all = Calibrate("in/volume.json", {"--distortion", "k1,k2,p1,p2,k3"});
  EXPECT_EQ(all.at("refinement").at("free_intrinsics").back(), "k3");
  EXPECT_TRUE(WithinSigmas(all, truth, {"fx", "fy", "k1", "k2", "k3"}, 5));

  // A rational term promotes the model (OpenCV's CALIB_RATIONAL_MODEL): the truth is the rational
  // model with k4 = k5 = k6 = 0, so k4 must come out within its σ of zero.
  const Json rational = Calibrate("in/volume.json", {"--distortion", "k1,k2,p1,p2,k4"});
  EXPECT_EQ(rational.at("distortion").at("model"), "rational");
  EXPECT_EQ(rational.at("refinement").at("free_intrinsics"), Json({"fx", "fy", "cx", "cy", "k1", "k2", "p1", "p2", "k4"}));
  for (const char* held : {"k3", "k5", "k6"}) EXPECT_EQ(rational.at("distortion").at(held), 0.0) << held;
  EXPECT_TRUE(WithinSigmas(rational, truth, {"fx", "fy", "cx", "cy", "k1", "k4"}, 5));

  // "none": a pinhole. The lens's distortion then shows in σ̂: more than 3 of its standard
  // deviations (1/√(2 dof) relative) above the true noise, which a right model exceeds with
  // probability 0.13 %.
  const Json none = Calibrate("in/volume.json", {"--distortion", "none"});
  EXPECT_EQ(none.at("distortion").at("model"), "none");
  EXPECT_EQ(none.at("refinement").at("free_intrinsics"), Json(kIntrinsics));
  const double dof = none.at("refinement").at("dof").get<double>();
  EXPECT_GT(none.at("refinement").at("sigma_px").get<double>(), kVolumeNoisePx * (1 + 3 / std::sqrt(2 * dof)));
}

TEST_F(CliCalibTsai, SkewIsOptIn) {
  // A sensor with skew: θ = 89.5°, s = −fx·cot θ ≈ −5.24 px.
  Synth("in/skewed.json", Override(DistortedVolumeArgs(), "--skew-deg", "89.5"));
  const Json truth = ReadJson("in/skewed.truth.json");
  ASSERT_LT(LensParameter(truth, "s"), -5);
  const Json without = Calibrate("in/skewed.json");
  EXPECT_EQ(without.at("K")[0][1], 0.0);
  EXPECT_FALSE(CovarianceIndex(without, "s").has_value());
  const Json with = Calibrate("in/skewed.json", {"--skew"});
  EXPECT_EQ(with.at("refinement").at("free_intrinsics"), Json({"fx", "fy", "cx", "cy", "s", "k1", "k2", "p1", "p2"}));
  EXPECT_EQ(with.at("covariance").at("parameters")[4], "s");
  EXPECT_TRUE(WithinSigmas(with, truth, {"fx", "fy", "cx", "cy", "s", "k1", "k2"}, 5));
  EXPECT_NEAR(with.at("intrinsics").at("skew_angle_deg").get<double>(), 89.5, 5 * Sigma(with, "s") / 600 * 180 / M_PI);
}

// A gross outlier (+40 px in u at views[2].points[5], "plane-02") is listed with its σ multiple,
// kept in the fit (never dropped), and a robust loss bounds its pull on the estimate.
TEST_F(CliCalibTsai, OutlierIsListedNotDroppedAndRobustLossBoundsIt) {
  Json doc = Synth("in/volume.json", DistortedVolumeArgs());
  doc["views"][2]["points"][5][3] = doc["views"][2]["points"][5][3].get<double>() + 40;
  WriteJson("in/outlier.json", doc);
  const Json clean = Calibrate("in/volume.json");

  const Json plain = Calibrate("in/outlier.json", {"--residuals", "out/residuals.json"});
  const Json& outliers = plain.at("refinement").at("outliers");
  ASSERT_EQ(outliers.size(), 1u) << outliers.dump();
  EXPECT_EQ(outliers[0].at("view"), "plane-02");
  EXPECT_EQ(outliers[0].at("view_index"), 2);
  EXPECT_EQ(outliers[0].at("point_index"), 5);
  EXPECT_GT(outliers[0].at("sigmas").get<double>(), 30);
  EXPECT_LT(outliers[0].at("residual_px")[0].get<double>(), -30);  // predicted − measured: it was moved right
  EXPECT_NE(last_.err.find("calib-tsai: warning: outlier: views[2].points[5] (view \"plane-02\") residual "),
            std::string::npos)
      << last_.err;
  EXPECT_NE(last_.err.find("1 outliers"), std::string::npos) << last_.err;
  EXPECT_EQ(plain.at("fit").at("n_points"), 315);  // still in the fit
  const Json residuals = ReadJson("out/residuals.json").at("views")[2].at("points");
  EXPECT_EQ(residuals.size(), 63u);
  EXPECT_EQ(residuals[5][5], outliers[0].at("residual_px")[0]);

  const Json huber = Calibrate("in/outlier.json", {"--loss", "huber", "--loss-scale", "1"});
  EXPECT_EQ(huber.at("refinement").at("loss"), "huber");
  EXPECT_EQ(huber.at("refinement").at("loss_scale_px"), 1.0);
  ASSERT_EQ(huber.at("refinement").at("outliers").size(), 1u);
  EXPECT_EQ(huber.at("refinement").at("outliers")[0].at("point_index"), 5);
  // Least squares lets the 40 px residual pull the principal point by several σ; Huber's loss
  // caps its influence at that of a 1 px residual, 1/40 of it: within 0.5σ of the clean estimate.
  double worst_plain = 0;
  for (const std::string& p : kDefaultTerms) {
    const double sigma = Sigma(clean, p);
    worst_plain = std::max(worst_plain, std::abs(LensParameter(plain, p) - LensParameter(clean, p)) / sigma);
    EXPECT_LT(std::abs(LensParameter(huber, p) - LensParameter(clean, p)), 0.5 * sigma) << p;
  }
  EXPECT_GT(worst_plain, 2.0) << "the outlier should matter without a robust loss";

  const Json cauchy = Calibrate("in/outlier.json", {"--loss", "cauchy"});
  EXPECT_EQ(cauchy.at("refinement").at("loss"), "cauchy");
  EXPECT_EQ(cauchy.at("refinement").at("outliers").size(), 1u);
}

TEST_F(CliCalibTsai, NoOutliersInCleanNoise) {
  // Bonferroni over all residuals at 1 %: Gaussian noise alone lists none (here, for this seed).
  Synth("in/volume.json", DistortedVolumeArgs());
  EXPECT_TRUE(Calibrate("in/volume.json").at("refinement").at("outliers").empty());
  EXPECT_EQ(last_.err.find("warning"), std::string::npos) << last_.err;
}

// ---------------------------------------------------------------------------------------------
// Projection uncertainty.

// The distorted projection of conventions.md for a camera@1 file, written out independently.
Eigen::Vector3d CameraPoint(const Json& camera, const Eigen::Vector3d& world) {
  const Pinhole pose = Pinhole::FromTruth(camera);
  return pose.R * world + pose.t;
}

Eigen::Vector2d Project(const Json& camera, const Eigen::Vector3d& p_cam) {
  const double x = p_cam.x() / p_cam.z(), y = p_cam.y() / p_cam.z();
  auto d = [&](const char* name) { return LensParameter(camera, name); };
  const double r2 = x * x + y * y;
  const double radial = 1 + d("k1") * r2 + d("k2") * r2 * r2 + d("k3") * r2 * r2 * r2;
  const double xd = x * radial + 2 * d("p1") * x * y + d("p2") * (r2 + 2 * x * x);
  const double yd = y * radial + d("p1") * (r2 + 2 * y * y) + 2 * d("p2") * x * y;
  return {d("fx") * xd + d("s") * yd + d("cx"), d("fy") * yd + d("cy")};
}

TEST_F(CliCalibTsai, ProjectionUncertaintyAtPointsPixelsAndGrid) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const Json camera = Calibrate("in/volume.json", {"--uncertainty-at", "100,-50,200", "--uncertainty-at",
                                                   "-200,150,400", "--uncertainty-grid", "1000", "--grid-size", "4x3"});
  const Json& u = camera.at("projection_uncertainty");
  EXPECT_TRUE(u.at("test_points").empty());  // --no-test-points
  ASSERT_EQ(u.at("world_points").size(), 2u);
  EXPECT_EQ(u.at("world_points")[0].at("world"), Json::array({100.0, -50.0, 200.0}));
  EXPECT_TRUE(u.at("pixels").empty());

  // The grid: 4×3 cells over the image [−0.5, W − 0.5] × [−0.5, H − 0.5], one row per cell
  // centre, u fastest.
  const Json& grid = u.at("grid");
  EXPECT_EQ(grid.at("depth"), 1000.0);
  EXPECT_EQ(grid.at("cols"), 4);
  EXPECT_EQ(grid.at("rows"), 3);
  EXPECT_EQ(grid.at("columns"), Json({"u", "v", "with_poses.sigma_major_px", "with_poses.sigma_minor_px",
                                       "with_poses.angle_deg", "intrinsics_only.sigma_major_px",
                                       "intrinsics_only.sigma_minor_px", "intrinsics_only.angle_deg"}));
  ASSERT_EQ(grid.at("cells").size(), 12u);
  for (size_t k = 0; k < 12; ++k) {
    const Json& cell = grid.at("cells")[k];
    ASSERT_EQ(cell.size(), 8u);
    EXPECT_GE(cell[5].get<double>(), cell[6].get<double>()) << k;
    EXPECT_EQ(cell[0].get<double>(), -0.5 + 640.0 * (k % 4 + 0.5) / 4) << k;
    EXPECT_EQ(cell[1].get<double>(), -0.5 + 480.0 * (k / 4 + 0.5) / 3) << k;
    EXPECT_GE(cell[2].get<double>(), cell[3].get<double>()) << k;
    EXPECT_GT(cell[3].get<double>(), 0) << k;
    EXPECT_GT(cell[4].get<double>(), -90) << k;
    EXPECT_LE(cell[4].get<double>(), 90) << k;
  }

  // Two paths to one point agree: the world point, and its pixel at its depth (unprojected and
  // carried back through camera_from_world). The pixel comes from the conventions.md projection.
  const Eigen::Vector3d world(100, -50, 200);
  const Eigen::Vector3d p_cam = CameraPoint(camera, world);
  const Eigen::Vector2d px = Project(camera, p_cam);
  char pixel_flag[120];
  std::snprintf(pixel_flag, sizeof pixel_flag, "%.17g,%.17g,%.17g", px.x(), px.y(), p_cam.z());
  const Json again =
      Calibrate("in/volume.json", {"--uncertainty-pixel", pixel_flag, "--uncertainty-pixel", "239.5,239.5,1000"});
  const Json& by_pixel = again.at("projection_uncertainty").at("pixels");
  ASSERT_EQ(by_pixel.size(), 2u);
  EXPECT_EQ(by_pixel[0].at("depth").get<double>(), p_cam.z());
  const Json& a = u.at("world_points")[0].at("with_poses");
  const Json& b = by_pixel[0].at("with_poses");
  for (const char* key : {"sigma_major_px", "sigma_minor_px"}) {
    EXPECT_NEAR(a.at(key).get<double>(), b.at(key).get<double>(), 1e-6 * a.at(key).get<double>()) << key;
  }
  EXPECT_NEAR(a.at("angle_deg").get<double>(), b.at("angle_deg").get<double>(), 1e-4);
  // And a pixel asked for directly equals the grid cell at the same place (cell 5: (239.5, 239.5)).
  const Json& cell = grid.at("cells")[5];
  EXPECT_EQ(by_pixel[1].at("with_poses").at("sigma_major_px"), cell[2]);
  EXPECT_EQ(by_pixel[1].at("with_poses").at("sigma_minor_px"), cell[3]);
  EXPECT_EQ(by_pixel[1].at("intrinsics_only").at("sigma_major_px"), cell[5]);
  EXPECT_EQ(by_pixel[1].at("intrinsics_only").at("sigma_minor_px"), cell[6]);
}

TEST_F(CliCalibTsai, TestPointErrorsAgreeWithTheirEllipses) {
  // seed 000's five test points, two of them outside the volume: the registration error there
  // is the calibration's projection error plus the measured pixel's own noise.
  Synth("in/volume.json", Remove(DistortedVolumeArgs(), "--no-test-points", false));
  const Json camera = Calibrate("in/volume.json");
  const Json& ellipses = camera.at("projection_uncertainty").at("test_points");
  const Json& fits = camera.at("fit").at("test_points");
  ASSERT_EQ(ellipses.size(), 5u);
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_EQ(ellipses[k].at("name"), fits[k].at("name"));
    const Json& e = ellipses[k].at("with_poses");
    const double major = e.at("sigma_major_px").get<double>(), minor = e.at("sigma_minor_px").get<double>();
    const double spread = std::sqrt(major * major + minor * minor + 2 * kVolumeNoisePx * kVolumeNoisePx);
    EXPECT_LT(fits[k].at("error_px").get<double>(), 5 * spread) << fits[k].at("name");
  }
  // Outside the volume the calibration extrapolates: the ellipse there is larger than inside.
  EXPECT_EQ(fits[0].at("inside_volume"), false);
  EXPECT_EQ(fits[2].at("inside_volume"), true);
  EXPECT_GT(ellipses[0].at("with_poses").at("sigma_major_px").get<double>(),
            5 * ellipses[2].at("with_poses").at("sigma_major_px").get<double>());
}

TEST_F(CliCalibTsai, PlanarViewsUncertaintyAtPixels) {
  Synth("in/views.json", PlanarArgs());
  const Json camera = Calibrate("in/views.json", {"--uncertainty-pixel", "320,240,500", "--uncertainty-grid", "500"});
  const Json& u = camera.at("projection_uncertainty");
  ASSERT_EQ(u.at("pixels").size(), 1u);
  // Both kinds, labelled: tied to the boards (the boards' poses re-estimated with the intrinsics,
  // averaged), and the intrinsics alone (what a user of the camera elsewhere inherits).
  EXPECT_NE(u.at("kinds").at("with_poses").get<std::string>().find("tied to the calibration object"), std::string::npos);
  EXPECT_NE(u.at("kinds").at("intrinsics_only").get<std::string>().find("only the intrinsics vary"), std::string::npos);
  EXPECT_GT(u.at("pixels")[0].at("with_poses").at("sigma_major_px").get<double>(), 0);
  EXPECT_GT(u.at("pixels")[0].at("intrinsics_only").at("sigma_major_px").get<double>(), 0);
  EXPECT_EQ(u.at("grid").at("cells").size(), 16u * 9u);  // --grid-size default 16x9
  EXPECT_EQ(u.at("grid").at("columns").size(), 8u);
  // The summary says both, labelled, at the image centre and at the pixel asked for.
  EXPECT_NE(last_.err.find("with poses = tied to the calibration object, intrinsics only = what using the camera elsewhere inherits"),
            std::string::npos)
      << last_.err;
  EXPECT_NE(last_.err.find("    at pixel (320.0, 240.0), depth 500 mm: "), std::string::npos) << last_.err;
}

TEST_F(CliCalibTsai, RepeatedRunsGiveByteIdenticalFiles) {
  Synth("in/volume.json", DistortedVolumeArgs());
  const std::vector<std::string> args = {"in/volume.json", "-o", "out/camera.json", "--uncertainty-grid", "800", "-q"};
  ASSERT_EQ(Run(kTool, args).exit_code, kOk);
  const std::string first = ReadText("out/camera.json");
  ASSERT_EQ(Run(kTool, args).exit_code, kOk);
  EXPECT_EQ(ReadText("out/camera.json"), first);
}

TEST_F(CliCalibTsai, OutputIsReadBackByCalibCompare) {
  // The covariance and views blocks are valid camera@1 for the other tools.
  Synth("in/views.json", PlanarArgs());
  Calibrate("in/views.json");
  const auto r = Run("calib-compare", {"in/views.truth.json", "out/camera.json"});
  EXPECT_EQ(r.exit_code, kOk) << r.err;
}

TEST_F(CliCalibTsai, HelpIsTheManual) {
  const auto r = Run(kTool, {"--help"});
  EXPECT_EQ(r.exit_code, kOk);
  for (const char* text : {"--variant", "--principal-point", "--no-refine", "--distortion", "--skew", "--loss",
                           "--uncertainty-grid", "--uncertainty-pixel", "Exit codes"}) {
    EXPECT_NE(r.out.find(text), std::string::npos) << text;
  }
  EXPECT_EQ(r.err, "");
}

// ---------------------------------------------------------------------------------------------
// Bad data (issue 3 item 9): each case edits a valid input and expects the documented exit code,
// one line naming the file (and the place, when there is one), and no output.

struct BadData {
  std::string name;
  int exit_code;
  std::vector<std::string> phrases;
  std::function<void(Json& doc)> edit;
  std::vector<std::string> synth_args;  // the input before the edit
  std::vector<std::string> flags = {};
};

void PrintTo(const BadData& c, std::ostream* os) { *os << c.name; }

Json& Point(Json& doc, size_t view, size_t index) { return doc["views"][view]["points"][index]; }

std::vector<BadData> BadDataCases() {
  return {
      {"TooFewViewsAfterSkippingShortOnes",
       kBadInput,
       {"planar views need at least 2 views of 6 or more points, got 1",
        "(view \"view-01\" skipped: 5 points, fewer than 6; view \"view-02\" skipped: 3 points, fewer than 6)",
        "add views"},
       [](Json& d) {
         Truncate(d["views"], 3);
         Truncate(d["views"][1]["points"], 5);
         Truncate(d["views"][2]["points"], 3);
       },
       PlanarArgs()},
      {"OneView",
       kBadInput,
       {"planar views need at least 2 views", "got 1;", "add views"},
       [](Json& d) { Truncate(d["views"], 1); },
       PlanarArgs()},
      {"ParallelBoards",
       kDegenerate,
       {"the views do not constrain K", "boards all parallel", "tilted in different directions"},
       [](Json& d) {
         Json copy = d["views"][0];
         copy["name"] = "copy";
         d["views"] = Json::array({d["views"][0], copy});
       },
       PlanarArgs()},
      {"TooFewPointsForTsai",
       kBadInput,
       {"Tsai's non-coplanar method needs at least 7 points, got 6", "add correspondences"},
       [](Json& d) {
         Json a = Json::array({Point(d, 0, 0), Point(d, 0, 8), Point(d, 0, 62)});
         Json b = Json::array({Point(d, 4, 3), Point(d, 4, 30), Point(d, 4, 58)});
         d["views"] = Json::array({{{"name", "a"}, {"points", a}}, {{"name", "b"}, {"points", b}}});
       },
       DistortedVolumeArgs()},
      {"TooFewPointsForTheRefinement",
       kBadInput,
       {"the refinement needs more residuals than free parameters", "7 points give 14 for 14", "add points"},
       [](Json& d) {
         Json a = Json::array({Point(d, 0, 0), Point(d, 0, 8), Point(d, 0, 62), Point(d, 0, 31)});
         Json b = Json::array({Point(d, 4, 3), Point(d, 4, 30), Point(d, 4, 58)});
         d["views"] = Json::array({{{"name", "a"}, {"points", a}}, {{"name", "b"}, {"points", b}}});
       },
       DistortedVolumeArgs()},
      {"PlaneParallelToTheImage",
       kDegenerate,
       {"f is not determined by these points (standard error ", "% of f, limit 10%)", "nearly parallel to the image",
        "tilt the target"},
       [](Json&) {},
       Override(PlaneArgs(), "--tilt-deg", "0"),
       {"--no-refine"}},
      {"CoplanarForcedIntoNonCoplanar",
       kDegenerate,
       {"the non-coplanar variant was asked for, but the points are coplanar", "--variant coplanar or auto"},
       [](Json&) {},
       PlaneArgs(),
       {"--variant", "non-coplanar"}},
      {"VolumeForcedIntoCoplanar",
       kDegenerate,
       {"the coplanar variant was asked for, but the points span a volume", "--variant non-coplanar or auto"},
       [](Json&) {},
       DistortedVolumeArgs(),
       {"--variant", "coplanar"}},
      {"NoConvergence",
       kDegenerate,
       {"the refinement did not converge in 2 iterations", "raise --max-iterations"},
       [](Json&) {},
       DistortedVolumeArgs(),
       {"--max-iterations", "2"}},
      {"PointBehindTheCamera",
       kBadInput,
       {"1 of 315 points lie behind the camera that the others define", "views[1].points[7] (view \"plane-01\")",
        "check their coordinates"},
       [](Json& d) {
         // Far behind the camera along the optical axis (the camera is ~0.9 m before Z = 0).
         Point(d, 1, 7)[2] = -5000.0;
       },
       DistortedVolumeArgs()},
      {"MirroredWorld",
       kBadInput,
       {"the world frame is mirrored relative to the image", "flip one world axis"},
       [](Json& d) {
         for (Json& view : d["views"]) {
           for (Json& p : view["points"]) p[0] = -p[0].get<double>();
         }
       },
       DistortedVolumeArgs()},
  };
}

class CliCalibTsaiBadData : public CliTest, public ::testing::WithParamInterface<BadData> {};

TEST_P(CliCalibTsaiBadData, FailsWithOneLineAndNoOutput) {
  const BadData& c = GetParam();
  Json doc = Synth("in/good.json", c.synth_args);
  c.edit(doc);
  WriteJson("in/bad.json", doc);
  std::vector<std::string> args = {"in/bad.json", "-o", "out/camera.json", "--residuals", "out/residuals.json"};
  args.insert(args.end(), c.flags.begin(), c.flags.end());
  EXPECT_TRUE(FailsWith(Run(kTool, args), kTool, c.exit_code, "in/bad.json: ", c.phrases));
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Cases, CliCalibTsaiBadData, ::testing::ValuesIn(BadDataCases()),
                         [](const auto& param_info) { return param_info.param.name; });

// A NaN where a number belongs never reaches a solver: the reader names line and column.
TEST_F(CliCalibTsai, NaNInTheCorners) {
  Json doc = Synth("in/volume.json", DistortedVolumeArgs());
  doc["views"][2]["points"][4][1] = "@@HERE@@";
  std::string text = doc.dump(2);
  const size_t at = text.find("\"@@HERE@@\"");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 10, "NaN");
  WriteText("in/bad.json", text);
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/bad.json", "-o", "out/camera.json"}), kTool, kBadInput,
                        "in/bad.json: " + LineColumn(text, at) + ": ",
                        {"'NaN' is not a JSON number", "every value must be a finite number"}));
  EXPECT_TRUE(OutDirEmpty());
}

// ---------------------------------------------------------------------------------------------
// Bad flags: exit code 2, one line starting with the flag, no output.

struct BadFlag {
  std::string name;
  std::vector<std::string> flags;
  std::string location;  // the start of the message after "calib-tsai: error: "
  std::vector<std::string> phrases;
};

void PrintTo(const BadFlag& c, std::ostream* os) { *os << c.name; }

std::vector<BadFlag> BadFlagCases() {
  const std::string kPositive = "expected a positive number, got ";
  return {
      {"UnknownDistortionTermSuggestsTheNearest",
       {"--distortion", "k1,K2"},
       "--distortion: ",
       {"unknown term \"K2\"", "did you mean \"k2\"?", "(known: k1, k2, p1, p2, k3, k4, k5, k6)", "or none"}},
      {"UnknownDistortionTermWithoutNearName",
       {"--distortion", "kappa1"},
       "--distortion: ",
       {"unknown term \"kappa1\"", "use one of k1, k2, p1, p2, k3, k4, k5, k6, or none"}},
      {"UnknownRationalTerm",
       {"--distortion", "k1,k7"},
       "--distortion: ",
       {"unknown term \"k7\"", "did you mean"}},
      {"EmptyDistortionTerm", {"--distortion", "k1,,k2"}, "--distortion: ", {"empty term in \"k1,,k2\"", "or none"}},
      {"DuplicateDistortionTerm",
       {"--distortion", "k1,k2,k1"},
       "--distortion: ",
       {"\"k1\" is named twice in \"k1,k2,k1\"", "name each term once"}},
      {"UnknownLoss", {"--loss", "tukey"}, "--loss: ", {"tukey", "none,huber,cauchy"}},
      {"ZeroLossScale", {"--loss", "huber", "--loss-scale", "0"}, "--loss-scale: ", {kPositive + "\"0\""}},
      {"ZeroMaxIterations", {"--max-iterations", "0"}, "--max-iterations: ", {"not in range 1 to 100000"}},
      {"UnknownVariant", {"--variant", "planar"}, "--variant: ", {"planar", "auto,coplanar,non-coplanar"}},
      {"PrincipalPointThreeNumbers",
       {"--principal-point", "320,240,1"},
       "--principal-point: ",
       {"At Most 2 required but received 3"}},
      {"PrincipalPointOneNumber", {"--principal-point", "320"}, "--principal-point: ", {"2 required U,V missing"}},
      {"PrincipalPointNaN", {"--principal-point", "nan,240"}, "--principal-point: ", {"must be a finite number, got nan"}},
      {"ZeroSx", {"--sx", "0"}, "--sx: ", {kPositive + "\"0\""}},
      {"ZeroGridDepth", {"--uncertainty-grid", "0"}, "--uncertainty-grid: ", {kPositive + "\"0\""}},
      {"NegativeGridDepth", {"--uncertainty-grid", "-1000"}, "--uncertainty-grid: ", {kPositive + "\"-1000\""}},
      {"GridDepthNotANumber", {"--uncertainty-grid", "far"}, "--uncertainty-grid: ", {kPositive + "\"far\""}},
      {"GridDepthInfinite", {"--uncertainty-grid", "inf"}, "--uncertainty-grid: ", {kPositive + "\"inf\""}},
      {"GridSizeOneNumber",
       {"--uncertainty-grid", "1000", "--grid-size", "16"},
       "--grid-size: ",
       {"expected two positive integers as COLSxROWS", "got \"16\""}},
      {"GridSizeZero", {"--uncertainty-grid", "1000", "--grid-size", "0x9"}, "--grid-size: ", {"got \"0x9\""}},
      {"UncertaintyPixelTwoNumbers",
       {"--uncertainty-pixel", "320,240"},
       "--uncertainty-pixel: ",
       {"expected three numbers U,V,DEPTH (e.g. 320,240,1000), got 2 (320,240)"}},
      {"UncertaintyPixelFourNumbers",
       {"--uncertainty-pixel", "320,240,1000,5"},
       "--uncertainty-pixel: ",
       {"got 4 (320,240,1000,5); give each point as its own --uncertainty-pixel"}},
      {"UncertaintyPixelNaN",
       {"--uncertainty-pixel", "nan,240,1000"},
       "--uncertainty-pixel: ",
       {"must be a finite number, got nan"}},
      {"UncertaintyPixelZeroDepth",
       {"--uncertainty-pixel", "320,240,0"},
       "--uncertainty-pixel: ",
       {"the depth in \"320,240,0\" must be positive"}},
      {"UncertaintyPixelNegativeDepth",
       {"--uncertainty-pixel", "320,240,-5"},
       "--uncertainty-pixel: ",
       {"must be positive"}},
      {"UncertaintyPixelOutsideTheImage",
       {"--uncertainty-pixel", "640,240,1000"},
       "--uncertainty-pixel: ",
       {"(640, 240) lies outside the 640×480 image", "U in [-0.5, 639.5]"}},
      {"UncertaintyPixelAboveTheImage",
       {"--uncertainty-pixel", "320,-0.75,1000"},
       "--uncertainty-pixel: ",
       {"(320, -0.75) lies outside"}},
      {"UncertaintyAtTwoNumbers",
       {"--uncertainty-at", "1,2"},
       "--uncertainty-at: ",
       {"expected three numbers X,Y,Z (e.g. 0,0,1000), got 2 (1,2)"}},
      {"UncertaintyAtLetters", {"--uncertainty-at", "1,2,z"}, "--uncertainty-at: ", {"expected a number, got \"z\""}},
      {"NoRefineWithDistortion", {"--no-refine", "--distortion", "k1"}, "--no-refine excludes --distortion", {}},
      {"NoRefineWithUncertaintyGrid",
       {"--no-refine", "--uncertainty-grid", "1000"},
       "--no-refine excludes --uncertainty-grid",
       {}},
      {"UnknownFlag", {"--refine"}, "", {"--refine", "see calib-tsai --help"}},
  };
}

class CliCalibTsaiBadFlag : public CliTest, public ::testing::WithParamInterface<BadFlag> {};

TEST_P(CliCalibTsaiBadFlag, FailsWithOneLineNamingTheFlag) {
  const BadFlag& c = GetParam();
  Synth("in/volume.json", DistortedVolumeArgs());
  std::vector<std::string> args = {"in/volume.json", "-o", "out/camera.json"};
  args.insert(args.end(), c.flags.begin(), c.flags.end());
  const auto r = Run(kTool, args);
  EXPECT_TRUE(FailsWith(r, kTool, kBadInput, c.location, c.phrases));
  if (!c.location.empty()) {
    EXPECT_EQ(r.err.rfind("calib-tsai: error: " + c.location, 0), 0u) << r.err;
  }
  EXPECT_TRUE(OutDirEmpty());
}

INSTANTIATE_TEST_SUITE_P(Cases, CliCalibTsaiBadFlag, ::testing::ValuesIn(BadFlagCases()),
                         [](const auto& param_info) { return param_info.param.name; });

TEST_F(CliCalibTsai, UncertaintyAtIsRefusedForPlanarViews) {
  Synth("in/views.json", PlanarArgs());
  EXPECT_TRUE(FailsWith(Run(kTool, {"in/views.json", "-o", "out/camera.json", "--uncertainty-at", "0,0,500"}), kTool,
                        kBadInput, "--uncertainty-at: ", {"planar views have no world frame", "--uncertainty-pixel"}));
  EXPECT_TRUE(OutDirEmpty());
}

TEST_F(CliCalibTsai, FailureLeavesAnExistingOutputUntouched) {
  Synth("in/plane.json", PlaneArgs());
  WriteText("out/camera.json", "previous result\n");
  const auto r = Run(kTool, {"in/plane.json", "-o", "out/camera.json", "--variant", "non-coplanar"});
  EXPECT_TRUE(FailsWith(r, kTool, kDegenerate, "in/plane.json: ", {"coplanar"}));
  EXPECT_EQ(List("out"), std::vector<std::string>{"camera.json"});
  EXPECT_EQ(ReadText("out/camera.json"), "previous result\n");
}

// Cross-validation from one run (issue 23 item 5): --split-halves writes each half's camera beside
// the whole's, calib-compare --cross-validate weighs their difference by both covariances: a
// model that fits agrees, k1 alone on a k1, k2 lens does not (exit code 4, its JUnit failure).
TEST_F(CliCalibTsai, SplitHalvesThenCrossValidate) {
  Synth("in/views.json", Override(Override(Override(PlanarArgs(), "--views", "24"), "--noise", "0.2"), "--distortion", "-0.3,0.15,0,0,0"));
  const Json whole = Calibrate("in/views.json", {"--split-halves", "--distortion", "k1,k2"});
  EXPECT_NE(last_.err.find("half a: 12 views"), std::string::npos) << last_.err;
  EXPECT_NE(last_.err.find("half b: 12 views"), std::string::npos) << last_.err;
  const Json a = ReadJson("out/camera.half-a.json"), b = ReadJson("out/camera.half-b.json");
  ASSERT_EQ(a.at("views").size(), 12u);
  EXPECT_EQ(a.at("views")[0].at("name"), whole.at("views")[0].at("name"));
  EXPECT_EQ(b.at("views")[0].at("name"), whole.at("views")[1].at("name"));
  CommandResult r = Run("calib-compare", {"out/camera.half-a.json", "out/camera.half-b.json", "--cross-validate", "--junit", "out/cv.xml"});
  EXPECT_EQ(r.exit_code, kOk) << r.out << r.err;
  EXPECT_NE(r.out.find("check cross-validation: pass: one camera within their uncertainty: all 12 regions jointly"), std::string::npos) << r.out;
  EXPECT_EQ(JUnitCounts(Path("out/cv.xml")), "1 0 0\n");
  // The lens has k2 = 0.15; each half fitted with k1 alone bends the edges by its own boards (χ² ≈ 135, 5 dof).
  Calibrate("in/views.json", {"--split-halves", "--distortion", "k1", "-q"});
  r = Run("calib-compare", {"out/camera.half-a.json", "out/camera.half-b.json", "--cross-validate"});
  EXPECT_EQ(r.exit_code, kCheckFailed) << r.out << r.err;
  EXPECT_NE(r.out.find("check cross-validation: fail: they disagree beyond their uncertainty"), std::string::npos) << r.out;
}

TEST_F(CliCalibTsai, CrossValidationRefusals) {
  Synth("in/views.json", PlanarArgs());
  Calibrate("in/views.json", {"-q"});
  // The truth has no covariance: the flag is named, nothing printed.
  CommandResult r = Run("calib-compare", {"in/views.truth.json", "out/camera.json", "--cross-validate"});
  EXPECT_TRUE(FailsWith(r, "calib-compare", kBadInput, "in/views.truth.json: covariance: none; --cross-validate needs both cameras'", {}));
  // One view cannot be halved.
  Json one = ReadJson("in/views.json");
  Json views = Json::array();
  views.push_back(one.at("views")[0]);
  one["views"] = views;
  WriteJson("in/one.json", one);
  fs::remove(Path("out/camera.json"));
  r = Run(kTool, {"in/one.json", "-o", "out/camera.json", "--split-halves"});
  EXPECT_TRUE(FailsWith(r, std::string(kTool), kBadInput, "", {}) || FailsWith(r, std::string(kTool), kDegenerate, "", {})) << r.err;
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test

namespace vstcal::cli_test {
namespace {

// --reject-views (docs/tools/calib-tsai.md#reject-views): a view 5× noisier than the others is
// rejected, named on stderr and in the camera's view_rejection block, and the camera is the one
// calibrated without it; with three views the rejection would leave too few, which is refused.
class CliCalibTsaiRejectViews : public CliTest {
 protected:
  // PlanarArgs() views, one of them (views[k]) given 5× the noise.
  Json NoisyView(size_t k, std::vector<std::string> args = PlanarArgs()) {
    Json doc = Synth("in/views.json", Override(args, "--noise", "0.3"));
    const CounterRng extra(5, 1);
    Json& points = doc["views"][k]["points"];
    for (size_t i = 0; i < points.size(); ++i) {
      const auto e = extra.Normal2(i, 0);
      points[i][3] = points[i][3].get<double>() + 0.3 * std::sqrt(24.0) * e[0];
      points[i][4] = points[i][4].get<double>() + 0.3 * std::sqrt(24.0) * e[1];
    }
    WriteJson("in/views.json", doc);
    return doc;
  }
};

TEST_F(CliCalibTsaiRejectViews, NoisyViewIsRejectedAndReported) {
  const Json doc = NoisyView(2);
  const CommandResult r = Run("calib-tsai", {"in/views.json", "-o", "out/camera.json", "--reject-views"});
  ASSERT_EQ(r.exit_code, kOk) << r.err;
  const Json camera = ReadJson("out/camera.json");
  const Json& block = camera.at("view_rejection");
  ASSERT_GE(block.at("rejected").size(), 1u);
  const Json& first = block.at("rejected")[0];
  EXPECT_EQ(first.at("kind"), "view");
  EXPECT_EQ(first.at("view_index"), 2);
  EXPECT_EQ(first.at("view"), doc["views"][2]["name"]);
  EXPECT_GT(first.at("rms_px").get<double>(), first.at("threshold_px").get<double>());
  EXPECT_NE(r.err.find("calib-tsai: warning: --reject-views: rejected view \"" + doc["views"][2]["name"].get<std::string>() +
                       "\" (views[2]) in round 1: view RMS"),
            std::string::npos)
      << r.err;
  EXPECT_NE(r.err.find("  view rejection: "), std::string::npos) << r.err;
  // The same camera as calibrating without that view.
  Json without = doc;
  without["views"].erase(2);
  WriteJson("in/without.json", without);
  ASSERT_EQ(Run("calib-tsai", {"in/without.json", "-o", "out/without.json", "-q"}).exit_code, kOk);
  if (block.at("rejected").size() == 1) {
    EXPECT_NEAR(camera["K"][0][0].get<double>(), ReadJson("out/without.json")["K"][0][0].get<double>(), 1e-6);
  }
  // Off by default: nothing rejected, no block.
  ASSERT_EQ(Run("calib-tsai", {"in/views.json", "-o", "out/kept.json", "-q"}).exit_code, kOk);
  EXPECT_FALSE(ReadJson("out/kept.json").contains("view_rejection"));
}

TEST_F(CliCalibTsaiRejectViews, RefusesToLeaveFewerViewsThanTheModelNeeds) {
  const Json doc = NoisyView(1, Override(PlanarArgs(), "--views", "3"));
  ASSERT_EQ(doc["views"].size(), 3u);
  const CommandResult r = Run("calib-tsai", {"in/views.json", "-o", "out/camera.json", "--reject-views"});
  EXPECT_TRUE(FailsWith(r, "calib-tsai", kBadInput, "in/views.json: --reject-views: view ",
                        {"would leave 2 views, fewer than the 3 planar views need", "drop --reject-views"}));
  EXPECT_TRUE(OutDirEmpty());
}

}  // namespace
}  // namespace vstcal::cli_test
