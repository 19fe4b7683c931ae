#include "vstcal/sensitivity/sobol_indices.h"

#include <algorithm>
#include <limits>

#include "vstcal/core/error.h"
#include "vstcal/core/parallel.h"

namespace vstcal {
namespace {

// Samples per parallel task: large enough to amortise the Sobol engine's set-up, small enough to
// balance two threads. The results do not depend on it.
constexpr size_t kSamplesPerTask = 256;

// Model values output-major (value of output k at sample j at [k·N + j]) so the estimator sums
// read each output contiguously.
struct Evaluations {
  size_t num_samples = 0;
  std::vector<double> a, b;               // f(A), f(B)
  std::vector<std::vector<double>> a_b;   // f(A_B^g) per evaluated group
};

struct Undefined {
  uint64_t count = 0;
  uint64_t first_sample = std::numeric_limits<uint64_t>::max();
};

// Groups with at least one non-constant parameter; the others have V_g = VT_g = 0 exactly.
std::vector<size_t> VaryingGroups(const ParameterSpace& space) {
  std::vector<size_t> groups;
  for (size_t g = 0; g < space.num_groups(); ++g) {
    for (size_t i : space.GroupMembers(g)) {
      if (!space.parameter(i).distribution.IsConstant()) {
        groups.push_back(g);
        break;
      }
    }
  }
  return groups;
}

Undefined EvaluateMatrices(const ParameterSpace& space, const Model& model, const SobolOptions& options,
                           const std::vector<size_t>& groups, Evaluations& ev) {
  const size_t n = space.size(), m = model.num_outputs(), big_n = ev.num_samples;
  ev.a.assign(m * big_n, 0.0);
  ev.b.assign(m * big_n, 0.0);
  ev.a_b.assign(groups.size(), std::vector<double>(m * big_n, 0.0));
  const UnitPoints points(options.sampling, 2 * n);
  const size_t num_tasks = (big_n + kSamplesPerTask - 1) / kSamplesPerTask;
  std::vector<Undefined> undefined(num_tasks);

  ParallelFor(num_tasks, options.threads, [&](size_t task) {
    const size_t first = task * kSamplesPerTask, count = std::min(kSamplesPerTask, big_n - first);
    std::vector<double> u(count * 2 * n), theta_a(n), theta_b(n), theta_ab(n), y(m);
    points.Fill(first, count, u.data());
    auto evaluate = [&](const std::vector<double>& theta, std::vector<double>& into, size_t j) {
      if (model.Evaluate(theta.data(), y.data())) {
        for (size_t k = 0; k < m; ++k) into[k * big_n + j] = y[k];
      } else {
        undefined[task].count++;
        undefined[task].first_sample = std::min<uint64_t>(undefined[task].first_sample, j);
      }
    };
    for (size_t s = 0; s < count; ++s) {
      const size_t j = first + s;
      space.ToParameters(&u[s * 2 * n], theta_a.data());
      space.ToParameters(&u[s * 2 * n + n], theta_b.data());
      evaluate(theta_a, ev.a, j);
      evaluate(theta_b, ev.b, j);
      for (size_t g = 0; g < groups.size(); ++g) {
        theta_ab = theta_a;
        for (size_t i : space.GroupMembers(groups[g])) theta_ab[i] = theta_b[i];
        evaluate(theta_ab, ev.a_b[g], j);
      }
    }
  });

  Undefined total;
  for (const Undefined& t : undefined) {
    total.count += t.count;
    total.first_sample = std::min(total.first_sample, t.first_sample);
  }
  return total;
}

// The estimators of the header for output k over `rows` (the identity, or a bootstrap resample).
struct Indices {
  double mean = 0, variance = 0;
  std::vector<double> first, total;  // per evaluated group
};

Indices ComputeIndices(const Evaluations& ev, size_t k, const std::vector<size_t>& rows) {
  const size_t big_n = ev.num_samples;
  const double* a = &ev.a[k * big_n];
  const double* b = &ev.b[k * big_n];
  Indices out;
  for (size_t j : rows) out.mean += a[j] + b[j];
  out.mean /= 2.0 * static_cast<double>(rows.size());
  for (size_t j : rows) out.variance += (a[j] - out.mean) * (a[j] - out.mean) + (b[j] - out.mean) * (b[j] - out.mean);
  out.variance /= 2.0 * static_cast<double>(rows.size());
  out.first.assign(ev.a_b.size(), 0.0);
  out.total.assign(ev.a_b.size(), 0.0);
  for (size_t g = 0; g < ev.a_b.size(); ++g) {
    const double* ab = &ev.a_b[g][k * big_n];
    double first = 0, total = 0;
    for (size_t j : rows) {
      first += (b[j] - out.mean) * (ab[j] - a[j]);
      total += (a[j] - ab[j]) * (a[j] - ab[j]);
    }
    out.first[g] = first / static_cast<double>(rows.size());
    out.total[g] = total / (2.0 * static_cast<double>(rows.size()));
  }
  return out;
}

// S_g and ST_g from variances; a constant output has every index 0.
double Ratio(double partial, double variance) { return variance > 0 ? partial / variance : 0.0; }

}  // namespace

SobolResult EstimateSobolIndices(const ParameterSpace& space, const Model& model, const SobolOptions& options) {
  RequireCompatible(space, model);
  if (options.samples < 2) throw InputError("sobol: need at least 2 samples; raise samples");
  if (!(options.confidence > 0 && options.confidence < 1)) {
    throw InputError("sobol: confidence must be in (0, 1), e.g. 0.95");
  }
  const size_t m = model.num_outputs();
  const std::vector<size_t> groups = VaryingGroups(space);

  SobolResult result;
  result.group_names = space.group_names();
  Evaluations ev;
  ev.num_samples = options.samples;
  const Undefined undefined = EvaluateMatrices(space, model, options, groups, ev);
  result.evaluations = options.samples * (groups.size() + 2);
  result.undefined_evaluations = undefined.count;
  if (undefined.count > 0) {
    result.status = SobolStatus::kModelUndefined;
    result.message = "sobol: the model is undefined at " + std::to_string(undefined.count) + " of " +
                     std::to_string(result.evaluations) + " evaluations (first at sample " +
                     std::to_string(undefined.first_sample) +
                     "); narrow the parameter distributions or make the model defined everywhere";
    return result;
  }

  std::vector<size_t> identity(options.samples);
  for (size_t j = 0; j < identity.size(); ++j) identity[j] = j;
  std::vector<Indices> point(m);
  for (size_t k = 0; k < m; ++k) point[k] = ComputeIndices(ev, k, identity);

  // replicates[r][k]: each replicate fills its own slot, whatever thread runs it.
  const size_t num_replicates = options.bootstrap_resamples;
  std::vector<std::vector<Indices>> replicates(num_replicates);
  ParallelFor(num_replicates, options.threads, [&](size_t r) {
    std::vector<size_t> rows;
    BootstrapRows(options.bootstrap_seed, r, options.samples, rows);
    replicates[r].resize(m);
    for (size_t k = 0; k < m; ++k) replicates[r][k] = ComputeIndices(ev, k, rows);
  });

  result.outputs.resize(m);
  for (size_t k = 0; k < m; ++k) {
    OutputSensitivity& out = result.outputs[k];
    out.name = model.output_names()[k];
    out.mean = point[k].mean;
    out.variance = point[k].variance;
    out.groups.assign(space.num_groups(), GroupSensitivity{});
    for (size_t g = 0; g < groups.size(); ++g) {
      std::vector<double> first(num_replicates), total(num_replicates);
      for (size_t r = 0; r < num_replicates; ++r) {
        first[r] = Ratio(replicates[r][k].first[g], replicates[r][k].variance);
        total[r] = Ratio(replicates[r][k].total[g], replicates[r][k].variance);
      }
      GroupSensitivity& gs = out.groups[groups[g]];
      gs.first_order = SummarizeReplicates(Ratio(point[k].first[g], point[k].variance), std::move(first),
                                           options.confidence);
      gs.total = SummarizeReplicates(Ratio(point[k].total[g], point[k].variance), std::move(total),
                                     options.confidence);
    }
  }
  return result;
}

}  // namespace vstcal
