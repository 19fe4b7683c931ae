// Pairing the views of two cameras' correspondences by a key taken from each view's name (a stereo
// rig's left01 / right01): the stereo solve and the rig's report match views this way.
#pragma once

#include <string>

#include "vstcal/scene/correspondences.h"

namespace vstcal {

// Renames each view of `c` to its key: the first group of `pattern`'s match (ECMAScript) in its
// name, as StereoSolveOptions::view_key_pattern pairs views. Throws InputError ("--match-views: …",
// or `file` and the name) for a pattern that is no regular expression or has no group, and for a
// name it does not match.
void KeyViews(const std::string& pattern, const std::string& file, Correspondences* c);

}  // namespace vstcal
