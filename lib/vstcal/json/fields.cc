#include "vstcal/json/fields.h"

#include <algorithm>

#include "vstcal/core/suggest.h"
#include "vstcal/geometry/rotation.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

// A rotation read is kept as written when ‖RᵀR − I‖_max is below this (rounding of a computed R).
constexpr double kRotationRounding = 1e-12;

}  // namespace

ImageSize ReadImageSize(const JsonNode& node) {
  node.ArraySize(2);
  auto side = [&](size_t i, std::string_view what) {
    const JsonNode n = node.at(i);
    const double v = n.Number();
    if (const auto problem = ImageSideProblem(v, what)) n.Fail(problem->reason, problem->fix);
    return static_cast<int>(v);
  };
  return ImageSize{side(0, "width"), side(1, "height")};
}

LengthUnit ReadLengthUnit(const JsonNode& node) { return *LengthUnitFromName(node.OneOf(kLengthUnitNames)); }

Rigid3d ReadRigid(const JsonNode& node) {
  Rigid3d pose;
  const JsonNode R = node.at("R");
  pose.R = R.Matrix<3, 3>();
  if (!IsRotation(pose.R, 1e-6)) {
    R.Fail("not a rotation matrix (RᵀR ≠ I or det R < 0, tolerance 1e-6)", "write R with at least 7 significant digits");
  }
  // Re-orthonormalized unless it already is one to rounding, as every writer leaves it: the SVD
  // would change its last bits on every pass, and a file read and written again must be the same.
  if (!IsRotation(pose.R, kRotationRounding)) pose.R = NearestRotation(pose.R);
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

}  // namespace vstcal
