// Pairing the views of two cameras' correspondences by a key taken from each view's name (a stereo
// rig's left01 / right01): the stereo solve and the rig's report match views this way.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "vstcal/scene/correspondences.h"

namespace vstcal {

// How a rig's views were paired (stereo@1's "view_pairing"): the key expression (as
// --match-views takes it) and, when it was derived from the names, the rule in words.
struct ViewPairing {
  std::string match_views;  // ECMAScript, the key in its first group
  std::string rule;         // e.g. "names differ only by left/right (left01 ↔ right01)"; "" when given
};

// Renames each view of `c` to its key: the first group of `pattern`'s match (ECMAScript) in its
// name, as StereoSolveOptions::view_key_pattern pairs views. Throws InputError (naming the option match_views,
// or `file` and the name) for a pattern that is no regular expression or has no group, and for a
// name it does not match.
void KeyViews(const std::string& pattern, const std::string& file, Correspondences* c);

// A pairing derived from two cameras' view names that share none (docs/tools/calib-stereo.md#pairing).
// Every name is cut into runs of digits and of other characters. The key is the number that varies
// from view to view (the run at the same place in every name; with one view per camera, the last
// number); the rest of the names must be one text per camera, the two differing only by a
// left/right token (left/right, Left/Right, LEFT/RIGHT, l/r, L/R, cam0/cam1, 0/1), and the keys
// unique within each camera and shared by at least one view of each. Otherwise `pairing` is
// nullopt, `problem` says why and `suggestion` is the --match-views expression that the numbers
// allow ("" when they do not: names of other shapes, no number, or no number in common).
struct DerivedPairing {
  std::optional<ViewPairing> pairing;
  size_t paired = 0;  // views whose key both cameras have
  std::string problem;
  std::string suggestion;
};
DerivedPairing DeriveViewPairing(const std::vector<std::string>& left_names, const std::vector<std::string>& right_names);

// The names of c's views.
std::vector<std::string> ViewNames(const Correspondences& c);
// True when a name is in both lists.
bool ShareAName(const std::vector<std::string>& a, const std::vector<std::string>& b);

}  // namespace vstcal
