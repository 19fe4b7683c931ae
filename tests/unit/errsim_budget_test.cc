// The error budget's arithmetic on a nearly linear chain (small, independent errors of four
// sources): the sources' alone mean squares add up to the whole chain's, and halving a source
// removes ¾ of its mean square — both within the Monte Carlo error of the cross terms, which
// common random numbers do not cancel. Display errors never reach the misregistration. The budget
// is measured against the error-free chain's systematic misperception: with the eyes 80 mm behind
// the cameras, or a design IPD of 60 mm on a 64 mm baseline, a source that does not touch what the
// eyes see contributes no misperception, and the display's contribution is its closed form. The
// simulation's numbers do not depend on threads or shards.
#include <gtest/gtest.h>

#include <cmath>

#include "support/vst_scenes.h"
#include "vstcal/errsim/budget.h"
#include "vstcal/errsim/simulation.h"

namespace vstcal {
namespace {

void SetNormal(ChainModel* m, const std::string& name, double sigma) {
  ChainParameter* p = m->Find(name);
  ASSERT_NE(p, nullptr) << name;
  p->distribution = Distribution::MakeNormal(0, sigma);
}

ChainModel LinearishChain(ChainGeometry g) {
  ChainModel m = ChainModel::WithZeroErrors(std::move(g));
  SetNormal(&m, "tracker_alignment.translation.x", 2.0);
  SetNormal(&m, "tracking.translation.y", 1.5);
  SetNormal(&m, "virtual_object_alignment.translation.x", 1.0);
  SetNormal(&m, "virtual_object_alignment.translation.y", 1.0);
  SetNormal(&m, "display.ipd", 3.0);
  return m;
}

std::vector<Eigen::Vector3d> Points() {
  return {testing::WorldFromHmdPoint({100, -50, 800}), testing::WorldFromHmdPoint({-200, 80, 1500}),
          testing::WorldFromHmdPoint({0, 0, 2500})};
}

SimulationOptions Options(uint64_t samples) {
  SimulationOptions o;
  o.samples = o.budget_samples = samples;
  o.seed = 11;
  return o;
}

TEST(ErrorBudget, AloneMeanSquaresAddUpAndHalvingRemovesThreeQuarters) {
  const ChainModel model = LinearishChain(testing::ParallelRig(Points()));
  const uint64_t n = 40000;
  const SimulationResult r = RunSimulation(MakeScenarios(model, true), Options(n), ChainDigest(model));
  const ScenarioTotals all = Totals(model, r.summaries[0], OutputSet::kFull);
  const ErrorBudget budget = Budget(model, r);
  ASSERT_EQ(budget.entries.size(), 4u);
  double sum = 0, cross = 0;
  for (const BudgetEntry& e : budget.entries) {
    const double ms = e.alone.image_rms_px * e.alone.image_rms_px;
    if (e.source == Source::kDisplay) {
      EXPECT_LT(e.alone.image_rms_px, 1e-9);         // cancels in the image, to rounding
      EXPECT_LT(e.alone.misregistration_rms, 1e-9);  // and in what the eyes see as misalignment
      EXPECT_GT(e.alone.misperception_rms, 1.0);     // but not in where things seem to be
    } else {
      EXPECT_EQ(e.alone.misperception_rms, 0.0);  // the video of the physical point does not move
    }
    for (const BudgetEntry& f : budget.entries) {
      if (&f < &e) cross += 4 * ms * f.alone.image_rms_px * f.alone.image_rms_px;
    }
    sum += ms;
  }
  // The cross terms 2·mean(e_s·e_t) have mean 0 and standard error ≈ 2σ_sσ_t/√N.
  const double tolerance = 5 * std::sqrt(cross / n);
  EXPECT_NEAR(all.image_rms_px * all.image_rms_px, sum, tolerance);
  for (const BudgetEntry& e : budget.entries) {
    const double ms_alone = e.alone.image_rms_px * e.alone.image_rms_px;
    EXPECT_NEAR(e.halved.image_rms_px * e.halved.image_rms_px, all.image_rms_px * all.image_rms_px - 0.75 * ms_alone, tolerance)
        << SourceKey(e.source);
    EXPECT_NEAR(e.share_of_image_ms, ms_alone / (all.image_rms_px * all.image_rms_px), 1e-12);
  }
  // Shares of the whole and what they leave out add to 1; zero-mean sources leave out only noise.
  for (const auto& [whole, share] : {std::pair{budget.image, &BudgetEntry::share_of_image_ms},
                                     std::pair{budget.misregistration, &BudgetEntry::share_of_misregistration_ms}}) {
    double total = whole.remainder_share;
    for (const BudgetEntry& e : budget.entries) total += e.*share;
    EXPECT_NEAR(total, 1.0, 1e-15);
    EXPECT_FALSE(whole.none);
  }
  EXPECT_NEAR(budget.image.remainder_mean_square, 0.0, tolerance);
  EXPECT_EQ(budget.entries[budget.by_misperception[0]].source, Source::kDisplay);
  EXPECT_EQ(budget.entries[budget.by_misregistration[0]].source, Source::kTrackerAlignment);
}

// The display alone, relative to the systematic misperception: an IPD error δI on a parallel rig
// (collimated display) makes the eyes see c + o + ((I + δI)/b)(P − c) where the error-free chain
// shows c + o + (I/b)(P − c) — o the camera–eye offset, c the cameras' midpoint — so the
// contribution is (δI/b)(P − c): RMS σ_I·|P − c|/b, whatever o and I. The systematic part is o +
// (I/b − 1)(P − c), reported on its own.
TEST(ErrorBudget, ContributionsAreMeasuredFromTheSystematicError) {
  struct Case {
    const char* name;
    Eigen::Vector3d eye_offset;
    double ipd;
  };
  const double baseline = 64.0;
  for (const Case& c : {Case{"eyes 80 mm behind", {0, 0, -80}, 64.0}, Case{"ipd 60 on 64", {0, 0, 0}, 60.0}}) {
    SCOPED_TRACE(c.name);
    ChainGeometry g = testing::ParallelRig(Points(), 700.0, baseline);
    g.display.eye_centre_in_hmd = c.eye_offset;
    g.display.ipd = c.ipd;
    const ChainModel model = LinearishChain(g);
    const ChainEvaluator chain(model);
    const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;
    double expected_ms = 0;
    for (size_t k = 0; k < g.test_points.size(); ++k) {
      const Eigen::Vector3d p = hmd_from_world * g.test_points[k].point_in_world;
      const Eigen::Vector3d systematic = c.eye_offset + (c.ipd / baseline - 1) * p;
      EXPECT_LT((chain.systematic(k).offset - systematic).norm(), 1e-9 * p.norm());
      expected_ms += std::pow(3.0 * p.norm() / baseline, 2);
    }
    const double expected_rms = std::sqrt(expected_ms / g.test_points.size());
    const uint64_t n = 20000;
    const SimulationResult r = RunSimulation(MakeScenarios(model, true), Options(n), ChainDigest(model));
    const ErrorBudget budget = Budget(model, r);
    for (const BudgetEntry& e : budget.entries) {
      if (e.source == Source::kDisplay) {
        // δI²'s sample mean has relative standard error √(2/N).
        EXPECT_NEAR(e.alone.misperception_rms, expected_rms, 5 * std::sqrt(2.0 / n) * expected_rms);
        EXPECT_LT(e.alone.misregistration_rms, 1e-9);
      } else {
        EXPECT_EQ(e.alone.misperception_rms, 0.0) << SourceKey(e.source);
        EXPECT_GT(e.alone.misregistration_rms, 0.1) << SourceKey(e.source);
      }
    }
  }
}

// Two sources with means in the same direction: tracking's translation error a and the rig mount's
// b, both along hmd x (ParallelRig's cameras have the hmd's axes). Both are left perturbations in
// the hmd frame, so the renderer sees every point moved by exactly a + b: the misregistration is
// (a + b, 0, 0) at every point and each eye's pixel error f·(a + b)/z_k. The whole chain's mean
// square is (a + b)², each source's part a² and b², and what the parts leave out is the cross term
// 2ab — exactly, for fixed biases (docs/math/sensitivity.md#shares-of-the-whole).
TEST(ErrorBudget, TheRemainderIsTheCrossTermOfTwoMeans) {
  const double a = 3.0, b = 5.0, focal = 700.0;
  ChainModel model = ChainModel::WithZeroErrors(testing::ParallelRig(Points(), focal));
  model.Find("tracking.translation.x")->distribution = Distribution::MakeFixed(a);
  model.Find("camera_extrinsic.rig.translation.x")->distribution = Distribution::MakeFixed(b);
  const SimulationResult r = RunSimulation(MakeScenarios(model, true), Options(64), ChainDigest(model));
  const ErrorBudget budget = Budget(model, r);
  ASSERT_EQ(budget.entries.size(), 2u);
  EXPECT_NEAR(budget.misregistration.mean_square, (a + b) * (a + b), 1e-9);
  EXPECT_NEAR(budget.misregistration.remainder_mean_square, 2 * a * b, 1e-9);
  EXPECT_NEAR(budget.misregistration.remainder_share, 2 * a * b / ((a + b) * (a + b)), 1e-12);
  // Image: mean over points and eyes of (f·a/z)², with z the point's depth in each camera.
  const ChainEvaluator chain(model);
  double inverse_z2 = 0;
  for (size_t k = 0; k < chain.num_points(); ++k) {
    for (int e = 0; e < kNumEyes; ++e) inverse_z2 += 1 / std::pow(chain.real_depth(e, k), 2);
  }
  inverse_z2 /= 2.0 * chain.num_points();
  EXPECT_NEAR(budget.image.remainder_mean_square, 2 * a * b * focal * focal * inverse_z2, 1e-9);
  EXPECT_NEAR(budget.image.remainder_share, 2 * a * b / ((a + b) * (a + b)), 1e-9);
  for (const BudgetEntry& e : budget.entries) {
    const double mean = e.source == Source::kTracking ? a : b;
    EXPECT_NEAR(e.share_of_misregistration_ms, mean * mean / ((a + b) * (a + b)), 1e-12);
  }
  EXPECT_EQ(budget.entries[0].share_of_misregistration_ms + budget.entries[1].share_of_misregistration_ms +
                budget.misregistration.remainder_share,
            1.0);
  // No display error: the misperception is none, not a share of rounding.
  EXPECT_TRUE(budget.misperception.none);
  EXPECT_TRUE(std::isnan(budget.entries[0].share_of_misperception_ms));
}

// The same two terms random, N(a, σ²) and N(b, σ²): E|e₁ + e₂|² = a² + σ² + b² + σ² + 2ab, so the
// remainder estimates 2ab, with Monte Carlo error 2σ²/√N (the sample mean of the product of the
// two zero-mean parts; common random numbers cancel the rest).
TEST(ErrorBudget, TheRemainderOfRandomTermsWithMeansIsTheirCrossTerm) {
  const double a = 2.0, b = -1.5, sigma = 1.0;
  ChainModel model = ChainModel::WithZeroErrors(testing::ParallelRig(Points()));
  model.Find("tracking.translation.x")->distribution = Distribution::MakeNormal(a, sigma);
  model.Find("camera_extrinsic.rig.translation.x")->distribution = Distribution::MakeNormal(b, sigma);
  const uint64_t n = 40000;
  const SimulationResult r = RunSimulation(MakeScenarios(model, true), Options(n), ChainDigest(model));
  const ErrorBudget budget = Budget(model, r);
  EXPECT_NEAR(budget.misregistration.remainder_mean_square, 2 * a * b, 5 * 2 * sigma * sigma / std::sqrt(n));
  EXPECT_LT(budget.misregistration.remainder_share, 0);  // opposite means cancel: the parts overstate the whole
}

// The budget's tree: the display's IPD error and its common eye offset, each alone. On a parallel
// rig with a collimated display the IPD error δI moves the seen point by (δI/b)(P − c) and the
// common offset δo by δo itself: the IPD term alone is σ_I·|P − c|/b RMS (as above), the offset
// term σ_o·√3, and the two parts add to the source's (independent, zero-mean, linear) to Monte
// Carlo error. A source of one term is that term, without a scenario of its own.
TEST(ErrorBudget, EachTermOfASourceAlone) {
  const double baseline = 63.0, sigma_ipd = 3.0, sigma_offset = 2.0;
  ChainGeometry g = testing::ParallelRig(Points(), 700.0, baseline);
  ChainModel model = ChainModel::WithZeroErrors(g);
  SetNormal(&model, "display.ipd", sigma_ipd);
  for (const char* axis : {"x", "y", "z"}) SetNormal(&model, std::string("display.eye_offset.") + axis, sigma_offset);
  SetNormal(&model, "tracking.translation.y", 1.5);
  const auto scenarios = MakeScenarios(model, true);
  EXPECT_EQ(scenarios.size(), 1u + 2 * 2 + 2);  // all; tracking and display alone and halved; display's two terms
  const uint64_t n = 40000;
  const SimulationResult r = RunSimulation(scenarios, Options(n), ChainDigest(model));
  const ErrorBudget budget = Budget(model, r);
  const Rigid3d hmd_from_world = g.hmd_from_tracker * g.tracker_from_world;
  double ipd_ms = 0;
  for (const ChainTestPoint& tp : g.test_points) ipd_ms += std::pow(sigma_ipd * (hmd_from_world * tp.point_in_world).norm() / baseline, 2);
  ipd_ms /= g.test_points.size();
  for (const BudgetEntry& e : budget.entries) {
    if (e.source == Source::kTracking) {
      ASSERT_EQ(e.terms.size(), 1u);
      EXPECT_EQ(e.terms[0].name, "tracking.translation");
      EXPECT_EQ(e.terms[0].alone.misregistration_rms, e.alone.misregistration_rms);
      continue;
    }
    ASSERT_EQ(e.terms.size(), 2u);
    EXPECT_EQ(e.terms[0].name, "display.eye_offset");
    EXPECT_EQ(e.terms[1].name, "display.ipd");
    const double offset_ms = 3 * sigma_offset * sigma_offset;
    const double rel = 5 * std::sqrt(2.0 / n);
    EXPECT_NEAR(std::pow(e.terms[1].alone.misperception_rms, 2), ipd_ms, rel * ipd_ms);
    EXPECT_NEAR(std::pow(e.terms[0].alone.misperception_rms, 2), offset_ms, rel * offset_ms);
    const double parts = std::pow(e.terms[0].alone.misperception_rms, 2) + std::pow(e.terms[1].alone.misperception_rms, 2);
    EXPECT_NEAR(std::pow(e.alone.misperception_rms, 2), parts, 5 * 2 * std::sqrt(ipd_ms * offset_ms / n));
    EXPECT_NEAR(e.terms[1].share_of_misperception_ms, std::pow(e.terms[1].alone.misperception_rms, 2) / budget.misperception.mean_square, 1e-12);
    EXPECT_EQ(DominantTerm(e, &TermPart::share_of_misperception_ms), ipd_ms > offset_ms ? 1u : 0u);
  }
}

TEST(Simulation, SameBitsForAnyThreadCountAndShardSplit) {
  const ChainModel model = LinearishChain(testing::ParallelRig(Points()));
  const auto scenarios = MakeScenarios(model, true);
  SimulationOptions one = Options(5000), two = Options(5000);
  one.threads = 1;
  two.threads = 2;
  const SimulationResult a = RunSimulation(scenarios, one, "d");
  const SimulationResult b = RunSimulation(scenarios, two, "d");
  SimulationOptions shard = Options(5000);
  shard.shards = 3;
  SimulationResult merged = RunSimulation(scenarios, shard, "d");
  for (uint64_t i = 1; i < 3; ++i) {
    shard.shard = i;
    MergeSimulation(&merged, RunSimulation(scenarios, shard, "d"));
  }
  ASSERT_TRUE(merged.complete());
  for (size_t s = 0; s < a.summaries.size(); ++s) {
    for (size_t k = 0; k < a.summaries[s].plan().output_names.size(); ++k) {
      const auto x = a.summaries[s].Statistics(k), y = b.summaries[s].Statistics(k), z = merged.summaries[s].Statistics(k);
      EXPECT_EQ(x.mean, y.mean);
      EXPECT_EQ(x.rms, y.rms);
      EXPECT_EQ(x.max, y.max);
      EXPECT_EQ(x.p95.value, y.p95.value);
      EXPECT_EQ(x.mean, z.mean);
      EXPECT_EQ(x.rms, z.rms);
      EXPECT_EQ(x.p99.value, z.p99.value);
    }
  }
}

}  // namespace
}  // namespace vstcal
