#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// U+2039 and U+203A (VSTCAL_OPT spells them too): characters no option name, file name or value of
// a message is expected to hold, so that rendering cannot touch the rest of the text.
constexpr std::string_view kOpen = "\u2039", kClose = "\u203a";
static_assert(std::string_view(VSTCAL_OPT("")) == std::string_view("\u2039\u203a"));

}  // namespace

std::string Opt(std::string_view name) {
  std::string out(kOpen);
  out += name;
  out += kClose;
  return out;
}

std::string RenderOptionNames(std::string_view message, std::string (*rename)(std::string_view name)) {
  std::string out;
  out.reserve(message.size());
  for (size_t at = 0;;) {
    const size_t open = message.find(kOpen, at);
    const size_t close = open == std::string_view::npos ? open : message.find(kClose, open + kOpen.size());
    if (close == std::string_view::npos) {
      out += message.substr(at);
      return out;
    }
    out += message.substr(at, open - at);
    out += rename(message.substr(open + kOpen.size(), close - open - kOpen.size()));
    at = close + kClose.size();
  }
}

std::string OptionAsFlag(std::string_view name) {
  std::string flag = "--";
  for (const char c : name) flag += c == '_' ? '-' : c;
  return flag;
}

std::string OptionAsKeyword(std::string_view name) { return std::string(name); }

}  // namespace vstcal
