#include "vstcal/json/format_check.h"

#include <string>

namespace vstcal {

void CheckFormat(const JsonNode& root, std::string_view expected) {
  const JsonNode format = root.at("format");
  const std::string got = format.String();
  if (got == expected) return;
  const std::string_view expected_schema = expected.substr(0, expected.find('@'));
  const std::string_view got_schema = std::string_view(got).substr(0, got.find('@'));
  if (got_schema == expected_schema) {
    format.Fail("unsupported version \"" + got + "\"", "this vstcal reads \"" + std::string(expected) + "\"");
  }
  if (got.rfind("vstcal/", 0) == 0) {
    format.Fail("this is a \"" + got + "\" file, expected \"" + std::string(expected) + "\"", "pass the right file");
  }
  format.Fail("unknown format \"" + got + "\"", "expected \"" + std::string(expected) + "\" (docs/formats.md)");
}

}  // namespace vstcal
