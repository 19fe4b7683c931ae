// Four samples at a time must give the bits of one at a time: SimdDouble's arithmetic and masks,
// ThetaSampler::FillLanes (AVX2 kernel) against Fill (one draw at a time), and SampleMeasurer's
// lanes (the chain and measures instantiated with SimdDouble, AVX2 clone) against double — on
// the shipped seed 001 chain, and on a chain whose samples often take the rare branches (points
// behind a camera, large rotations, wide angles, fiducial registrations that converge after
// different numbers of iterations), so that groups whose lanes diverge are redone and checked too.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstring>
#include <memory>

#include "support/vst_scenes.h"
#include "vstcal/core/simd_double.h"
#include "vstcal/formats/errsim/chain_reader.h"
#include "vstcal/errsim/sample_measurer.h"
#include "vstcal/errsim/sampler.h"
#include "vstcal/random/philox.h"

namespace vstcal {
namespace {

constexpr size_t kLanes = SampleMeasurer::kLanes;

bool SameBits(double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); }

TEST(SimdDouble, EveryOperationIsTheDoubleOperationPerLane) {
  const CounterRng rng(5, 0);
  for (uint64_t i = 0; i < 2000; ++i) {
    double a[kLanes], b[kLanes];
    for (size_t l = 0; l < kLanes; ++l) {
      const auto z = rng.Normal2(i, static_cast<uint32_t>(l));
      a[l] = std::ldexp(z[0], static_cast<int>(i % 40) - 20);
      b[l] = z[1];
    }
    const SimdDouble x = SimdDouble::Load(a), y = SimdDouble::Load(b);
    const SimdDouble sum = x + y, difference = x - y, product = x * y, quotient = x / y;
    const SimdDouble mixed = 2.5 * x - y / 3.0, root = sqrt(abs(x)), negated = -x;
    const SimdDouble chosen = Select(x < y, x, y);
    for (size_t l = 0; l < kLanes; ++l) {
      const int k = static_cast<int>(l);
      EXPECT_TRUE(SameBits(sum.lane(k), a[l] + b[l]));
      EXPECT_TRUE(SameBits(difference.lane(k), a[l] - b[l]));
      EXPECT_TRUE(SameBits(product.lane(k), a[l] * b[l]));
      EXPECT_TRUE(SameBits(quotient.lane(k), a[l] / b[l]));
      EXPECT_TRUE(SameBits(mixed.lane(k), 2.5 * a[l] - b[l] / 3.0));
      EXPECT_TRUE(SameBits(root.lane(k), std::sqrt(std::abs(a[l]))));
      EXPECT_TRUE(SameBits(negated.lane(k), -a[l]));
      EXPECT_TRUE(SameBits(chosen.lane(k), a[l] < b[l] ? a[l] : b[l]));
      EXPECT_EQ((x < y).lane(k), a[l] < b[l]);
    }
  }
}

TEST(SimdDouble, ABranchOnLanesThatDisagreeIsRecorded) {
  const double lanes[kLanes] = {1, 2, 3, 4};
  const SimdDouble x = SimdDouble::Load(lanes);
  SimdDivergence::Clear();
  EXPECT_TRUE(static_cast<bool>(x > SimdDouble(0)));
  EXPECT_FALSE(static_cast<bool>(x > SimdDouble(5)));
  EXPECT_FALSE(SimdDivergence::Occurred());
  EXPECT_FALSE(static_cast<bool>(x > SimdDouble(2.5)));
  EXPECT_TRUE(SimdDivergence::Occurred());
  SimdDivergence::Clear();
  EXPECT_FALSE(SimdDivergence::Occurred());
}

// Every random parameter of seed 001, plus a uniform and a constant, drawn for enough samples
// that the ziggurat's slow path comes up often: 0.43 % of normal draws leave their rectangle
// (1024 layers): some 1,800 of the 420,000 normal draws here, about 20 of them in the tail
// beyond r (P(|z| > 4.04) = 5.4e-5).
TEST(ThetaSampler, LanesHoldTheBitsOfOneDrawAtATime) {
  ChainModel model = ReadChain(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json");
  model.parameters[1].distribution = Distribution::MakeUniform(-2.0, 3.0);
  model.parameters[2].distribution = Distribution::MakeFixed(0.75);
  const ThetaSampler sampler(model, 99);
  const size_t n = sampler.size(), groups = 1500;
  const uint64_t first = (uint64_t{1} << 32) - 2000;  // the counter's high word changes inside
  std::vector<SimdDouble> lanes(groups * n);
  std::vector<double> rows(groups * kLanes * n);
  sampler.FillLanes(first, groups, lanes.data());
  sampler.Fill(first, groups * kLanes, rows.data());
  size_t mismatches = 0;
  for (size_t s = 0; s < groups * kLanes; ++s) {
    for (size_t j = 0; j < n; ++j) {
      mismatches += !SameBits(lanes[s / kLanes * n + j].lane(static_cast<int>(s % kLanes)), rows[s * n + j]);
    }
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(rows[2], 0.75);
}

// The x86-64 baseline lowering of SimdDouble (two SSE2 operations each), for comparison with the
// AVX2 clone that SampleMeasurer runs on this machine.
[[VSTCAL_FLATTEN_LANES]] void EvaluateBaseline(const ChainEvaluator& chain, const ErrorOutputs& outputs,
                                               const SimdDouble* theta, ChainSample<SimdDouble>* sample,
                                               SimdDouble* y, bool* defined) {
  chain.Evaluate(theta, sample);
  outputs.Measure(chain, *sample, theta, y, defined);
}

struct LaneComparison {
  size_t samples = 0, defined = 0, divergent_groups = 0, mismatches = 0;
};

LaneComparison CompareLanesWithDouble(const ChainModel& model, size_t groups) {
  const ChainEvaluator chain(model);
  const ErrorOutputs outputs(model);
  const ThetaSampler sampler(model, 2024);
  SampleMeasurer lanes(chain, outputs), one(chain, outputs);
  const size_t n = sampler.size(), m = outputs.size(), points = chain.num_points();
  std::vector<double> row(n), y(kLanes * m), y_one(m);
  std::vector<SimdDouble> theta(n), y_simd(m);
  std::vector<uint8_t> defined(m);
  std::unique_ptr<bool[]> baseline_defined(new bool[points]), expected(new bool[points]);
  ChainSample<SimdDouble> sample(points);
  LaneComparison c;
  for (size_t g = 0; g < groups; ++g) {
    const uint64_t first = kLanes * g;
    sampler.FillLanes(first, 1, theta.data());
    const size_t divergent_before = lanes.divergent_groups();
    lanes.MeasureLanes(theta.data(), y.data(), defined.data());
    const bool divergent = lanes.divergent_groups() != divergent_before;
    c.divergent_groups += divergent;
    if (!divergent) {
      SimdDivergence::Clear();
      EvaluateBaseline(chain, outputs, theta.data(), &sample, y_simd.data(), baseline_defined.get());
      c.mismatches += SimdDivergence::Occurred();
    }
    for (size_t l = 0; l < kLanes; ++l) {
      sampler.Fill(first + l, 1, row.data());
      one.MeasureOne(row.data(), y_one.data(), expected.get());
      ++c.samples;
      bool all = true;
      for (size_t p = 0; p < points; ++p) {
        all = all && expected[p];
        if (!divergent) c.mismatches += baseline_defined[p] != expected[p];
      }
      c.defined += all;
      for (size_t k = 0; k < m; ++k) {
        const bool lane_defined = (defined[k] >> l) & 1;
        c.mismatches += lane_defined != expected[outputs.point_of(k)];
        if (!lane_defined || !expected[outputs.point_of(k)]) continue;
        c.mismatches += !SameBits(y[kLanes * k + l], y_one[k]);
        if (!divergent) c.mismatches += !SameBits(y_simd[k].lane(static_cast<int>(l)), y_one[k]);
      }
    }
  }
  return c;
}

TEST(SampleMeasurer, LanesGiveTheBitsOfOneSampleAtATimeOnSeed001) {
  const ChainModel model = ReadChain(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json");
  const LaneComparison c = CompareLanesWithDouble(model, 2500);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(c.defined, c.samples);
  // Most groups run four lanes together: otherwise this test would compare double with double.
  EXPECT_LT(c.divergent_groups, 2500u / 20);
}

// Errors shared and correlated between the eyes (ChainModel::couplings) go through the same
// lanes: seed 001 with fx shared, cx correlated and the screen shift correlated per component.
TEST(SampleMeasurer, LanesGiveTheBitsOfOneSampleAtATimeWithCoupledEyes) {
  ChainModel model = ReadChain(std::string(VSTCAL_SOURCE_DIR) + "/datasets/vst/seed001.json");
  auto slot = [&](Term term, int eye, int i) { return model.layout.Offset(term, eye) + i; };
  model.parameters[slot(Term::kLens, 1, 0)].distribution = Distribution::MakeFixed(0);
  model.couplings = {{slot(Term::kLens, 0, 0), slot(Term::kLens, 1, 0), 1.0},
                     {slot(Term::kLens, 0, 2), slot(Term::kLens, 1, 2), 0.9},
                     {slot(Term::kScreenShift, 0, 0), slot(Term::kScreenShift, 1, 0), -0.4},
                     {slot(Term::kScreenShift, 0, 1), slot(Term::kScreenShift, 1, 1), 0.7}};
  const LaneComparison c = CompareLanesWithDouble(model, 1000);
  EXPECT_EQ(c.mismatches, 0u);
  EXPECT_EQ(c.defined, c.samples);
  EXPECT_LT(c.divergent_groups, 1000u / 20);
}

TEST(SampleMeasurer, LanesThatTakeDifferentBranchesAreRedoneOneAtATime) {
  // Fiducial alignment, a correlated lens, occlusion outputs, and errors large enough that some
  // samples put the near point behind a virtual camera, rotate by more than 0.1 rad or see an
  // overlay more than 0.1 rad off.
  ChainGeometry g = testing::ParallelRig({testing::WorldFromHmdPoint({20, -10, 120}),
                                          testing::WorldFromHmdPoint({-300, 200, 2000})});
  g.test_points[1].surface_behind = 40.0;
  g.head_angular_velocity = Eigen::Vector3d(0.3, -0.2, 0.1);
  // A rational left lens, a camera–eye offset and a virtual image at 1.5 m exercise every path of
  // the chain's display and projection.
  g.cameras[0] = Camera::FromK(g.cameras[0].K(), g.cameras[0].image_size, RationalModel{},
                               std::vector<double>{-0.05, 0.01, 0.001, -0.001, 0.0, 0.02, 0.0, 0.0});
  g.display.eye_centre_in_hmd = Eigen::Vector3d(0, 15, -90);
  g.display.inverse_image_distance = 1 / 1500.0;
  ChainModel model = ChainModel::WithZeroErrors(
      g, {{-120, -80, 0}, {150, -60, 20}, {130, 90, -30}, {-100, 110, 10}});
  model.intrinsic_mixing[0](0, 2) = 0.4;
  // A rig covariance's correlated right camera pose (camera_extrinsic.right.covariance).
  model.extrinsic_mixing[1](3, 1) = 0.8;
  model.extrinsic_mixing[1](0, 5) = 0.002;
  for (ChainParameter& p : model.parameters) {
    const bool angle = p.slot.file_unit == "deg";
    const bool length = p.slot.file_unit == "mm";
    const std::string& name = p.name();
    if (name.find("virtual_object_alignment.fiducial") == 0) p.distribution = Distribution::MakeNormal(0, 2.0);
    if (name.find("tracking") == 0) p.distribution = Distribution::MakeNormal(0, angle ? 0.03 : length ? 40 : 0.01);
    if (name.find("camera_intrinsic") == 0) {
      p.distribution = Distribution::MakeNormal(0, p.slot.file_unit == "px" ? 3.0 : 1e-3);
    }
    if (name.find("camera_extrinsic.right") == 0) p.distribution = Distribution::MakeNormal(0, angle ? 0.002 : 0.5);
    if (name.find("rendering.disparity") == 0) p.distribution = Distribution::MakeUniform(-2.0, 2.0);
    if (name.find("display.") == 0 && length) p.distribution = Distribution::MakeNormal(0, 1.0);
  }
  const LaneComparison c = CompareLanesWithDouble(model, 1500);
  EXPECT_EQ(c.mismatches, 0u);
  // Both kinds of group, in numbers: at least a tenth of each.
  EXPECT_GT(c.divergent_groups, 150u);
  EXPECT_LT(c.divergent_groups, 1350u);
  EXPECT_GT(c.defined, 0u);
  EXPECT_LT(c.defined, c.samples);
}

}  // namespace
}  // namespace vstcal
