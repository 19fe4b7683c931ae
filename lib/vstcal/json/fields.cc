#include "vstcal/json/fields.h"

#include <algorithm>

#include "vstcal/core/suggest.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal::io {

ImageSize ReadImageSize(const JsonNode& node) {
  node.ArraySize(2);
  return ImageSize{node.at(0).PositiveInteger(), node.at(1).PositiveInteger()};
}

LengthUnit ReadLengthUnit(const JsonNode& node) { return *LengthUnitFromName(node.OneOf(kLengthUnitNames)); }

Rigid3d ReadRigid(const JsonNode& node) {
  Rigid3d pose;
  const JsonNode R = node.at("R");
  pose.R = R.Matrix<3, 3>();
  if (!IsRotation(pose.R, 1e-6)) {
    R.Fail("not a rotation matrix (RᵀR ≠ I or det R < 0, tolerance 1e-6)", "write R with at least 7 significant digits");
  }
  pose.R = NearestRotation(pose.R);
  pose.t = node.at("t").Vector<3>();
  return pose;
}

void ExpectKeys(const JsonNode& node, const std::vector<std::string_view>& allowed, const std::string& what) {
  node.ExpectObject();
  for (auto it = node.json().begin(); it != node.json().end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) == allowed.end()) {
      node.at(it.key()).Fail("unknown " + what + " \"" + it.key() + "\"", SuggestKey(it.key(), allowed));
    }
  }
}

}  // namespace vstcal::io
