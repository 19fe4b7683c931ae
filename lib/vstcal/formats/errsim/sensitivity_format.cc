#include "vstcal/formats/errsim/sensitivity_format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/errsim/chain.h"
#include "vstcal/errsim/measures.h"
#include "vstcal/errsim/models.h"
#include "vstcal/formats/errsim/report_keys.h"

namespace vstcal {
namespace {


OrderedJson Header(std::string_view format, const RunDescription& run, const ChainModel& model) {
  OrderedJson j;
  j[errsim_key::kFormat] = format;
  j[errsim_key::kChain] = run.chain_path;
  j[errsim_key::kChainDigest] = run.digest;
  j[errsim_key::kLengthUnit] = LengthUnitName(model.geometry.length_unit);
  j[errsim_key::kOnly] = run.only;
  j[errsim_key::kWithout] = run.without;
  return j;
}

// RMS over test points (and eyes) of a row of VectorModel outputs: pixels, misregistration,
// misperception (kVectorOutputs, errsim/outputs.h).
struct RowRms {
  double image_px, misregistration, misperception;
};
RowRms Rms(const Eigen::Ref<const Eigen::VectorXd>& row, size_t points) {
  auto sum_of_squares = [&](VectorOutput v, size_t t) {
    return row.segment(kVectorOutputsPerPoint * t + VectorOffset(v), VectorSize(v)).squaredNorm();
  };
  double px = 0, reg = 0, per = 0;
  for (size_t t = 0; t < points; ++t) {
    px += sum_of_squares(VectorOutput::kPixelError, t);
    reg += sum_of_squares(VectorOutput::kMisregistration, t);
    per += sum_of_squares(VectorOutput::kMisperception, t);
  }
  return {std::sqrt(px / (2.0 * points)), std::sqrt(reg / points), std::sqrt(per / points)};
}

}  // namespace

TextAndJson SweepOutput(const ChainModel& model, const RunDescription& run, const std::vector<ParameterSweep>& sweeps,
                        const Provenance& provenance) {
  const size_t points = model.geometry.test_points.size();
  const std::string unit(LengthUnitName(model.geometry.length_unit));
  OrderedJson j = Header(kSweepFormat, run, model);
  j[errsim_key::kOutputs] = VectorOutputNames(model);
  OrderedJson list = OrderedJson::array();
  // One word per quantity: a parameter's "gain" on a measure is the RMS over test points (and eyes)
  // of |∂e/∂θ|, e the measure's error vector; a "slope" is one output's ∂y/∂θ (slope_per_unit, and
  // the page's steepest slope).
  size_t name_width = 44;
  for (const ParameterSweep& sweep : sweeps) name_width = std::max(name_width, model.parameters[sweep.parameter].name().size() + 1);
  std::string text = "err-sim sweep: " + run.chain_path + ": " + std::to_string(sweeps.size()) +
                     " parameters; gain at the nominal point per unit of the parameter (RMS over the test points of "
                     "|d error / d parameter|; a slope is one output's, in the JSON)\n" +
                     "  " + std::string("parameter").append(name_width - 9, ' ') +
                     " image gain     misregistration gain misperception gain\n";
  for (const ParameterSweep& sweep : sweeps) {
    const ChainParameter& p = model.parameters[sweep.parameter];
    const SweepResult& r = sweep.result;
    const double per = p.slot.file_per_internal;
    OrderedJson values = OrderedJson::array(), image = OrderedJson::array(), reg = OrderedJson::array(),
                perc = OrderedJson::array();
    for (size_t k = 0; k < r.values.size(); ++k) {
      values.push_back(r.values[k] * per);
      if (!r.defined[k]) {
        image.push_back(nullptr);
        reg.push_back(nullptr);
        perc.push_back(nullptr);
        continue;
      }
      const RowRms rms = Rms(r.outputs.row(k).transpose(), points);
      image.push_back(NumberOrNull(rms.image_px));
      reg.push_back(NumberOrNull(rms.misregistration));
      perc.push_back(NumberOrNull(rms.misperception));
    }
    OrderedJson e;
    e[errsim_key::kName] = p.name();
    e[errsim_key::kSource] = SourceKey(p.source);
    e[errsim_key::kUnit] = p.slot.file_unit;
    e[errsim_key::kValues] = std::move(values);
    e[TotalKey(Total::kImage)] = std::move(image);
    e[TotalKey(Total::kMisregistration)] = std::move(reg);
    e[TotalKey(Total::kMisperception)] = std::move(perc);
    OrderedJson slope = nullptr;
    if (r.slope_defined) {
      slope = OrderedJson::array();
      for (Eigen::Index o = 0; o < r.slope.size(); ++o) slope.push_back(NumberOrNull(r.slope(o) / per));
      const RowRms rms = Rms(r.slope, points);
      char line[320];
      std::snprintf(line, sizeof line, "  %-*s %10.4g px/%-4s %10.4g %s/%-4s %10.4g %s/%s\n", static_cast<int>(name_width), p.name().c_str(),
                    rms.image_px / per, p.slot.file_unit.c_str(), rms.misregistration / per, unit.c_str(),
                    p.slot.file_unit.c_str(), rms.misperception / per, unit.c_str(), p.slot.file_unit.c_str());
      text += line;
    }
    e[errsim_key::kSlopePerUnit] = std::move(slope);
    list.push_back(std::move(e));
  }
  j[errsim_key::kParameters] = std::move(list);
  j[errsim_key::kProvenance] = ProvenanceToJson(provenance);
  return {std::move(j), std::move(text)};
}

TextAndJson SobolOutput(const ChainModel& model, const RunDescription& run, const std::string& sampling,
                        const SobolResult& r, const Provenance& provenance) {
  OrderedJson j = Header(kSobolFormat, run, model);
  j[errsim_key::kSamples] = run.options.samples;
  j[errsim_key::kSampling] = sampling;
  j[errsim_key::kSeed] = run.options.seed;
  j[errsim_key::kEvaluations] = r.evaluations;
  j[errsim_key::kGroups] = r.group_names;
  auto estimate = [](const Estimate& e) {
    return OrderedJson{{errsim_key::kValue, NumberOrNull(e.value)},
                       {errsim_key::kStandardError, NumberOrNull(e.standard_error)},
                       {errsim_key::kInterval, {NumberOrNull(e.interval.lo), NumberOrNull(e.interval.hi)}}};
  };
  OrderedJson outputs = OrderedJson::array();
  std::string text = "err-sim sobol: " + run.chain_path + ": N = " + std::to_string(run.options.samples) + " (" + sampling +
                     "), " + std::to_string(r.evaluations) + " evaluations; total index S_T per source\n";
  // Columns as wide as the longest name: a name is never cut.
  size_t name_width = 34;
  std::vector<size_t> group_width;
  for (const OutputSensitivity& o : r.outputs) name_width = std::max(name_width, o.name.size() + 1);
  for (const std::string& g : r.group_names) group_width.push_back(std::max<size_t>(8, g.size() + 2));
  text += "  " + std::string(name_width, ' ');
  for (size_t g = 0; g < r.group_names.size(); ++g) {
    text += r.group_names[g] + std::string(g + 1 < r.group_names.size() ? group_width[g] - r.group_names[g].size() : 0, ' ');
  }
  text += "\n";
  // Sobol's outputs are ErrorModel's: the summary shows the headline magnitudes (kMeasures).
  const ErrorOutputs measured(model);
  VSTCAL_CHECK(r.outputs.size() == measured.size(), "Sobol's outputs are ErrorModel's");
  for (size_t i = 0; i < r.outputs.size(); ++i) {
    const OutputSensitivity& o = r.outputs[i];
    OrderedJson groups;
    for (size_t g = 0; g < r.group_names.size(); ++g) {
      groups[r.group_names[g]] = {{errsim_key::kFirst, estimate(o.groups[g].first_order)}, {errsim_key::kTotal, estimate(o.groups[g].total)}};
    }
    outputs.push_back({{errsim_key::kName, o.name}, {errsim_key::kMean, NumberOrNull(o.mean)}, {errsim_key::kVariance, NumberOrNull(o.variance)}, {errsim_key::kIndices, groups}});
    if (measured.is_headline(i)) {
      text += "  " + o.name + std::string(name_width - o.name.size(), ' ');
      for (size_t g = 0; g < o.groups.size(); ++g) {
        char line[64];
        std::snprintf(line, sizeof line, "%-*.3f", static_cast<int>(g + 1 < o.groups.size() ? group_width[g] : 0),
                      o.groups[g].total.value);
        text += line;
      }
      text += "\n";
    }
  }
  j[errsim_key::kOutputs] = std::move(outputs);
  j[errsim_key::kProvenance] = ProvenanceToJson(provenance);
  return {std::move(j), std::move(text)};
}

TextAndJson LinearOutput(const ChainModel& model, const RunDescription& run, const LinearPropagation& linear,
                         const MonteCarloSummary& monte_carlo, const Provenance& provenance) {
  const auto comparison = CompareLinearWithMonteCarlo(linear, monte_carlo);
  OrderedJson j = Header(kLinearFormat, run, model);
  j[errsim_key::kSamples] = run.options.samples;
  j[errsim_key::kSeed] = run.options.seed;
  j[errsim_key::kDerivatives] = DerivativeMethodName(linear.method);
  j[errsim_key::kUndefinedSamples] = monte_carlo.undefined_samples();
  OrderedJson outputs = OrderedJson::array();
  int disagreements = 0;
  std::string text = "err-sim linear: " + run.chain_path + ": first-order σ (J Σ Jᵀ, autodiff) vs Monte Carlo (" +
                     std::to_string(run.options.samples) + " samples)\n  output                                  linear σ     MC σ         rel. diff\n";
  for (size_t k = 0; k < comparison.size(); ++k) {
    const auto& c = comparison[k];
    OrderedJson groups;
    for (size_t g = 0; g < linear.group_names.size(); ++g) groups[linear.group_names[g]] = NumberOrNull(std::sqrt(linear.group_variance(k, g)));
    outputs.push_back({{errsim_key::kName, c.name},
                       {errsim_key::kLinearMean, NumberOrNull(c.linear_mean)},
                       {errsim_key::kMonteCarloMean, NumberOrNull(c.monte_carlo_mean)},
                       {errsim_key::kMeanStandardError, NumberOrNull(c.mean_standard_error)},
                       {errsim_key::kLinearSigma, NumberOrNull(c.linear_sigma)},
                       {errsim_key::kMonteCarloSigma, NumberOrNull(c.monte_carlo_sigma)},
                       {errsim_key::kSigmaStandardError, NumberOrNull(c.sigma_standard_error)},
                       {errsim_key::kSigmaRelativeDifference, NumberOrNull(c.sigma_relative_difference)},
                       {errsim_key::kMeanDisagrees, c.mean_disagrees},
                       {errsim_key::kSigmaDisagrees, c.sigma_disagrees},
                       {errsim_key::kLinearSigmaBySource, groups}});
    disagreements += c.mean_disagrees || c.sigma_disagrees;
    char line[200];
    std::snprintf(line, sizeof line, "  %-38s %-12.4g %-12.4g %+8.2f %%%s\n", c.name.substr(0, 38).c_str(), c.linear_sigma,
                  c.monte_carlo_sigma, 100 * c.sigma_relative_difference,
                  c.mean_disagrees || c.sigma_disagrees ? "  ← not linear here" : "");
    text += line;
  }
  text += "  " + std::to_string(disagreements) + " of " + std::to_string(comparison.size()) +
          " outputs differ by more than the Monte Carlo error explains (3 standard errors)\n";
  j[errsim_key::kOutputs] = std::move(outputs);
  j[errsim_key::kDisagreements] = disagreements;
  j[errsim_key::kProvenance] = ProvenanceToJson(provenance);
  return {std::move(j), std::move(text)};
}

}  // namespace vstcal
