// Errors shared and correlated between the eyes (docs/math/vst-chain.md#correlated-eyes), against
// closed forms on a parallel orthostereo rig (pinhole, fx = 700, 63 mm baseline, eyes at the
// cameras): the same cx error in both eyes moves the overlay of a point on the cyclopean axis
// sideways by Z·δcx/f and not at all in depth; a correlation ρ between the eyes' cx errors scales
// the disparity error's variance by 2(1 − ρ) (unequal σ's: σ_L² + σ_R² − 2ρσ_Lσ_R), and each
// eye keeps its own σ. The reader's bad inputs name the field and the fix; a written chain with
// shared and correlated terms reads back the same.
#include <gtest/gtest.h>

#include <cmath>

#include "support/vst_scenes.h"
#include "vstcal/core/error.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/errsim/simulation.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/formats/errsim/chain_writer.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {
namespace {

constexpr double kFocal = 700.0, kDepth = 1500.0;

OrderedJson Normal(double sigma) { return testing::ChainNormal(sigma); }

// The hmd at the world origin; a test point on the cyclopean axis at depth kDepth and one off it.
OrderedJson Chain(const OrderedJson& sources) { return testing::ParallelRigChain(sources, kFocal, kDepth); }

ChainSpec Spec(const OrderedJson& chain) { return ChainSpecFromJson(JsonDocument::Parse(chain.dump(), "chain.json"), "."); }
ChainModel Model(const OrderedJson& chain) { return BuildChainModel(Spec(chain)); }

std::string ReadError(const OrderedJson& chain) {
  try {
    Model(chain);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// Samples of the chain at θ drawn by err-sim's sampler.
template <typename Visit>
void ForEachSample(const ChainModel& model, size_t n, Visit visit) {
  const ChainEvaluator chain(model);
  const ThetaSampler sampler(model, 17);
  std::vector<double> theta(sampler.size());
  ChainSample<double> sample(chain.num_points());
  for (size_t i = 0; i < n; ++i) {
    sampler.Fill(i, 1, theta.data());
    chain.Evaluate(theta.data(), &sample);
    visit(theta, sample);
  }
}

TEST(CorrelatedEyes, TheSameCxErrorInBothEyesMovesTheOverlaySidewaysOnly) {
  const ChainModel model = Model(Chain({{"camera_intrinsic", {{"shared", {{"cx", Normal(1.0)}}}}}}));
  const int left_cx = model.layout.Offset(Term::kLens, 0) + 2;
  double largest_depth = 0, largest_lateral_error = 0, largest_disparity = 0, sum_squares = 0;
  const size_t n = 2000;
  ForEachSample(model, n, [&](const std::vector<double>& theta, const ChainSample<double>& s) {
    const PointSample<double>& axis = s.points[0];
    ASSERT_TRUE(axis.valid());
    const Eigen::Vector3d misregistration = axis.overlay - axis.seen;  // hmd frame: z is the cyclopean axis
    const double dcx = theta[left_cx];
    largest_depth = std::max(largest_depth, std::abs(misregistration.z()));
    largest_lateral_error = std::max(largest_lateral_error, std::abs(misregistration.x() - kDepth * dcx / kFocal));
    largest_disparity = std::max(largest_disparity, std::abs(axis.pixel_error[0].x() - axis.pixel_error[1].x()));
    EXPECT_NEAR(axis.pixel_error[0].x(), dcx, 1e-9);
    sum_squares += dcx * dcx;
  });
  EXPECT_LT(largest_disparity, 1e-9);  // one draw: no disparity error
  EXPECT_LT(largest_depth, 1e-9 * kDepth);
  EXPECT_LT(largest_lateral_error, 1e-9 * kDepth);
  EXPECT_NEAR(sum_squares / n, 1.0, 5 * std::sqrt(2.0 / n));  // σ = 1 px in each eye
}

// Each eye's cx error e_L, e_R with σ_L, σ_R and correlation ρ: the disparity error e_L − e_R has
// variance σ_L² + σ_R² − 2ρσ_Lσ_R, 2σ²(1 − ρ) for equal σ's (1.41 px RMS for 1 px per eye, ρ = 0).
TEST(CorrelatedEyes, CorrelationScalesTheDisparityVariance) {
  struct Case {
    double sigma_left, sigma_right, rho;
  };
  for (const Case c : {Case{1, 1, 0}, Case{1, 1, 0.5}, Case{1, 1, 0.9}, Case{1, 1, -0.6}, Case{1, 1, 1}, Case{1, 2, 0.6},
                       Case{2, 0.5, -0.3}}) {
    SCOPED_TRACE(::testing::Message() << "σ " << c.sigma_left << ", " << c.sigma_right << ", ρ " << c.rho);
    const ChainModel model = Model(Chain({{"camera_intrinsic",
                                           {{"left", {{"cx", Normal(c.sigma_left)}}},
                                            {"right", {{"cx", Normal(c.sigma_right)}}},
                                            {"correlation", {{"cx", c.rho}}}}}}));
    const size_t n = 40000;
    double ll = 0, rr = 0, lr = 0, dd = 0;
    ForEachSample(model, n, [&](const std::vector<double>&, const ChainSample<double>& s) {
      const double l = s.points[0].pixel_error[0].x(), r = s.points[0].pixel_error[1].x();
      ll += l * l, rr += r * r, lr += l * r, dd += (l - r) * (l - r);
    });
    const double sl = c.sigma_left, sr = c.sigma_right;
    const double disparity = sl * sl + sr * sr - 2 * c.rho * sl * sr;
    // A sample variance's relative standard error is √(2/N); a covariance's standard error is
    // σ_Lσ_R·√((1 + ρ²)/N).
    const double rel = 5 * std::sqrt(2.0 / n);
    EXPECT_NEAR(ll / n, sl * sl, rel * sl * sl);
    EXPECT_NEAR(rr / n, sr * sr, rel * sr * sr);
    EXPECT_NEAR(lr / n, c.rho * sl * sr, 5 * sl * sr * std::sqrt((1 + c.rho * c.rho) / n));
    if (c.rho == 1 && sl == sr) {
      EXPECT_LT(dd / n, 1e-24);
    } else {
      EXPECT_NEAR(dd / n, disparity, rel * disparity);
    }
    if (sl == sr) {
      EXPECT_NEAR(dd / n / (2 * sl * sl), 1 - c.rho, rel * (1 - c.rho) + 1e-12);
    }
  }
}

// A shared term is the correlation-1 limit: the same numbers as ρ = 1 with equal σ's, and the
// simulation keeps its bits whatever the thread count or shard split.
TEST(CorrelatedEyes, SharedIsCorrelationOneAndRunsAreReproducible) {
  const OrderedJson shared = Chain({{"display", {{"shared", {{"screen_shift_px", Normal(0.5)}}}}},
                                    {"camera_intrinsic", {{"shared", {{"fx", Normal(2.0)}}}, {"both", {{"cx", Normal(1.0)}}},
                                                          {"correlation", {{"cx", 0.8}}}}}});
  const ChainModel model = Model(shared);
  EXPECT_EQ(model.couplings.size(), 4u);  // screen shift u, v; fx; cx
  testing::ExpectTheSameBitsWhateverThreadsAndShards(model);
  // Written and read back: the same chain (same digest), and a fixed point of writing.
  const Provenance provenance{"errsim_correlation_test", {}, std::nullopt};
  const OrderedJson written = ChainSpecToJson(Spec(shared), provenance);
  EXPECT_EQ(ChainDigest(Model(written)), ChainDigest(model));
  EXPECT_EQ(ChainSpecToJson(Spec(written), provenance).dump(), written.dump());
  EXPECT_EQ(written["sources"]["camera_intrinsic"]["correlation"]["cx"], 0.8);
  // Without a coupling the digest is the independent chain's, and a coupling changes it.
  OrderedJson independent = shared;
  independent["sources"]["camera_intrinsic"].erase("correlation");
  EXPECT_NE(ChainDigest(Model(independent)), ChainDigest(model));
}

TEST(CorrelatedEyes, BadInputNamesTheFieldAndTheFix) {
  auto error = [](const OrderedJson& intrinsic) { return ReadError(Chain({{"camera_intrinsic", intrinsic}})); };
  EXPECT_EQ(error({{"both", {{"cx", Normal(1.0)}}}, {"correlation", {{"cx", 1.5}}}}),
            "chain.json: sources.camera_intrinsic.correlation.cx: must lie within [-1, 1], got 1.5; give the correlation ρ "
            "between the eyes' draws, -1 ≤ ρ ≤ 1 (ρ = 1 with equal σ's is \"shared\")");
  EXPECT_EQ(ReadError(Chain({{"display", {{"both", {{"eyepoint", Normal(1.0)}}}, {"correlation", {{"eyepoint", {0.5, -1.01, 0}}}}}}})),
            "chain.json: sources.display.correlation.eyepoint[1]: must lie within [-1, 1], got -1.01; give the correlation ρ "
            "between the eyes' draws, -1 ≤ ρ ≤ 1 (ρ = 1 with equal σ's is \"shared\")");
  EXPECT_EQ(error({{"left", {{"cx", Normal(1.0)}}}, {"shared", {{"cx", Normal(1.0)}}}}),
            "chain.json: sources.camera_intrinsic.shared.cx: given in both \"shared\" and \"left\"; give the term once: in "
            "\"shared\" (one draw for both eyes) or in \"left\"/\"right\"/\"both\" (a draw per eye, optionally with a \"correlation\")");
  EXPECT_EQ(ReadError(Chain({{"display", {{"both", {{"screen_shift_px", Normal(1.0)}}}, {"shared", {{"screen_shift_px", Normal(1.0)}}}}}})),
            "chain.json: sources.display.shared.screen_shift_px: given in both \"shared\" and \"both\"; give the term once: in "
            "\"shared\" (one draw for both eyes) or in \"left\"/\"right\"/\"both\" (a draw per eye, optionally with a \"correlation\")");
  EXPECT_EQ(error({{"shared", {{"cx", Normal(1.0)}}}, {"correlation", {{"cx", 0.5}}}}),
            "chain.json: sources.camera_intrinsic.correlation.cx: the term is \"shared\" (one draw for both eyes, ρ = 1); delete "
            "the correlation, or give the term in \"both\" or \"left\"/\"right\"");
  EXPECT_EQ(error({{"left", {{"cx", Normal(1.0)}}}, {"correlation", {{"cx", 0.5}}}}),
            "chain.json: sources.camera_intrinsic.correlation.cx: the term is not given for both eyes; give it in \"both\", or in "
            "\"left\" and \"right\", as normal σ's");
  EXPECT_EQ(error({{"both", {{"cx", {{"distribution", "uniform"}, {"half_width", 1.0}}}}}, {"correlation", {{"cx", 0.5}}}}),
            "chain.json: sources.camera_intrinsic.correlation.cx: needs normal distributions, but the term is not normal; give "
            "normal σ's for both eyes, or put the term in \"shared\" for one draw of any distribution");
  EXPECT_EQ(ReadError(Chain({{"tracking", {{"shared", {{"latency_s", Normal(0.01)}}}}}})).substr(0, 48),
            "chain.json: sources.tracking.shared: unknown ter");
}

}  // namespace
}  // namespace vstcal
