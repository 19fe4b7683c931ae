#include "vstcal/scene/view_keys.h"

#include <regex>

#include "vstcal/core/error.h"

namespace vstcal {

void KeyViews(const std::string& pattern, const std::string& file, Correspondences* c) {
  std::regex re;
  try {
    re = std::regex(pattern);
  } catch (const std::regex_error& e) {
    throw InputError("--match-views: \"" + pattern + "\" is not a regular expression (" + e.what() + "); e.g. '([0-9]+)$'");
  }
  if (re.mark_count() < 1) throw InputError("--match-views: \"" + pattern + "\" has no group; put the key in parentheses, e.g. '([0-9]+)$'");
  for (View& v : c->views) {
    std::smatch m;
    if (!std::regex_search(v.name, m, re) || !m[1].matched) {
      throw InputError(file + ": views: the name \"" + v.name + "\" does not match --match-views \"" + pattern +
                       "\"; change the pattern or the view's name");
    }
    v.name = m[1].str();
  }
}

}  // namespace vstcal
