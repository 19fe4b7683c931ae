// The Python-literal parser of .cameramodel files: what mrcal writes parses, and every syntax
// error names the line and column where it is.
#include <gtest/gtest.h>

#include "vstcal/core/error.h"
#include "vstcal/formats/camera/python_literal.h"

namespace vstcal {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParsePythonDict(text, "m.cameramodel");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PythonLiteral, ParsesTheSubsetMrcalWrites) {
  const PyValue v = ParsePythonDict(
      "# comment\n{ 'a': [1, -2.5, 1e-12, .5, 3., +4, 1_000,],  # trailing comma\n"
      "  \"b\": (True, False, None), 'c': {'d': 'x' \"y\"}, 'e': b'q\\'r', 'f': r'\\d', 'g': '''t'r''', }\n",
      "m.cameramodel");
  ASSERT_EQ(v.kind, PyValue::Kind::kDict);
  ASSERT_EQ(v.members.size(), 6u);
  const PyValue& a = v.members[0].second;
  ASSERT_EQ(a.items.size(), 7u);
  const double expected[] = {1, -2.5, 1e-12, 0.5, 3, 4, 1000};
  for (int i = 0; i < 7; ++i) EXPECT_EQ(a.items[i].number, expected[i]) << i;
  EXPECT_TRUE(a.items[0].integral);
  EXPECT_FALSE(a.items[2].integral);
  EXPECT_EQ(v.members[1].first, "b");
  EXPECT_EQ(v.members[1].second.items[0].kind, PyValue::Kind::kBool);
  EXPECT_EQ(v.members[1].second.items[2].kind, PyValue::Kind::kNone);
  EXPECT_EQ(v.members[2].second.members[0].second.text, "xy");  // adjacent strings join
  EXPECT_EQ(v.members[3].second.text, "q'r");
  EXPECT_EQ(v.members[4].second.text, "\\d");  // raw: the backslash stays
  EXPECT_EQ(v.members[5].second.text, "t'r");
  EXPECT_EQ(v.members[0].second.items[1].offset, 21u);  // where "-2.5" starts
}

// Doubles parse correctly rounded: the shortest round-trip forms come back bit for bit.
TEST(PythonLiteral, NumbersAreExact) {
  for (const double x : {0.1, 1234.5678901234567, -2.5e-12, 5e-324, 1.7976931348623157e308, 640.0000000000001}) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    const PyValue v = ParsePythonDict(std::string("{'x': ") + buf + "}", "m.cameramodel");
    EXPECT_EQ(v.members[0].second.number, x) << buf;
  }
}

struct BadText {
  std::string text;
  std::string where;   // "line L, column C"
  std::string phrase;  // in the message
};

TEST(PythonLiteral, SyntaxErrorsNameLineAndColumn) {
  const std::vector<BadText> cases = {
      {"", "line 1, column 1", "expected '{'"},
      {"[1, 2]", "line 1, column 1", "expected '{': a .cameramodel file is one Python dict"},
      {"{'a': 1\n 'b': 2}", "line 2, column 2", "expected ',' or '}'"},
      {"{'a': [1, 2}", "line 1, column 12", "expected ',' or ']'"},
      {"{'a': [1, 2,\n", "line 2, column 1", "the list is not closed"},
      {"{'a': 1", "line 1, column 8", "the dict is not closed"},
      {"{'a' 1}", "line 1, column 6", "expected ':' after the key 'a'"},
      {"{1: 2}", "line 1, column 2", "a key must be a string"},
      {"{'a': 1, 'a': 2}", "line 1, column 10", "duplicate key 'a'"},
      {"{'a': nan}", "line 1, column 7", "'nan' is not a Python literal"},
      {"{'a': float('inf')}", "line 1, column 7", "'float' is not a Python literal"},
      {"{'a': 1e999}", "line 1, column 7", "'1e999' is too large for a double"},
      {"{'a': -1e400}", "line 1, column 7", "'-1e400' is too large for a double"},
      {"{'a': 12abc}", "line 1, column 7", "'12abc' is not a number"},
      {"{'a': 1e}", "line 1, column 7", "the exponent has no digits"},
      {"{'a': 0x10}", "line 1, column 7", "'0x10' is not a number"},
      {"{'a': -}", "line 1, column 7", "'-' is not a number"},
      {"{'a': 'x\n'}", "line 1, column 7", "the string is not closed"},
      {"{'a': 1} {}", "line 1, column 10", "unexpected text after the dict's closing '}'"},
      {"{'a': @}", "line 1, column 7", "unexpected '@'"},
      {"{'a':" + std::string(100, '[') + std::string(100, ']') + "}", "line 1, column ", "nested more than 64 levels deep"},
  };
  for (const BadText& c : cases) {
    const std::string e = ErrorOf(c.text);
    EXPECT_EQ(e.rfind("m.cameramodel: " + c.where, 0), 0u) << c.text << "\n" << e;
    EXPECT_NE(e.find(c.phrase), std::string::npos) << c.text << "\n" << e;
  }
}

TEST(PythonLiteral, NodesNameTheirField) {
  const std::string name = "m.cameramodel";
  const PyValue v = ParsePythonDict("{'a': [1, 'x'], 'b': {'c': 2}}", name);
  const PyNode root(&v, "", &name);
  EXPECT_EQ(root.at("a", "add it").at(0).Number(), 1);
  EXPECT_EQ(root.at("b", "add it").at("c", "add it").path(), "b.c");
  EXPECT_FALSE(root.find("z").has_value());
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message([&] { root.at("a", "").at(1).Number(); }),
            "m.cameramodel: a[1]: expected a number, got the string 'x'; write a finite number");
  EXPECT_EQ(message([&] { root.at("z", "add 'z': [0, 0]"); }), "m.cameramodel: z: missing key; add 'z': [0, 0]");
  EXPECT_EQ(message([&] { root.at("b", "").ListSize(); }),
            "m.cameramodel: b: expected a list, got a dict; write it as [a, b, ...]");
  EXPECT_EQ(message([&] { root.at("a", "").at(5); }),
            "m.cameramodel: a: has 2 items, expected at least 6; add the missing items");
}

}  // namespace
}  // namespace vstcal
