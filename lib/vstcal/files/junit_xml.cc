#include "vstcal/files/junit_xml.h"

#include <cstdio>

namespace vstcal {
namespace {

// Length of the valid UTF-8 sequence at s[i] (1 … 4), or 0 when it is not one (overlong forms,
// surrogates and code points above U+10FFFF are not valid UTF-8).
size_t Utf8Length(std::string_view s, size_t i) {
  const auto byte = [&](size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  size_t n = 0;
  unsigned cp = 0;
  if ((c & 0xe0) == 0xc0) {
    n = 2, cp = c & 0x1f;
  } else if ((c & 0xf0) == 0xe0) {
    n = 3, cp = c & 0x0f;
  } else if ((c & 0xf8) == 0xf0) {
    n = 4, cp = c & 0x07;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return 0;
    cp = (cp << 6) | (byte(i + k) & 0x3f);
  }
  const unsigned min[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < min[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff) || cp == 0xfffe || cp == 0xffff) return 0;
  return n;
}

std::string Hex(unsigned char c) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02x", c);
  return buf;
}

}  // namespace

std::string XmlEscape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size();) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    switch (c) {
      case '&': out += "&amp;"; ++i; continue;
      case '<': out += "&lt;"; ++i; continue;
      case '>': out += "&gt;"; ++i; continue;
      case '"': out += "&quot;"; ++i; continue;
      case '\'': out += "&apos;"; ++i; continue;
      default: break;
    }
    if ((u < 0x20 && c != '\t' && c != '\n' && c != '\r') || u == 0x7f) {
      out += Hex(u);
      ++i;
      continue;
    }
    const size_t n = Utf8Length(text, i);
    if (n == 0) {
      out += Hex(u);
      ++i;
      continue;
    }
    out.append(text.substr(i, n));
    i += n;
  }
  return out;
}

std::string JUnitXml(std::string_view suite, std::span<const CheckResult> results) {
  size_t failures = 0;
  for (const CheckResult& r : results) failures += r.verdict == CheckVerdict::kFail;
  const std::string name = XmlEscape(suite);
  const std::string counts = " tests=\"" + std::to_string(results.size()) + "\" failures=\"" + std::to_string(failures) + "\" errors=\"0\"";
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<testsuites name=\"" + name + "\"" + counts + ">\n";
  out += "  <testsuite name=\"" + name + "\"" + counts + " skipped=\"0\">\n";
  for (const CheckResult& r : results) {
    const std::string verdict(CheckVerdictName(r.verdict));
    const std::string line = XmlEscape(verdict + ": " + r.message);
    out += "    <testcase classname=\"" + name + "\" name=\"" + XmlEscape(r.name) + "\">\n";
    if (r.verdict == CheckVerdict::kFail) {
      out += "      <failure message=\"" + line + "\" type=\"threshold\">" + line + "</failure>\n";
    }
    out += "      <system-out>" + line + "</system-out>\n";
    out += "    </testcase>\n";
  }
  out += "  </testsuite>\n</testsuites>\n";
  return out;
}

}  // namespace vstcal
