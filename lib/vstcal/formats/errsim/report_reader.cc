#include "vstcal/formats/errsim/report_reader.h"

#include "vstcal/errsim/sources.h"
#include "vstcal/formats/errsim/report_format.h"
#include "vstcal/formats/errsim/report_keys.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr const char* kReportRegenerate = "give a report written by err-sim run or merge (this one was changed)";

uint64_t ReportCount(const JsonNode& n) {
  if (!n.json().is_number_unsigned()) n.Fail("expected a non-negative integer, got " + n.json().dump(), kReportRegenerate);
  return n.json().get<uint64_t>();
}

// Follows a JSON pointer relative to a test point ("image/left/pixel_px"); nullopt at a null on
// the way (a statistic with no defined sample, or an occlusion at a point without a surface).
std::optional<JsonNode> Follow(JsonNode node, std::string_view pointer) {
  while (!pointer.empty()) {
    const size_t slash = pointer.find('/');
    const std::string key(pointer.substr(0, slash));
    pointer = slash == std::string_view::npos ? std::string_view() : pointer.substr(slash + 1);
    if (node.json().is_null()) return std::nullopt;
    node = node.at(key);
  }
  if (node.json().is_null()) return std::nullopt;
  return node;
}

double StandardError(const JsonNode& n) {
  const double se = n.NonNegativeNumber();
  return se;
}

}  // namespace

ReportForCheck ReadReportForCheck(const JsonDocument& document) {
  const JsonNode root = document.root();
  root.ExpectObject();
  // Version 2 differs only in its budget, which check does not read: an accepted report kept
  // in a repository stays usable.
  if (root.at(errsim_key::kFormat).json() != kReportFormatV2) CheckFormat(root, kReportFormat);
  ReportForCheck r;
  r.chain = root.at(errsim_key::kChain).String();
  r.chain_digest = root.at(errsim_key::kChainDigest).String();
  r.length_unit = root.at(errsim_key::kLengthUnit).String();
  r.samples = ReportCount(root.at(errsim_key::kSamples));
  if (r.samples == 0) root.at(errsim_key::kSamples).Fail("is 0", kReportRegenerate);
  r.seed = ReportCount(root.at(errsim_key::kSeed));
  const JsonNode sources = root.at(errsim_key::kSources);
  for (const char* key : {errsim_key::kOnly, errsim_key::kWithout}) {
    const JsonNode list = sources.at(key);
    std::vector<std::string>& out = std::string_view(key) == errsim_key::kOnly ? r.only : r.without;
    for (size_t i = 0; i < list.ArraySize(); ++i) {
      out.push_back(list.at(i).String());
      if (!SourceFromKey(out.back())) list.at(i).Fail("unknown error source \"" + out.back() + "\"", kReportRegenerate);
    }
  }
  const JsonNode points = root.at(errsim_key::kTestPoints);
  for (size_t k = 0; k < points.ArraySize(); ++k) {
    const JsonNode point = points.at(k);
    const std::string name = point.at(errsim_key::kName).String();
    for (const CheckedMeasure& checked : CheckedMeasures()) {
      const std::optional<JsonNode> stats = Follow(point, MeasurePointer(checked.measure, checked.eye));
      if (!stats) continue;
      MonteCarloMetric m{name, checked.name, 0, 0};
      if (Declaration(checked.measure).unit == OutputUnit::kDecision) {
        m.value = stats->at(RateKey(checked.measure)).NonNegativeNumber();
        m.standard_error = StandardError(stats->at(errsim_key::kStandardError));
      } else {
        m.value = stats->at(errsim_key::kMean).Number();
        m.standard_error = StandardError(stats->at(errsim_key::kMeanStandardError));
      }
      r.metrics.push_back(std::move(m));
    }
  }
  return r;
}

}  // namespace vstcal
