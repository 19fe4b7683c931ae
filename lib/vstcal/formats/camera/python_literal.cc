#include "vstcal/formats/camera/python_literal.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <unordered_set>

#include "vstcal/core/limits.h"

#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

bool IsIdentifierStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool IsIdentifierChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool IsDigit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// A quoted token for a message; long ones are shortened.
std::string Quote(std::string_view token) {
  // Built by appending: GCC 12's -Wrestrict misfires on "'" + std::string.
  std::string quoted(1, '\'');
  if (token.size() <= 24) return quoted.append(token).append("'");
  return quoted.append(token.substr(0, 20)).append("...'");
}

class Parser {
 public:
  Parser(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  PyValue Document() {
    SkipBlank();
    if (Peek() != '{') Fail(pos_, "expected '{': a .cameramodel file is one Python dict", "start it with '{'");
    PyValue v = Value(0);
    SkipBlank();
    if (pos_ < text_.size()) Fail(pos_, "unexpected text after the dict's closing '}'", "remove it");
    return v;
  }

 private:
  [[noreturn]] void Fail(size_t at, std::string_view reason, std::string_view fix) const {
    FailSyntax(name_, text_, at, reason, fix);
  }

  char Peek(size_t ahead = 0) const { return pos_ + ahead < text_.size() ? text_[pos_ + ahead] : '\0'; }
  bool AtEnd() const { return pos_ >= text_.size(); }

  // Whitespace, '#' comments to the end of the line, and backslash line continuations.
  void SkipBlank() {
    while (!AtEnd()) {
      const char c = Peek();
      if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
        ++pos_;
      } else if (c == '#') {
        while (!AtEnd() && Peek() != '\n') ++pos_;
      } else if (c == '\\' && (Peek(1) == '\n' || (Peek(1) == '\r' && Peek(2) == '\n'))) {
        pos_ += Peek(1) == '\n' ? 2 : 3;
      } else {
        return;
      }
    }
  }

  // Length of a string prefix (b, r, u, br, rb in any case) followed by a quote at pos_; 0 if none.
  size_t StringPrefixLength() const {
    size_t n = 0;
    while (n < 2 && std::string_view("bBrRuU").find(Peek(n)) != std::string_view::npos) ++n;
    return (Peek(n) == '\'' || Peek(n) == '"') ? n + 1 : 0;
  }
  bool AtString() const { return Peek() == '\'' || Peek() == '"' || StringPrefixLength() > 0; }

  PyValue Value(int depth) {
    // The parser recurses once a level: deeper nesting would exhaust the stack, and more values the
    // memory (docs/reliability.md#limits).
    if (depth > limits::kMaxNesting) {
      Fail(pos_, "nested more than " + std::to_string(limits::kMaxNesting) + " levels deep",
           "a camera model needs a few levels at most");
    }
    if (++values_ > limits::kMaxLiteralValues) {
      Fail(pos_, "more than " + std::to_string(limits::kMaxLiteralValues) + " values",
           "a camera model holds a few dozen; check that this is the right file");
    }
    SkipBlank();
    const size_t start = pos_;
    if (AtEnd()) Fail(pos_, "unexpected end of file: a value is missing", "complete the file (is it truncated?)");
    const char c = Peek();
    PyValue v;
    if (c == '{') {
      v = Dict(depth);
    } else if (c == '[' || c == '(') {
      v = List(depth);
    } else if (AtString()) {
      v = Strings();
    } else if (IsDigit(c) || c == '.' || c == '-' || c == '+') {
      v = Number();
    } else if (IsIdentifierStart(c)) {
      v = Word();
    } else {
      Fail(pos_, "unexpected " + Quote(std::string(1, c)), "fix the syntax there");
    }
    v.offset = start;
    return v;
  }

  PyValue Dict(int depth) {
    PyValue v;
    v.kind = PyValue::Kind::kDict;
    std::unordered_set<std::string> keys;
    ++pos_;  // '{'
    SkipBlank();
    while (Peek() != '}') {
      const size_t key_at = pos_;
      PyValue key = Value(depth + 1);
      if (key.kind != PyValue::Kind::kString) Fail(key_at, "a key must be a string", "quote the key: 'name'");
      if (!keys.insert(key.text).second) Fail(key_at, "duplicate key " + Quote(key.text), "keep one of them");
      SkipBlank();
      if (Peek() != ':') Fail(pos_, "expected ':' after the key " + Quote(key.text), "write 'key': value");
      ++pos_;
      PyValue value = Value(depth + 1);
      v.members.push_back({std::move(key.text), std::move(value)});
      if (!Separator('}')) break;
    }
    Close('}', "the dict");
    return v;
  }

  PyValue List(int depth) {
    PyValue v;
    v.kind = PyValue::Kind::kList;
    const char close = Peek() == '[' ? ']' : ')';
    ++pos_;
    SkipBlank();
    while (Peek() != close) {
      v.items.push_back(Value(depth + 1));
      if (!Separator(close)) break;
    }
    Close(close, close == ']' ? "the list" : "the tuple");
    return v;
  }

  // After an item: a ',' (then more items, or the closing bracket: trailing commas are Python)
  // returns true; the closing bracket returns false; anything else is an error.
  bool Separator(char close) {
    SkipBlank();
    if (Peek() == ',') {
      ++pos_;
      SkipBlank();
      return Peek() != close && !AtEnd();  // at the end, Close() reports the missing bracket
    }
    if (Peek() == close) return false;
    if (AtEnd()) return false;  // Close() reports the missing bracket
    Fail(pos_, std::string("expected ',' or '") + close + "'", "separate the items with commas");
  }

  void Close(char close, std::string_view what) {
    if (Peek() != close) {
      Fail(pos_, "unexpected end of file: " + std::string(what) + " is not closed",
           std::string("add the closing '") + close + "' (is the file truncated?)");
    }
    ++pos_;
  }

  // One string literal, or several written side by side (Python joins them).
  PyValue Strings() {
    PyValue v;
    v.kind = PyValue::Kind::kString;
    do {
      v.text += String();
      SkipBlank();
    } while (AtString());
    return v;
  }

  std::string String() {
    const size_t start = pos_;
    const size_t prefix = StringPrefixLength() - 1;
    const bool raw = std::string_view(text_.substr(pos_, prefix)).find_first_of("rR") != std::string_view::npos;
    pos_ += prefix;
    const char quote = Peek();
    const bool triple = Peek(1) == quote && Peek(2) == quote;
    pos_ += triple ? 3 : 1;
    std::string out;
    while (true) {
      if (AtEnd() || (!triple && Peek() == '\n')) {
        Fail(start, "the string is not closed", std::string("end it with ") + quote + " on the same line");
      }
      const char c = Peek();
      if (c == quote && (!triple || (Peek(1) == quote && Peek(2) == quote))) {
        pos_ += triple ? 3 : 1;
        return out;
      }
      if (c == '\\' && pos_ + 1 < text_.size()) {
        const char e = Peek(1);
        pos_ += 2;
        if (raw) {
          out += c;
          out += e;
        } else if (e == 'n') {
          out += '\n';
        } else if (e == 't') {
          out += '\t';
        } else if (e == '\\' || e == '\'' || e == '"') {
          out += e;
        } else if (e != '\n') {  // a backslash-newline inside a string joins the lines
          out += c;
          out += e;
        }
        continue;
      }
      out += c;
      ++pos_;
    }
  }

  // A decimal integer or float with an optional sign ("1", "-2.5", "1e-12", ".5", "1_000").
  PyValue Number() {
    const size_t start = pos_;
    std::string digits;
    if (Peek() == '-' || Peek() == '+') digits += text_[pos_++];
    bool any_digit = false, integral = true;
    auto take_digits = [&] {
      while (IsDigit(Peek()) || Peek() == '_') {
        if (Peek() != '_') {
          digits += Peek();
          any_digit = true;
        }
        ++pos_;
      }
    };
    take_digits();
    if (Peek() == '.') {
      integral = false;
      digits += text_[pos_++];
      take_digits();
    }
    if (any_digit && (Peek() == 'e' || Peek() == 'E')) {
      integral = false;
      digits += text_[pos_++];
      if (Peek() == '-' || Peek() == '+') digits += text_[pos_++];
      if (!IsDigit(Peek())) Fail(start, "the exponent has no digits", "write a number such as 1e-12");
      take_digits();
    }
    while (IsIdentifierChar(Peek()) || Peek() == '.') ++pos_;  // the rest of a malformed token, for the message
    const std::string_view token = text_.substr(start, pos_ - start);
    if (!any_digit || token.size() != digits.size() + std::count(token.begin(), token.end(), '_')) {
      Fail(start, Quote(token) + " is not a number", "write a decimal number such as -0.25 or 1e-12");
    }
    char* end = nullptr;
    const double x = std::strtod(digits.c_str(), &end);  // correctly rounded, like Python's float()
    if (!std::isfinite(x)) {
      Fail(start, Quote(token) + " is too large for a double", "every value must be a finite number");
    }
    PyValue v;
    v.kind = PyValue::Kind::kNumber;
    v.number = x;
    v.integral = integral;
    v.text = std::string(token);
    return v;
  }

  PyValue Word() {
    const size_t start = pos_;
    while (IsIdentifierChar(Peek())) ++pos_;
    const std::string_view word = text_.substr(start, pos_ - start);
    PyValue v;
    if (word == "True" || word == "False") {
      v.kind = PyValue::Kind::kBool;
      v.number = word == "True";
    } else if (word != "None") {
      Fail(start, Quote(word) + " is not a Python literal",
           "a .cameramodel holds numbers, strings, lists and dicts only (write a finite number, or quote a string)");
    }
    return v;
  }

  std::string_view text_;
  const std::string& name_;
  size_t pos_ = 0;
  size_t values_ = 0;
};

}  // namespace

PyValue ParsePythonDict(std::string_view text, const std::string& name) { return Parser(text, name).Document(); }

void PyNode::Fail(std::string_view reason, std::string_view fix) const { FailField(*file_, path_, reason, fix); }

std::string PyNode::Describe() const {
  switch (value_->kind) {
    case PyValue::Kind::kNone:
      return "None";
    case PyValue::Kind::kBool:
      return value_->number != 0 ? "True" : "False";
    case PyValue::Kind::kNumber:
      return "the number " + value_->text;
    case PyValue::Kind::kString:
      return "the string " + Quote(value_->text);
    case PyValue::Kind::kList:
      return "a list of " + std::to_string(value_->items.size());
    case PyValue::Kind::kDict:
      return "a dict";
  }
  return "?";
}

void PyNode::ExpectDict() const {
  if (value_->kind != PyValue::Kind::kDict) {
    Fail("expected a dict, got " + Describe(), "write it as { 'key': value, ... }");
  }
}

std::optional<PyNode> PyNode::find(std::string_view key) const {
  ExpectDict();
  for (const auto& [k, v] : value_->members) {
    if (k == key) return PyNode(&v, path_.empty() ? std::string(key) : path_ + "." + std::string(key), file_);
  }
  return std::nullopt;
}

PyNode PyNode::at(std::string_view key, std::string_view fix_if_missing) const {
  if (auto node = find(key)) return *node;
  PyNode(value_, path_.empty() ? std::string(key) : path_ + "." + std::string(key), file_)
      .Fail("missing key", fix_if_missing);
}

size_t PyNode::ListSize() const {
  if (value_->kind != PyValue::Kind::kList) Fail("expected a list, got " + Describe(), "write it as [a, b, ...]");
  return value_->items.size();
}

PyNode PyNode::at(size_t index) const {
  const size_t n = ListSize();
  if (index >= n) {
    Fail("has " + std::to_string(n) + " items, expected at least " + std::to_string(index + 1),
         "add the missing items");
  }
  return PyNode(&value_->items[index], path_ + "[" + std::to_string(index) + "]", file_);
}

double PyNode::Number() const {
  if (value_->kind != PyValue::Kind::kNumber) Fail("expected a number, got " + Describe(), "write a finite number");
  return value_->number;
}

std::string PyNode::String() const {
  if (value_->kind != PyValue::Kind::kString) Fail("expected a string, got " + Describe(), "write it in quotes");
  return value_->text;
}

}  // namespace vstcal
