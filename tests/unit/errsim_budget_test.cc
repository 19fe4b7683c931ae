// The error budget's arithmetic on a nearly linear chain (small, independent errors of four
// sources): the sources' alone mean squares add up to the whole chain's, and halving a source
// removes ¾ of its mean square — both within the Monte Carlo error of the cross terms, which
// common random numbers do not cancel. Display errors never reach the image. The simulation's
// numbers do not depend on threads or shards.
#include <gtest/gtest.h>

#include <cmath>

#include "support/vst_scenes.h"
#include "vstcal/errsim/report.h"
#include "vstcal/errsim/simulation.h"

namespace vstcal::errsim {
namespace {

ChainModel LinearishChain() {
  ChainGeometry g = testing::ParallelRig({testing::WorldFromHmdPoint({100, -50, 800}), testing::WorldFromHmdPoint({-200, 80, 1500}),
                                          testing::WorldFromHmdPoint({0, 0, 2500})});
  ChainModel m = ChainModel::WithZeroErrors(g);
  auto set = [&](const std::string& name, double sigma) {
    for (auto& p : m.parameters) {
      if (p.name == name) p.distribution = Distribution::MakeNormal(0, sigma);
    }
  };
  set("tracker_alignment.translation.x", 2.0);
  set("tracking.translation.y", 1.5);
  set("virtual_object_alignment.translation.x", 1.0);
  set("virtual_object_alignment.translation.y", 1.0);
  set("display.ipd", 3.0);
  return m;
}

SimulationOptions Options(uint64_t samples) {
  SimulationOptions o;
  o.samples = o.budget_samples = samples;
  o.seed = 11;
  return o;
}

TEST(ErrorBudget, AloneMeanSquaresAddUpAndHalvingRemovesThreeQuarters) {
  const ChainModel model = LinearishChain();
  const uint64_t n = 40000;
  const SimulationResult r = RunSimulation(MakeScenarios(model, true), Options(n), ChainDigest(model));
  const ScenarioTotals all = Totals(model, r.summaries[0]);
  const std::vector<BudgetEntry> budget = Budget(model, r);
  ASSERT_EQ(budget.size(), 4u);
  double sum = 0, cross = 0;
  for (const BudgetEntry& e : budget) {
    const double ms = e.alone.image_rms_px * e.alone.image_rms_px;
    if (e.source == Source::kDisplay) {
      EXPECT_LT(e.alone.image_rms_px, 1e-9);  // cancels in the image, to rounding
    }
    for (const BudgetEntry& f : budget) {
      if (&f < &e) cross += 4 * ms * f.alone.image_rms_px * f.alone.image_rms_px;
    }
    sum += ms;
  }
  // The cross terms 2·mean(e_s·e_t) have mean 0 and standard error ≈ 2σ_sσ_t/√N.
  const double tolerance = 5 * std::sqrt(cross / n);
  EXPECT_NEAR(all.image_rms_px * all.image_rms_px, sum, tolerance);
  for (const BudgetEntry& e : budget) {
    const double ms_alone = e.alone.image_rms_px * e.alone.image_rms_px;
    EXPECT_NEAR(e.halved.image_rms_px * e.halved.image_rms_px, all.image_rms_px * all.image_rms_px - 0.75 * ms_alone, tolerance)
        << SourceKey(e.source);
    EXPECT_NEAR(e.share_of_image_ms, ms_alone / sum, 1e-12);
  }
}

TEST(Simulation, SameBitsForAnyThreadCountAndShardSplit) {
  const ChainModel model = LinearishChain();
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
}  // namespace vstcal::errsim
