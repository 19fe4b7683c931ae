// err-sim's outputs per test point, declared once (docs/math/vst-chain.md#measures), as θ's terms
// are declared in schema.h. Two tables:
//  - kMeasures: the scalar error measures of a sample (ErrorOutputs, measures.h) that Monte Carlo,
//    Sobol and the budget summarise — each eye's image misregistration, Holloway's terms of the
//    misregistration and of the misperception, each eye's occlusion decision;
//  - kTotals: their aggregates over the test points that the report's totals, the budget and the
//    sweep show;
//  - kVectorOutputs: the signed vector errors (ChainEvaluator::operator(), chain.h) that linear
//    propagation and the sweep differentiate.
// Everything else is derived from them: each output's slot within its test point's block
// (MeasureOffset, VectorOffset), the output names ("<point>.misregistration.linear"), which
// outputs the budget's totals keep and which get percentiles, and where each measure sits in the
// report file (formats/errsim/report_keys.h), which the pages read. Adding an output is one row
// here and the line of measures.h or chain.h that computes it.
#pragma once

#include <array>
#include <string>
#include <string_view>

#include "vstcal/errsim/eyes.h"

namespace vstcal {

// Which outputs a Monte Carlo run keeps: every measure (the report's "all" scenario, Sobol), or
// only those the budget's totals need.
enum class OutputSet { kFull, kTotals };

// The unit of an output: px; the chain's length unit; degrees; a decision (1 wrong, 0 right),
// summarised as a rate.
enum class OutputUnit { kPixel, kLength, kDegree, kDecision };
// kPerEye: one slot per eye, in kEyeNames order.
enum class OutputScope { kOnce, kPerEye };

enum class ErrorMeasure : int {
  kImagePixel,
  kMisregistrationLinear,
  kMisregistrationLateral,
  kMisregistrationDepth,
  kMisregistrationDepthAbs,
  kMisregistrationAngular,
  kMisperceptionLinear,
  kMisperceptionLateral,
  kMisperceptionDepth,
  kMisperceptionDepthAbs,
  kMisperceptionAngular,
  kWrongOcclusion,
  kCount
};
inline constexpr int kNumMeasures = static_cast<int>(ErrorMeasure::kCount);

struct MeasureDecl {
  ErrorMeasure measure;
  // The output's name below its test point: <group>[.<eye>].<name>. In the report file the
  // measure's statistics sit at test_points[k].<group>[.<eye>].<name>, a decision's rate at
  // test_points[k].<group>[.<eye>].<name>_rate (report_keys.h).
  std::string_view group;
  std::string_view name;
  OutputScope scope;
  OutputUnit unit;
  bool in_totals;      // kept by OutputSet::kTotals: what the budget's totals need
  bool headline;       // a magnitude the report ranks by: a histogram (percentiles) under kFull, a row of sobol's summary
  bool needs_surface;  // only at test points with a surface_behind (the occlusion decisions)
  // A rise is worse and the report gives the statistic's standard error, so err-sim check judges it
  // (errsim/report_check.h). Not the signed depth parts: a bias of either sign (depth_abs is checked).
  bool checked;
  std::string_view description;
};

// clang-format off
inline constexpr std::array<MeasureDecl, kNumMeasures> kMeasures = {{
    // |q̂ − q| in each eye's image: the overlay against the video.
    {ErrorMeasure::kImagePixel,               "image",           "pixel_px",    OutputScope::kPerEye, OutputUnit::kPixel,    true,  true,  false, true,  "image misregistration |q̂ − q|"},
    // Holloway's terms of P̂' − P' seen from the cyclopean eye (geometry/registration_error.h).
    {ErrorMeasure::kMisregistrationLinear,    "misregistration", "linear",      OutputScope::kOnce,   OutputUnit::kLength,   true,  true,  false, true,  "3-D misregistration |P̂' − P'|"},
    {ErrorMeasure::kMisregistrationLateral,   "misregistration", "lateral",     OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, true,  "its part across the line of sight"},
    {ErrorMeasure::kMisregistrationDepth,     "misregistration", "depth",       OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, false, "its signed part along the line of sight"},
    {ErrorMeasure::kMisregistrationDepthAbs,  "misregistration", "depth_abs",   OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, true,  "the magnitude of the depth part"},
    {ErrorMeasure::kMisregistrationAngular,   "misregistration", "angular_deg", OutputScope::kOnce,   OutputUnit::kDegree,   false, false, false, true,  "the visual angle it subtends"},
    // Holloway's terms of P' − (P + o₀): where the eyes see the point against where it is, beyond
    // the error-free chain's systematic misperception o₀.
    {ErrorMeasure::kMisperceptionLinear,      "misperception",   "linear",      OutputScope::kOnce,   OutputUnit::kLength,   true,  true,  false, true,  "misperception |P' − (P + o₀)|"},
    {ErrorMeasure::kMisperceptionLateral,     "misperception",   "lateral",     OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, true,  "its part across the line of sight"},
    {ErrorMeasure::kMisperceptionDepth,       "misperception",   "depth",       OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, false, "its signed part along the line of sight"},
    {ErrorMeasure::kMisperceptionDepthAbs,    "misperception",   "depth_abs",   OutputScope::kOnce,   OutputUnit::kLength,   false, false, false, true,  "the magnitude of the depth part"},
    {ErrorMeasure::kMisperceptionAngular,     "misperception",   "angular_deg", OutputScope::kOnce,   OutputUnit::kDegree,   false, false, false, true,  "the visual angle it subtends"},
    // The compositor's depth test at the overlay's pixel drew the wrong layer (§4.5).
    {ErrorMeasure::kWrongOcclusion,           "occlusion",       "wrong",       OutputScope::kPerEye, OutputUnit::kDecision, true,  false, true,  true,  "wrong occlusion decision"},
}};
// clang-format on

constexpr const MeasureDecl& Declaration(ErrorMeasure m) { return kMeasures[static_cast<int>(m)]; }
// "<group>[.<eye>].<name>": measure m's output name below its test point.
inline std::string MeasureName(ErrorMeasure m, int eye = 0) {
  const MeasureDecl& d = Declaration(m);
  std::string name(d.group);
  if (d.scope == OutputScope::kPerEye) name.append(".").append(kEyeNames[eye]);
  return name.append(".").append(d.name);
}
// A decision is summarised by its rate, named "<name>_rate" in the report and in err-sim check.
inline constexpr std::string_view kRateSuffix = "_rate";
// The name of measure m's summary statistic below its test point: its output name, or its rate's
// for a decision ("occlusion.left.wrong_rate").
inline std::string SummaryName(ErrorMeasure m, int eye = 0) {
  std::string name = MeasureName(m, eye);
  if (Declaration(m).unit == OutputUnit::kDecision) name.append(kRateSuffix);
  return name;
}
constexpr int SlotsOf(OutputScope scope) { return scope == OutputScope::kPerEye ? kNumEyes : 1; }
constexpr bool InSet(const MeasureDecl& d, OutputSet set) { return set == OutputSet::kFull || d.in_totals; }

// The slot of measure m (of `eye` for a per-eye one) within a test point's block of outputs
// under `set`; −1 when the set leaves it out.
constexpr int MeasureOffset(OutputSet set, ErrorMeasure m, int eye = 0) {
  int offset = 0;
  for (const MeasureDecl& d : kMeasures) {
    if (d.measure == m) return InSet(d, set) ? offset + (d.scope == OutputScope::kPerEye ? eye : 0) : -1;
    if (InSet(d, set)) offset += SlotsOf(d.scope);
  }
  return -1;
}
// The size of a test point's block under `set`, with or without a surface behind it.
constexpr int PointMeasures(OutputSet set, bool surface) {
  int size = 0;
  for (const MeasureDecl& d : kMeasures) {
    if (InSet(d, set) && (surface || !d.needs_surface)) size += SlotsOf(d.scope);
  }
  return size;
}

namespace detail {
constexpr bool MeasuresInOrder() {
  for (int i = 0; i < kNumMeasures; ++i) {
    if (static_cast<int>(kMeasures[i].measure) != i) return false;
    // The outputs that exist only with a surface come last: every other slot is where it is at
    // every test point.
    if (i > 0 && kMeasures[i - 1].needs_surface && !kMeasures[i].needs_surface) return false;
    // A decision is summarised as a rate, never a histogram.
    if (kMeasures[i].unit == OutputUnit::kDecision && kMeasures[i].headline) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::MeasuresInOrder(),
              "kMeasures must list every ErrorMeasure in order, those that need a surface last, no percentiles of a decision");

// The whole chain's aggregates of a scenario over its test points (errsim/budget.h,
// ScenarioTotals): the report's totals, the budget's columns, the sweep's curves.
enum class Total : int { kImage, kMisregistration, kMisperception, kWrongOcclusion, kCount };
inline constexpr int kNumTotals = static_cast<int>(Total::kCount);

struct TotalDecl {
  Total total;
  std::string_view key;      // in files: under "totals", a budget row's "alone" and "halved", a sweep's parameter
  // The budget's name of the measure it totals ("image"): share_of_<measure>_ms, the ranking and the
  // whole by it; empty when the budget does not rank by it.
  std::string_view measure;
  ErrorMeasure of;           // the per-point measure it aggregates
  OutputUnit unit;
  std::string_view description;
};

// clang-format off
inline constexpr std::array<TotalDecl, kNumTotals> kTotals = {{
    {Total::kImage,           "image_rms_px",         "image",           ErrorMeasure::kImagePixel,            OutputUnit::kPixel,    "√(mean over test points and eyes of RMS(|q̂ − q|)²)"},
    {Total::kMisregistration, "misregistration_rms",  "misregistration", ErrorMeasure::kMisregistrationLinear, OutputUnit::kLength,   "√(mean over test points of RMS(misregistration linear)²)"},
    {Total::kMisperception,   "misperception_rms",    "misperception",   ErrorMeasure::kMisperceptionLinear,   OutputUnit::kLength,   "the same for the misperception, beyond the systematic one"},
    {Total::kWrongOcclusion,  "wrong_occlusion_rate", "",                ErrorMeasure::kWrongOcclusion,        OutputUnit::kDecision, "mean over occlusion points and eyes"},
}};
// clang-format on

constexpr const TotalDecl& Declaration(Total t) { return kTotals[static_cast<int>(t)]; }

namespace detail {
// True when row i of `table` declares the enumerator i (its field `key`): Declaration(e) indexes
// the table by the enumerator.
template <typename Decl, size_t N, typename Key>
constexpr bool ListedInOrder(const std::array<Decl, N>& table, Key Decl::*key) {
  for (size_t i = 0; i < N; ++i) {
    if (static_cast<size_t>(table[i].*key) != i) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::ListedInOrder(kTotals, &TotalDecl::total), "kTotals must list every Total in order");

// The signed vector errors of a test point, for linear propagation and the sweep's slopes.
enum class VectorOutput : int { kPixelError, kMisregistration, kMisperception, kCount };
inline constexpr int kNumVectorOutputs = static_cast<int>(VectorOutput::kCount);

struct VectorOutputDecl {
  VectorOutput output;
  // Its components' names below the test point: [<group>.][<eye>.]<component>.
  std::string_view group;
  std::array<std::string_view, 3> components;
  int size;  // components used
  OutputScope scope;
  OutputUnit unit;
  std::string_view description;
};

// clang-format off
inline constexpr std::array<VectorOutputDecl, kNumVectorOutputs> kVectorOutputs = {{
    {VectorOutput::kPixelError,      "",                {"du_px", "dv_px", ""}, 2, OutputScope::kPerEye, OutputUnit::kPixel,  "q̂ − q in the eye's image"},
    {VectorOutput::kMisregistration, "misregistration", {"dx", "dy", "dz"},     3, OutputScope::kOnce,   OutputUnit::kLength, "P̂' − P', hmd frame"},
    {VectorOutput::kMisperception,   "misperception",   {"dx", "dy", "dz"},     3, OutputScope::kOnce,   OutputUnit::kLength, "P' − (P + o₀), hmd frame"},
}};
// clang-format on

constexpr const VectorOutputDecl& Declaration(VectorOutput v) { return kVectorOutputs[static_cast<int>(v)]; }
// "[<group>.][<eye>.]<component>": a component's output name below its test point.
inline std::string VectorOutputName(VectorOutput v, int eye, int component) {
  const VectorOutputDecl& d = Declaration(v);
  std::string name;
  if (!d.group.empty()) name.append(d.group).append(".");
  if (d.scope == OutputScope::kPerEye) name.append(kEyeNames[eye]).append(".");
  return name.append(d.components[component]);
}
// The size of a vector output over all its eyes.
constexpr int VectorSize(VectorOutput v) { return Declaration(v).size * SlotsOf(Declaration(v).scope); }
// The first slot of output v (of `eye` for a per-eye one) within a test point's block.
constexpr int VectorOffset(VectorOutput v, int eye = 0) {
  int offset = 0;
  for (int i = 0; i < static_cast<int>(v); ++i) offset += VectorSize(static_cast<VectorOutput>(i));
  return offset + (Declaration(v).scope == OutputScope::kPerEye ? eye * Declaration(v).size : 0);
}
constexpr int VectorOutputsPerPoint() {
  int size = 0;
  for (const VectorOutputDecl& d : kVectorOutputs) size += d.size * SlotsOf(d.scope);
  return size;
}
inline constexpr int kVectorOutputsPerPoint = VectorOutputsPerPoint();

static_assert(detail::ListedInOrder(kVectorOutputs, &VectorOutputDecl::output), "kVectorOutputs must list every VectorOutput in order");

}  // namespace vstcal
