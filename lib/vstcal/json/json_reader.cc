#include "vstcal/json/json_reader.h"

#include <cctype>
#include <cmath>

#include "vstcal/core/error.h"
#include "vstcal/json/reader_common.h"

namespace vstcal::io {
namespace {

bool IsTokenChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
}

// The token around byte `last` (the last byte nlohmann read, its reported position minus one):
// walks back to the token's start and forward to its end. Returns the token and its first byte.
std::pair<std::string, size_t> TokenNear(const std::string& text, size_t last) {
  if (last >= text.size()) return {"", text.size()};
  size_t begin = last, end = last;
  if (IsTokenChar(text[last])) {
    while (begin > 0 && IsTokenChar(text[begin - 1])) --begin;
    while (end < text.size() && IsTokenChar(text[end])) ++end;
  }
  return {text.substr(begin, end - begin), begin};
}

// A token quoted for a message: long ones (a 400-digit number) are shortened.
std::string Quote(const std::string& token) {
  return "'" + (token.size() <= 24 ? token : token.substr(0, 20) + "...") + "'";
}

// A SAX handler that builds nothing and only records where parsing failed. Used to find the
// position of a number overflow, which nlohmann reports without one (out_of_range.406).
class ErrorLocator : public nlohmann::json_sax<nlohmann::json> {
 public:
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override { return true; }
  bool key(string_t&) override { return true; }
  bool end_object() override { return true; }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::json::exception&) override {
    position_ = position;
    return false;
  }
  size_t position() const { return position_; }

 private:
  size_t position_ = 0;
};

bool IsNonFiniteToken(const std::string& token) {
  for (const char* word : {"NaN", "nan", "Infinity", "-Infinity", "inf", "-inf", "Inf", "-Inf", "-NaN", "-nan"}) {
    if (token == word) return true;
  }
  return false;
}

}  // namespace

JsonDocument JsonDocument::Load(const std::filesystem::path& path) {
  return Parse(ReadInputFile(path, "a JSON file"), path.string());
}

JsonDocument JsonDocument::Parse(const std::string& text, std::string name) {
  JsonDocument doc;
  doc.name_ = std::move(name);
  if (IsBlank(text)) throw InputError(doc.name_ + ": the file is empty; expected a JSON object");
  // nlohmann reports the byte after the offending token; `where` finds the token and its first byte.
  auto where = [&](size_t position) { return TokenNear(text, position > 0 ? position - 1 : 0); };
  try {
    doc.json_ = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    const auto [token, at] = where(e.byte);
    if (IsNonFiniteToken(token)) {
      FailSyntax(doc.name_, text, at, Quote(token) + " is not a JSON number",
                 "every value must be a finite number (remove or fix the point)");
    }
    FailSyntax(doc.name_, text, at, "not valid JSON", "fix the syntax there");
  } catch (const nlohmann::json::out_of_range&) {
    // A number too large for a double (1e999): parse again to find where.
    ErrorLocator locator;
    nlohmann::json::sax_parse(text, &locator);
    const auto [token, at] = where(locator.position());
    FailSyntax(doc.name_, text, at, Quote(token) + " is too large for a double",
               "every value must be a finite number (remove or fix the point)");
  }
  return doc;
}

JsonNode JsonDocument::root() const { return JsonNode(&json_, "", &name_); }

JsonNode JsonNode::at(std::string_view key) const {
  ExpectObject();
  const std::string child = path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  auto it = value_->find(key);
  if (it == value_->end()) {
    JsonNode(value_, child, file_).Fail("missing field", "add \"" + std::string(key) + "\"");
  }
  return JsonNode(&*it, child, file_);
}

std::optional<JsonNode> JsonNode::find(std::string_view key) const {
  ExpectObject();
  auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return JsonNode(&*it, path_.empty() ? std::string(key) : path_ + "." + std::string(key), file_);
}

JsonNode JsonNode::at(size_t index) const {
  const size_t n = ArraySize();
  if (index >= n) Fail("has " + std::to_string(n) + " items, expected at least " + std::to_string(index + 1), "add the missing items");
  return JsonNode(&(*value_)[index], path_ + "[" + std::to_string(index) + "]", file_);
}

size_t JsonNode::ArraySize(std::optional<size_t> expected) const {
  if (!value_->is_array()) Fail("expected an array, got " + Describe(), "write it as a JSON array");
  const size_t n = value_->size();
  if (expected && n != *expected) {
    Fail("expected " + std::to_string(*expected) + " items, got " + std::to_string(n),
         "give exactly " + std::to_string(*expected));
  }
  return n;
}

void JsonNode::ExpectObject() const {
  if (!value_->is_object()) Fail("expected an object, got " + Describe(), "write it as a JSON object { ... }");
}

double JsonNode::Number() const {
  if (!value_->is_number()) Fail("expected a number, got " + Describe(), "write a finite number");
  const double v = value_->get<double>();
  if (!std::isfinite(v)) Fail("the number is not finite", "write a finite number");
  return v;
}

double JsonNode::PositiveNumber() const {
  const double v = Number();
  if (!(v > 0)) Fail("must be positive, got " + value_->dump(), "give a value > 0");
  return v;
}

double JsonNode::NonNegativeNumber() const {
  const double v = Number();
  if (v < 0) Fail("must not be negative, got " + value_->dump(), "give a value ≥ 0");
  return v;
}

int JsonNode::Integer() const {
  const double v = Number();
  if (v != std::floor(v) || std::abs(v) > 2147483647.0) Fail("expected an integer, got " + value_->dump(), "write a whole number");
  return static_cast<int>(v);
}

int JsonNode::PositiveInteger() const {
  const int v = Integer();
  if (v <= 0) Fail("must be a positive integer, got " + value_->dump(), "give a whole number > 0");
  return v;
}

bool JsonNode::Boolean() const {
  if (!value_->is_boolean()) Fail("expected true or false, got " + Describe(), "write true or false");
  return value_->get<bool>();
}

std::string JsonNode::String() const {
  if (!value_->is_string()) Fail("expected a string, got " + Describe(), "write it in double quotes");
  return value_->get<std::string>();
}

std::string JsonNode::OneOf(std::initializer_list<std::string_view> allowed) const {
  return OneOf(std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string JsonNode::OneOf(std::span<const std::string_view> allowed) const {
  const std::string s = String();
  std::string list;
  for (std::string_view a : allowed) {
    if (a == s) return s;
    list += (list.empty() ? "\"" : ", \"") + std::string(a) + "\"";
  }
  Fail("unknown value \"" + s + "\"", "use one of " + list);
}

void JsonNode::Fail(std::string_view reason, std::string_view fix) const { FailField(*file_, path_, reason, fix); }

std::string JsonNode::Describe() const {
  switch (value_->type()) {
    case nlohmann::json::value_t::null: return "null";
    case nlohmann::json::value_t::object: return "an object";
    case nlohmann::json::value_t::array: return "an array of " + std::to_string(value_->size());
    case nlohmann::json::value_t::string: return "the string " + value_->dump();
    case nlohmann::json::value_t::boolean: return value_->dump();
    default: return "the number " + value_->dump();
  }
}

}  // namespace vstcal::io
