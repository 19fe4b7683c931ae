#include "vstcal/formats/capture/plan_compare.h"

#include <cstdio>

#include "vstcal/core/error.h"
#include "vstcal/json/format_check.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

struct Row {
  std::string name;
  double a = 0, b = 0;
};

// Rows named in both plans, in A's order; B's unmatched names are left out (said in the text).
std::vector<Row> Pair(const PlanPrediction& a, const PlanPrediction& b, bool points, bool intrinsics_only) {
  std::vector<Row> rows;
  if (points) {
    for (const PlanPrediction::Point& p : a.points) {
      for (const PlanPrediction::Point& q : b.points) {
        if (p.name == q.name) {
          rows.push_back({p.name, intrinsics_only ? p.intrinsics_only_px : p.with_poses_px,
                          intrinsics_only ? q.intrinsics_only_px : q.with_poses_px});
        }
      }
    }
    return rows;
  }
  for (const auto& [name, sigma] : a.sigmas) {
    for (const auto& [other, sigma_b] : b.sigmas) {
      if (name == other) rows.push_back({name, sigma, sigma_b});
    }
  }
  return rows;
}

void Check(const PlanPrediction& a, const PlanPrediction& b) {
  for (const PlanPrediction* p : {&a, &b}) {
    if (!p->observable) {
      throw DegenerateError(p->file + ": prediction: the plan does not determine the calibration (observable "
                                                   "false); fix that plan before comparing it");
    }
  }
  if (a.pixel_sigma != b.pixel_sigma) {
    throw InputError(b.file + ": prediction.pixel_sigma: " + std::to_string(b.pixel_sigma) + " px differs from " + a.file +
                     "'s " + std::to_string(a.pixel_sigma) + " px; plan both at the same " VSTCAL_OPT("pixel_sigma"));
  }
  if (Pair(a, b, false, false).empty()) {
    throw InputError(b.file + ": prediction.parameters: no parameter in common with " + a.file + "; compare plans of the same solve");
  }
}

const char* Better(const Row& r) { return r.b < r.a ? "B" : r.a < r.b ? "A" : "="; }

}  // namespace

PlanPrediction PlanPredictionFromJson(const JsonDocument& doc) {
  const JsonNode root = doc.root();
  root.ExpectObject();
  CheckFormat(root, "vstcal/capture-plan@1");
  PlanPrediction p;
  p.file = doc.name();
  const JsonNode prediction = root.at("prediction");
  prediction.ExpectObject();
  p.pixel_sigma = prediction.at("pixel_sigma").PositiveNumber();
  p.observable = prediction.at("observable").Boolean();
  const JsonNode parameters = prediction.at("parameters");
  for (size_t i = 0, n = parameters.ArraySize(); i < n; ++i) {
    const JsonNode s = parameters.at(i);
    s.ExpectObject();
    p.sigmas.emplace_back(s.at("name").String(), s.at("sigma").NonNegativeNumber());
  }
  const JsonNode points = prediction.at("test_points");
  for (size_t i = 0, n = points.ArraySize(); i < n; ++i) {
    const JsonNode q = points.at(i);
    q.ExpectObject();
    p.points.push_back({q.at("name").String(), q.at("with_poses_px").NonNegativeNumber(), q.at("intrinsics_only_px").NonNegativeNumber()});
  }
  return p;
}

PlanPrediction ReadPlanPrediction(const std::filesystem::path& path) { return PlanPredictionFromJson(JsonDocument::Load(path)); }

OrderedJson ComparePlansToJson(const PlanPrediction& a, const PlanPrediction& b, const Provenance& provenance) {
  Check(a, b);
  OrderedJson j;
  j["format"] = "vstcal/capture-plan-comparison@1";
  j["provenance"] = ProvenanceToJson(provenance);
  j["a"] = a.file;
  j["b"] = b.file;
  j["pixel_sigma"] = a.pixel_sigma;
  const auto rows = [](const std::vector<Row>& in) {
    OrderedJson out = OrderedJson::array();
    for (const Row& r : in) {
      out.push_back({{"name", r.name}, {"a", r.a}, {"b", r.b}, {"ratio", r.a > 0 ? OrderedJson(r.b / r.a) : OrderedJson()},
                     {"better", Better(r)}});
    }
    return out;
  };
  j["parameters"] = rows(Pair(a, b, false, false));
  j["test_points_with_poses_px"] = rows(Pair(a, b, true, false));
  j["test_points_intrinsics_only_px"] = rows(Pair(a, b, true, true));
  return j;
}

std::string ComparePlansText(const PlanPrediction& a, const PlanPrediction& b) {
  Check(a, b);
  std::string text = "A = " + a.file + ", B = " + b.file + "; 1-σ at the same pixel noise, ratio B/A (< 1: B is better)\n";
  char buf[200];
  const auto table = [&](const char* title, const std::vector<Row>& rows) {
    text += title;
    for (const Row& r : rows) {
      std::snprintf(buf, sizeof buf, "  %-28s %12.4g %12.4g %8.3f  %s\n", r.name.c_str(), r.a, r.b, r.a > 0 ? r.b / r.a : NAN, Better(r));
      text += buf;
    }
  };
  table("parameter                            A            B    B/A  better\n", Pair(a, b, false, false));
  table("projection with poses, px\n", Pair(a, b, true, false));
  table("projection intrinsics only, px\n", Pair(a, b, true, true));
  return text;
}

}  // namespace vstcal
