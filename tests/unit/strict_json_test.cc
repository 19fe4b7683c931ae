// The JSON reader is strict (docs/reliability.md#strict-json): a key given twice, nesting beyond
// limits::kMaxNesting and integers out of range are refused with the file, the line and column
// and the key; the writer refuses NaN and infinity instead of writing null.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "support/error_of.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"

namespace vstcal {
namespace {

// The message of the InputError that parsing `text` throws ("" when it parses).
std::string ParseError(const std::string& text) {
  return testing::ErrorOf([&] { JsonDocument::Parse(text, "t.json"); });
}

TEST(StrictJson, DuplicateKeysAreRefusedWithLineColumnAndPath) {
  EXPECT_EQ(ParseError("{\"a\": 1,\n \"a\": 2}"),
            "t.json: line 2, column 2: duplicate key \"a\" in the top-level object; keep one of them (JSON readers "
            "disagree on which one counts)");
  EXPECT_EQ(ParseError("{\"views\": [{\"name\": \"x\"}, {\"n\": 1, \"name\": \"y\", \"name\": \"z\"}]}")
                .substr(0, 70),
            "t.json: line 1, column 49: duplicate key \"name\" in views[1]; keep one ");
  // Escapes in the key: the column is that of its opening quote.
  EXPECT_NE(ParseError("{\"o\": {\"k\\\"\": 1, \"k\\\"\": 2}}").find("line 1, column 18: duplicate key \"k\"\" in o"),
            std::string::npos);
  // Equal keys in different objects are fine; so are keys differing only in case.
  EXPECT_EQ(ParseError("{\"a\": {\"x\": 1}, \"b\": {\"x\": 2}, \"A\": 3}"), "");
}

TEST(StrictJson, NestingIsBounded) {
  const int ok = limits::kMaxNesting;
  EXPECT_EQ(ParseError(std::string(ok, '[') + std::string(ok, ']')), "");
  const std::string deep = std::string(ok + 1, '[') + std::string(ok + 1, ']');
  EXPECT_EQ(ParseError(deep), "t.json: line 1, column 65: nested more than 64 levels deep; vstcal's formats need a "
                              "few levels; check that this is the right file");
  // 50,000 levels of objects: refused at the 65th, without recursion.
  std::string objects;
  for (int i = 0; i < 50000; ++i) objects += "{\"a\":";
  EXPECT_NE(ParseError(objects).find("nested more than 64 levels"), std::string::npos);
}

TEST(StrictJson, ParsedDocumentMatchesNlohmann) {
  const std::string text = R"({"b": [1, -2, 3.5, 1e-300, 18446744073709551615, true, null, "s\u00e9"], "a": {"x": {}}})";
  const JsonDocument doc = JsonDocument::Parse(text, "t.json");
  EXPECT_EQ(doc.root().json(), nlohmann::json::parse(text));
}

TEST(StrictJson, SyntaxErrorsKeepTheirMessages) {
  EXPECT_EQ(ParseError("{\"a\": NaN}"),
            "t.json: line 1, column 7: 'NaN' is not a JSON number; every value must be a finite number (remove or fix "
            "the point)");
  EXPECT_EQ(ParseError("{\"a\": 1e999}"),
            "t.json: line 1, column 7: '1e999' is too large for a double; every value must be a finite number (remove "
            "or fix the point)");
  EXPECT_EQ(ParseError("{\"a\": 1,}"), "t.json: line 1, column 9: not valid JSON; fix the syntax there");
}

TEST(StrictJson, IntegersOutOfRangeSaySo) {
  const JsonDocument doc = JsonDocument::Parse(R"({"n": 1e10, "f": 2.5})", "t.json");
  EXPECT_EQ(testing::ErrorOf([&] { doc.root().at("n").Integer(); }),
            "t.json: n: the integer 10000000000.0 is out of range; write a whole number from -2147483647 to 2147483647");
  EXPECT_THROW(doc.root().at("f").Integer(), InputError);
}

TEST(JsonWriter, RefusesNonFiniteNumbersInsteadOfWritingNull) {
  OrderedJson j;
  j["fit"]["rms_px"] = 0.5;
  j["P"] = {{1.0, std::numeric_limits<double>::quiet_NaN()}};
  try {
    DumpJson(j);
    FAIL();
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("a non-finite number at P[0][1] would be written as null"), std::string::npos)
        << e.what();
  }
  j["P"] = {{1.0, 2.0}};
  j["fit"]["max_px"] = std::numeric_limits<double>::infinity();
  EXPECT_THROW(DumpJson(j), InternalError);
  EXPECT_THROW(ShortestDecimal(-std::numeric_limits<double>::infinity()), InternalError);
  j["fit"]["max_px"] = nullptr;  // null written on purpose stays allowed
  EXPECT_NO_THROW(DumpJson(j));
}

}  // namespace
}  // namespace vstcal
