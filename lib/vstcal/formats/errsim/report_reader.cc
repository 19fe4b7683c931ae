#include "vstcal/formats/errsim/report_reader.h"

#include "vstcal/errsim/sources.h"
#include "vstcal/formats/errsim/report_format.h"
#include "vstcal/json/format_check.h"

namespace vstcal {
namespace {

constexpr const char* kRegenerate = "give a report written by err-sim run or merge (this one was changed)";

uint64_t Count(const JsonNode& n) {
  if (!n.json().is_number_unsigned()) n.Fail("expected a non-negative integer, got " + n.json().dump(), kRegenerate);
  return n.json().get<uint64_t>();
}

// Follows a dotted measure ("image.left.pixel_px") from a test point; nullopt at a null on the way.
std::optional<JsonNode> Follow(JsonNode node, std::string_view path) {
  while (!path.empty()) {
    const size_t dot = path.find('.');
    const std::string key(path.substr(0, dot));
    path = dot == std::string_view::npos ? std::string_view() : path.substr(dot + 1);
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
  if (root.at("format").json() != kReportFormatV2) CheckFormat(root, kReportFormat);
  ReportForCheck r;
  r.chain = root.at("chain").String();
  r.chain_digest = root.at("chain_digest").String();
  r.length_unit = root.at("length_unit").String();
  r.samples = Count(root.at("samples"));
  if (r.samples == 0) root.at("samples").Fail("is 0", kRegenerate);
  r.seed = Count(root.at("seed"));
  const JsonNode sources = root.at("sources");
  for (const char* key : {"only", "without"}) {
    const JsonNode list = sources.at(key);
    std::vector<std::string>& out = std::string_view(key) == "only" ? r.only : r.without;
    for (size_t i = 0; i < list.ArraySize(); ++i) {
      out.push_back(list.at(i).String());
      if (!SourceFromKey(out.back())) list.at(i).Fail("unknown error source \"" + out.back() + "\"", kRegenerate);
    }
  }
  const JsonNode points = root.at("test_points");
  for (size_t k = 0; k < points.ArraySize(); ++k) {
    const JsonNode point = points.at(k);
    const std::string name = point.at("name").String();
    for (const std::string_view measure : kCheckedMeasures) {
      const bool rate = measure.starts_with("occlusion.");
      // "occlusion.left.wrong_rate" is {wrong_rate, standard_error} under occlusion.left.
      const std::string_view object = rate ? measure.substr(0, measure.rfind('.')) : measure;
      const std::optional<JsonNode> stats = Follow(point, object);
      if (!stats) continue;
      MonteCarloMetric m{name, std::string(measure), 0, 0};
      if (rate) {
        m.value = stats->at("wrong_rate").NonNegativeNumber();
        m.standard_error = StandardError(stats->at("standard_error"));
      } else {
        m.value = stats->at("mean").Number();
        m.standard_error = StandardError(stats->at("mean_standard_error"));
      }
      r.metrics.push_back(std::move(m));
    }
  }
  return r;
}

}  // namespace vstcal
