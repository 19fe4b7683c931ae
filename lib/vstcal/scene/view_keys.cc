#include "vstcal/scene/view_keys.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <regex>
#include <set>
#include <tuple>
#include <utility>

#include "vstcal/core/error.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// Runs of digits and of other characters: "img_left_3" → {"img_left_", "3"}.
struct Runs {
  std::vector<std::string> text;
  std::vector<bool> digits;
};

Runs Cut(const std::string& name) {
  Runs r;
  for (char ch : name) {
    const bool d = std::isdigit(static_cast<unsigned char>(ch)) != 0;
    if (r.text.empty() || r.digits.back() != d) {
      r.text.emplace_back();
      r.digits.push_back(d);
    }
    r.text.back() += ch;
  }
  return r;
}

// The expression whose first group is the k-th of n digit runs: the common forms when they fit.
std::string NumberPattern(int k, int n_digit_runs, bool ends_with_it) {
  if (k == n_digit_runs - 1) return ends_with_it ? "([0-9]+)$" : "([0-9]+)[^0-9]*$";
  if (k == 0) return "^[^0-9]*([0-9]+)";
  return "^[^0-9]*(?:[0-9]+[^0-9]*){" + std::to_string(k) + "}([0-9]+)";
}

// The name with run `skip` replaced by '#'.
std::string Template(const Runs& r, size_t skip) {
  std::string t;
  for (size_t i = 0; i < r.text.size(); ++i) t += i == skip ? "#" : r.text[i];
  return t;
}

// The token pairs a left and a right name may differ by, most specific first.
constexpr std::array<std::pair<const char*, const char*>, 7> kTokens = {
    {{"left", "right"}, {"Left", "Right"}, {"LEFT", "RIGHT"}, {"cam0", "cam1"}, {"l", "r"}, {"L", "R"}, {"0", "1"}}};

// The token pair by which the two templates differ, if any: left = P + a + S and right = P + b + S.
std::optional<std::pair<std::string, std::string>> TokenBetween(const std::string& left, const std::string& right) {
  for (const auto& [a, b] : kTokens) {
    const std::string sa = a, sb = b;
    for (size_t at = left.find(sa); at != std::string::npos; at = left.find(sa, at + 1)) {
      if (left.substr(0, at) + sb + left.substr(at + sa.size()) == right) return std::pair{sa, sb};
    }
  }
  return std::nullopt;
}

std::string Quote(const std::string& s) { return "\"" + s + "\""; }

}  // namespace

void KeyViews(const std::string& pattern, const std::string& file, Correspondences* c) {
  std::regex re;
  try {
    re = std::regex(pattern);
  } catch (const std::regex_error& e) {
    throw InputError(VSTCAL_OPT("match_views") ": \"" + pattern + "\" is not a regular expression (" + e.what() + "); e.g. '([0-9]+)$'");
  }
  if (re.mark_count() < 1) throw InputError(VSTCAL_OPT("match_views") ": \"" + pattern + "\" has no group; put the key in parentheses, e.g. '([0-9]+)$'");
  for (View& v : c->views) {
    std::smatch m;
    if (!std::regex_search(v.name, m, re) || !m[1].matched) {
      throw InputError(file + ": views: the name \"" + v.name + "\" does not match " VSTCAL_OPT("match_views") " \"" + pattern +
                       "\"; change the pattern or the view's name");
    }
    v.name = m[1].str();
  }
}

std::vector<std::string> ViewNames(const Correspondences& c) {
  std::vector<std::string> names;
  for (const View& v : c.views) names.push_back(v.name);
  return names;
}

bool ShareAName(const std::vector<std::string>& a, const std::vector<std::string>& b) {
  const std::set<std::string> in_a(a.begin(), a.end());
  for (const std::string& n : b) {
    if (in_a.contains(n)) return true;
  }
  return false;
}

DerivedPairing DeriveViewPairing(const std::vector<std::string>& left_names, const std::vector<std::string>& right_names) {
  DerivedPairing out;
  if (left_names.empty() || right_names.empty()) {
    out.problem = "a camera has no views";
    return out;
  }
  std::vector<Runs> left, right;
  for (const std::string& n : left_names) left.push_back(Cut(n));
  for (const std::string& n : right_names) right.push_back(Cut(n));
  // One shape for every name: the same runs, digits at the same places.
  const std::vector<bool>& shape = left[0].digits;
  for (const auto* side : {&left, &right}) {
    for (const Runs& r : *side) {
      if (r.digits != shape) {
        out.problem = "the names do not have one shape (" + Quote(left_names[0]) + ", " +
                      Quote(side == &left ? left_names[&r - left.data()] : right_names[&r - right.data()]) + ")";
        return out;
      }
    }
  }
  std::vector<int> digit_runs;
  for (size_t i = 0; i < shape.size(); ++i) {
    if (shape[i]) digit_runs.push_back(static_cast<int>(i));
  }
  if (digit_runs.empty()) {
    out.problem = "the names hold no number to pair them by";
    return out;
  }
  // The key: the digit run that varies within a camera.
  std::vector<int> varying;
  for (int i : digit_runs) {
    bool varies = false;
    for (const auto* side : {&left, &right}) {
      for (const Runs& r : *side) varies |= r.text[i] != (*side)[0].text[i];
    }
    if (varies) varying.push_back(i);
  }
  if (varying.size() > 1) {
    out.problem = "more than one number changes from view to view (" + Quote(left_names[0]) + ", " + Quote(left_names.back()) + ")";
    return out;
  }
  const int key_run = varying.empty() ? digit_runs.back() : varying[0];
  const int k = static_cast<int>(std::find(digit_runs.begin(), digit_runs.end(), key_run) - digit_runs.begin());
  const std::string pattern = NumberPattern(k, static_cast<int>(digit_runs.size()), key_run == static_cast<int>(shape.size()) - 1);
  std::set<std::string> left_keys, right_keys;
  for (const auto& [side, keys, names] : {std::tuple{&left, &left_keys, &left_names}, std::tuple{&right, &right_keys, &right_names}}) {
    for (size_t v = 0; v < side->size(); ++v) {
      if (!keys->insert((*side)[v].text[key_run]).second) {
        out.problem = "two views of one camera have the number " + (*side)[v].text[key_run] + " (" + Quote((*names)[v]) + ")";
        return out;
      }
    }
  }
  for (const std::string& key : left_keys) out.paired += right_keys.count(key);
  if (out.paired == 0) {
    out.problem = "no number is in both cameras' names (" + Quote(left_names[0]) + ", " + Quote(right_names[0]) + ")";
    return out;
  }
  out.suggestion = pattern;
  // The rest of the names: one text per camera, differing by a left/right token.
  const std::string left_template = Template(left[0], key_run), right_template = Template(right[0], key_run);
  for (const auto& [side, tmpl, names] : {std::tuple{&left, &left_template, &left_names}, std::tuple{&right, &right_template, &right_names}}) {
    for (size_t v = 0; v < side->size(); ++v) {
      if (Template((*side)[v], key_run) != *tmpl) {
        out.problem = "the names differ by more than their number (" + Quote((*names)[0]) + ", " + Quote((*names)[v]) + ")";
        return out;
      }
    }
  }
  const auto token = TokenBetween(left_template, right_template);
  if (!token) {
    out.problem = "the names " + Quote(left_names[0]) + " and " + Quote(right_names[0]) + " do not differ by a left/right token";
    return out;
  }
  // An example pair for the message: the first left view the right camera also saw.
  size_t l = 0, r = 0;
  while (!right_keys.contains(left[l].text[key_run])) ++l;
  while (right[r].text[key_run] != left[l].text[key_run]) ++r;
  out.pairing = ViewPairing{pattern, "names differ only by " + token->first + "/" + token->second + " (" + left_names[l] + " ↔ " +
                                         right_names[r] + "); paired by the number in the name"};
  return out;
}

}  // namespace vstcal
