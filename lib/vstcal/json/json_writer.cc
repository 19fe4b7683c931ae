#include "vstcal/json/json_writer.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "vstcal/core/error.h"

namespace vstcal {

OrderedJson RigidToJson(const Rigid3d& a_from_b) {
  OrderedJson j;
  j["R"] = MatrixToJson(a_from_b.R);
  j["t"] = MatrixToJson(a_from_b.t);
  return j;
}

namespace {

// NaN and infinity are not JSON numbers: nlohmann would write them as null, silently.
void CheckFinite(const OrderedJson& json, const std::string& path) {
  if (json.is_number_float()) {
    VSTCAL_CHECK(std::isfinite(json.get<double>()), "a non-finite number at " + (path.empty() ? "(top level)" : path) +
                                                        " would be written as null");
  } else if (json.is_object()) {
    for (const auto& [key, value] : json.items()) CheckFinite(value, path.empty() ? key : path + "." + key);
  } else if (json.is_array()) {
    for (size_t i = 0; i < json.size(); ++i) CheckFinite(json[i], path + "[" + std::to_string(i) + "]");
  }
}

}  // namespace

std::string DumpJson(const OrderedJson& json) {
  CheckFinite(json, "");
  return json.dump(2) + "\n";
}

std::string ShortestDecimal(double v) {
  VSTCAL_CHECK(std::isfinite(v), "a non-finite number would be written");
  return OrderedJson(v).dump();
}

std::string DumpJsonCompact(const OrderedJson& json) { return json.dump() + "\n"; }


}  // namespace vstcal
