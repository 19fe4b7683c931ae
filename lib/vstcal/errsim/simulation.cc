#include "vstcal/errsim/simulation.h"

#include <algorithm>
#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/errsim/engine.h"
#include "vstcal/core/option_name.h"

namespace vstcal {

namespace {

bool ParameterActive(const ChainParameter& p) { return !(p.distribution.IsConstant() && p.distribution.Mean() == 0); }

std::string TermName(const TermDecl& d) {
  std::string name(SourceKey(d.source));
  if (!d.group.empty()) name.append(".").append(d.group);
  return name.append(".").append(d.extent == TermExtent::kLens ? std::string_view("lens") : d.name);
}

}  // namespace

std::vector<TermGroup> ActiveTerms(const ChainModel& model, Source source) {
  std::vector<TermGroup> out;
  const bool rig_covariance = !model.extrinsic_mixing[1].isIdentity(0.0);
  const bool mount_covariance = !model.mount_mixing.isIdentity(0.0);
  const bool alignment_covariance = !model.tracker_alignment_mixing.isIdentity(0.0);
  for (const TermDecl& d : kTerms) {
    if (d.source != source) continue;
    const bool active = std::any_of(model.parameters.begin(), model.parameters.end(),
                                    [&](const ChainParameter& p) { return p.slot.term == d.term && ParameterActive(p); });
    if (!active) continue;
    // A measured pose covariance mixes a rotation and a translation term into one correlated draw:
    // they are one term of the budget (their slots hold the covariance's principal modes).
    const char* pose = nullptr;
    if (rig_covariance && (d.term == Term::kCameraRotation || d.term == Term::kCameraTranslation)) pose = "camera_extrinsic.pose";
    if (mount_covariance && (d.term == Term::kRigRotation || d.term == Term::kRigTranslation)) pose = "camera_extrinsic.rig.pose";
    if (alignment_covariance && (d.term == Term::kTrackerAlignmentRotation || d.term == Term::kTrackerAlignmentTranslation)) {
      pose = "tracker_alignment.pose";
    }
    if (pose) {
      if (out.empty() || out.back().name != pose) out.push_back({pose, {}});
      out.back().terms.push_back(d.term);
      continue;
    }
    out.push_back({TermName(d), {d.term}});
  }
  return out;
}

std::vector<DistributionOrigin> OriginsOf(const ChainModel& model, const std::vector<Term>& terms) {
  std::vector<DistributionOrigin> out;
  for (const ChainParameter& p : model.parameters) {
    if (!ParameterActive(p) || std::find(terms.begin(), terms.end(), p.slot.term) == terms.end()) continue;
    if (std::find(out.begin(), out.end(), p.origin) == out.end()) out.push_back(p.origin);
  }
  return out;
}

ChainModel WithTermsOnly(const ChainModel& model, const TermGroup& group) {
  ChainModel m = model;
  for (ChainParameter& p : m.parameters) {
    if (std::find(group.terms.begin(), group.terms.end(), p.slot.term) == group.terms.end()) {
      p.distribution = Distribution::MakeFixed(0);
    }
  }
  return m;
}

std::vector<Scenario> MakeScenarios(const ChainModel& model, bool budget) {
  std::vector<Scenario> out = {{"all", model}};
  if (!budget) return out;
  for (int s = 0; s < kNumSources; ++s) {
    const Source source = static_cast<Source>(s);
    if (!model.SourceActive(source)) continue;
    std::array<bool, kNumSources> alone{};
    alone[s] = true;
    out.push_back({"alone:" + std::string(SourceKey(source)), model.WithSources(alone)});
    out.push_back({"halved:" + std::string(SourceKey(source)), model.WithSourceScaled(source, 0.5)});
  }
  // The terms of each source with more than one (a source of one term is that term).
  for (int s = 0; s < kNumSources; ++s) {
    const std::vector<TermGroup> terms = ActiveTerms(model, static_cast<Source>(s));
    if (terms.size() < 2) continue;
    for (const TermGroup& t : terms) out.push_back({"term:" + t.name, WithTermsOnly(model, t)});
  }
  return out;
}

ChainModel SelectSources(const ChainModel& model, const std::vector<Source>& only, const std::vector<Source>& without) {
  std::array<bool, kNumSources> active{};
  active.fill(only.empty());
  for (const Source s : only) active[static_cast<int>(s)] = true;
  for (const Source s : without) active[static_cast<int>(s)] = false;
  return model.WithSources(active);
}

namespace {

class Fnv1a {
 public:
  void Add(const std::string& text) {
    for (const unsigned char c : text) hash_ = (hash_ ^ c) * 0x100000001b3ull;
    hash_ = (hash_ ^ 0xff) * 0x100000001b3ull;  // separator
  }
  void Add(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    Add(std::string(buf));
  }
  template <typename Derived>
  void Add(const Eigen::MatrixBase<Derived>& m) {
    for (Eigen::Index r = 0; r < m.rows(); ++r)
      for (Eigen::Index c = 0; c < m.cols(); ++c) Add(static_cast<double>(m(r, c)));
  }
  void Add(const Rigid3d& t) {
    Add(t.R);
    Add(t.t);
  }
  std::string Hex() const {
    char buf[20];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash_));
    return buf;
  }

 private:
  uint64_t hash_ = 0xcbf29ce484222325ull;
};

}  // namespace

std::string ChainDigest(const ChainModel& model) {
  Fnv1a h;
  const ChainGeometry& g = model.geometry;
  h.Add(std::string(LengthUnitName(g.length_unit)));
  for (const Rigid3d& t : {g.tracker_from_world, g.hmd_from_tracker, g.camera_from_hmd[0], g.camera_from_hmd[1],
                           g.world_from_virtual, g.world_from_object}) {
    h.Add(t);
  }
  for (const auto& cameras : {g.cameras, model.renderer}) {
    for (const Camera& c : cameras) {
      h.Add(std::string(LensModelName(c.model)));
      for (double p : c.params) h.Add(p);
      h.Add(static_cast<double>(c.image_size.width));
      h.Add(static_cast<double>(c.image_size.height));
    }
  }
  h.Add(g.display.ipd);
  h.Add(g.display.eye_centre_in_hmd);
  h.Add(g.display.inverse_image_distance);
  // Only when given: a chain whose display shows the camera's field of view keeps its digest.
  for (int e = 0; e < kNumEyes; ++e) {
    if (!g.display.focal_px[e]) continue;
    h.Add("display_focal");
    h.Add(static_cast<double>(e));
    h.Add(*g.display.focal_px[e]);
  }
  h.Add(g.head_angular_velocity);
  h.Add(g.head_linear_velocity);
  for (const ChainTestPoint& tp : g.test_points) {
    h.Add(tp.name);
    h.Add(tp.point_in_world);
    h.Add(tp.surface_behind ? *tp.surface_behind : 0.0);
  }
  for (const auto& f : model.fiducials_in_object) h.Add(f);
  for (const auto& m : model.intrinsic_mixing) h.Add(m);
  // Only when used: a chain without a rig covariance keeps the digest it always had.
  for (const auto& m : model.extrinsic_mixing) {
    if (!m.isIdentity(0.0)) h.Add(m);
  }
  for (const auto* m : {&model.mount_mixing, &model.tracker_alignment_mixing}) {
    if (!m->isIdentity(0.0)) h.Add(*m);
  }
  // Likewise only when used: shared, correlated and jointly drawn terms.
  for (const ChainModel::SlotCoupling& c : model.couplings) {
    h.Add("coupling");
    h.Add(static_cast<double>(c.from));
    h.Add(static_cast<double>(c.to));
    h.Add(c.alpha);
  }
  for (const ChainParameter& p : model.parameters) {
    h.Add(p.name());
    h.Add(p.distribution.Describe());
  }
  return h.Hex();
}

bool SimulationResult::complete() const {
  return std::all_of(summaries.begin(), summaries.end(), [](const auto& s) { return s.complete(); });
}

namespace {

ChainMonteCarloOptions ScenarioOptions(const Scenario& scenario, const SimulationOptions& options, const std::string& digest) {
  ChainMonteCarloOptions mc;
  mc.samples = scenario.name == "all" ? options.samples : options.budget_samples;
  mc.block_size = options.block_size;
  mc.seed = options.seed;
  mc.run_id = "err-sim/" + digest + "/" + scenario.name + "/seed=" + std::to_string(options.seed);
  mc.threads = options.threads;
  mc.outputs = scenario.name == "all" ? OutputSet::kFull : OutputSet::kTotals;
  return mc;
}

}  // namespace

SimulationResult EmptySimulation(const std::vector<Scenario>& scenarios, const SimulationOptions& options,
                                 const std::string& digest) {
  SimulationResult result;
  for (const Scenario& scenario : scenarios) {
    result.scenarios.push_back(scenario.name);
    result.summaries.emplace_back(ChainPlan(scenario.model, ScenarioOptions(scenario, options, digest)));
  }
  return result;
}

SimulationResult RunSimulation(const std::vector<Scenario>& scenarios, const SimulationOptions& options,
                               const std::string& digest, const Progress& progress) {
  SimulationResult result;
  // Each scenario's blocks are run in `pieces` consecutive sub-shards of this shard (shard i of N is
  // exactly sub-shards i·M … i·M + M − 1 of N·M), merged as they come: identical bits, and a place
  // to report progress.
  double total = 0, done = 0;
  for (const Scenario& s : scenarios) total += static_cast<double>(s.name == "all" ? options.samples : options.budget_samples);
  for (const Scenario& scenario : scenarios) {
    ChainMonteCarloOptions mc = ScenarioOptions(scenario, options, digest);
    const SummaryPlan plan = ChainPlan(scenario.model, mc);
    const BlockRange range = ShardBlocks(plan, options.shard, options.shards);
    const uint64_t pieces = std::clamp<uint64_t>((range.end - range.begin) / 16, 1, 50);
    MonteCarloSummary summary(plan);
    for (uint64_t piece = 0; piece < pieces; ++piece) {
      mc.shard = options.shard * pieces + piece;
      mc.shards = options.shards * pieces;
      summary.Merge(RunChainMonteCarlo(scenario.model, mc));
      if (progress) progress((done + static_cast<double>(mc.samples) * (piece + 1) / pieces / options.shards) / (total / options.shards));
    }
    done += static_cast<double>(mc.samples);
    result.scenarios.push_back(scenario.name);
    result.summaries.push_back(std::move(summary));
  }
  return result;
}

void MergeSimulation(SimulationResult* into, const SimulationResult& other) {
  if (into->scenarios != other.scenarios) {
    throw InputError("the shards ran different scenarios (different " VSTCAL_OPT("only") "/" VSTCAL_OPT("without") " or " VSTCAL_OPT("no_budget") "); merge shards of one run");
  }
  for (size_t i = 0; i < into->summaries.size(); ++i) into->summaries[i].Merge(other.summaries[i]);
}

}  // namespace vstcal
