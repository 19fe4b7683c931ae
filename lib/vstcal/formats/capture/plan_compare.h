// Two capture plans side by side (calib-capture plan --compare A B): the predicted σ of every
// parameter and the projection uncertainty at every test point both plans name, their ratio
// B / A and which plan is better there. Read from vstcal/capture-plan@1 files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "vstcal/json/provenance.h"
#include "vstcal/json/json_reader.h"

namespace vstcal {

struct PlanPrediction {
  std::string file;
  double pixel_sigma = 0;
  bool observable = false;
  std::vector<std::pair<std::string, double>> sigmas;  // parameter, 1-σ
  struct Point {
    std::string name;
    double with_poses_px = 0, intrinsics_only_px = 0;
  };
  std::vector<Point> points;
};

// The prediction block of a vstcal/capture-plan@1 file. Throws InputError naming the file and field.
PlanPrediction PlanPredictionFromJson(const JsonDocument& doc);
PlanPrediction ReadPlanPrediction(const std::filesystem::path& path);

// Throws InputError when the plans assume different pixel noise (their σ's would not compare) or
// name no parameter in common; DegenerateError when a plan is not observable.
OrderedJson ComparePlansToJson(const PlanPrediction& a, const PlanPrediction& b, const Provenance& provenance);
std::string ComparePlansText(const PlanPrediction& a, const PlanPrediction& b);

}  // namespace vstcal
