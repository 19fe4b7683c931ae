#include "vstcal/formats/camera/yaml_tree.h"

#include <yaml.h>

#include <cctype>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <cmath>
#include <memory>
#include <optional>

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {

YamlNode::YamlNode() = default;
YamlNode::YamlNode(const YamlNode&) = default;
YamlNode::YamlNode(YamlNode&&) noexcept = default;
YamlNode& YamlNode::operator=(const YamlNode&) = default;
YamlNode& YamlNode::operator=(YamlNode&&) noexcept = default;
YamlNode::~YamlNode() = default;

namespace {

// One open collection while the events are turned into a tree: libyaml's parser keeps its own
// state on the heap, and so does this, so no input nests the C++ stack.
struct OpenContainer {
  YamlNode node;
  std::string key;  // a map's key waiting for its value
  bool have_key = false;
};

struct YamlParser {
  yaml_parser_t parser;
  YamlParser() { yaml_parser_initialize(&parser); }
  ~YamlParser() { yaml_parser_delete(&parser); }
};

struct Event {
  yaml_event_t event;
  ~Event() { yaml_event_delete(&event); }
};

bool IsNumberText(std::string_view s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (!((c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' || c == 'E')) return false;
  }
  return true;
}

}  // namespace

YamlNode ParseYamlMap(const std::string& text, const std::string& name, std::string_view what) {
  if (IsBlank(text)) throw InputError(name + ": the file is empty; expected " + std::string(what));
  if (text.size() > limits::kMaxOpenCvYamlBytes) {
    throw InputError(name + ": larger than the " + std::to_string(limits::kMaxOpenCvYamlBytes >> 20) +
                     " MiB vstcal reads as YAML (docs/reliability.md#limits); check that it is " + std::string(what));
  }
  YamlParser p;
  yaml_parser_set_input_string(&p.parser, reinterpret_cast<const unsigned char*>(text.data()), text.size());
  std::vector<OpenContainer> stack;
  std::optional<YamlNode> root;
  int documents = 0;
  // Adds a finished node to the collection it belongs to, or makes it the root.
  auto attach = [&](YamlNode node, size_t offset) {
    if (stack.empty()) {
      root = std::move(node);
      return;
    }
    OpenContainer& top = stack.back();
    if (top.node.kind == YamlNode::Kind::kSequence) {
      top.node.items.push_back(std::move(node));
    } else if (!top.have_key) {
      if (node.kind != YamlNode::Kind::kScalar) {
        FailSyntax(name, text, offset, "a key that is a collection", "keys are names: write \"name: value\"");
      }
      for (const auto& [key, value] : top.node.members) {
        if (key == node.scalar) {
          FailSyntax(name, text, offset, "the key \"" + key + "\" appears a second time in this map", "keep one");
        }
      }
      top.key = std::move(node.scalar);
      top.have_key = true;
    } else {
      top.node.members.emplace_back(std::move(top.key), std::move(node));
      top.have_key = false;
    }
  };
  for (bool done = false; !done;) {
    Event e;
    if (!yaml_parser_parse(&p.parser, &e.event)) {
      const std::string problem = p.parser.problem ? p.parser.problem : "a syntax error";
      const std::string context = p.parser.context ? std::string(" ") + p.parser.context : "";
      FailSyntax(name, text, std::min(p.parser.problem_mark.index, text.size()),
                 "not valid YAML (" + problem + context + ")", "fix the syntax there");
    }
    const size_t offset = e.event.start_mark.index;
    switch (e.event.type) {
      case YAML_DOCUMENT_START_EVENT:
        if (++documents > 1) {
          FailSyntax(name, text, offset, "a second YAML document",
                     "a camera file is one document: keep its fields in the first and delete the rest");
        }
        break;
      case YAML_ALIAS_EVENT:
        FailSyntax(name, text, offset, "an alias (*name)", "write the value itself: camera files use no anchors");
      case YAML_SCALAR_EVENT: {
        YamlNode node;
        node.scalar.assign(reinterpret_cast<const char*>(e.event.data.scalar.value), e.event.data.scalar.length);
        node.plain = e.event.data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
        node.offset = offset;
        attach(std::move(node), offset);
        break;
      }
      case YAML_SEQUENCE_START_EVENT:
      case YAML_MAPPING_START_EVENT: {
        if (static_cast<int>(stack.size()) + 1 > limits::kMaxNesting) {
          FailSyntax(name, text, offset, "nested more than " + std::to_string(limits::kMaxNesting) + " levels deep",
                     "a camera file needs 3 levels; check that this is the right file");
        }
        OpenContainer open;
        open.node.kind =
            e.event.type == YAML_SEQUENCE_START_EVENT ? YamlNode::Kind::kSequence : YamlNode::Kind::kMap;
        open.node.offset = offset;
        stack.push_back(std::move(open));
        break;
      }
      case YAML_SEQUENCE_END_EVENT:
      case YAML_MAPPING_END_EVENT: {
        YamlNode node = std::move(stack.back().node);
        stack.pop_back();
        attach(std::move(node), node.offset);
        break;
      }
      case YAML_STREAM_END_EVENT:
        done = true;
        break;
      default:
        break;
    }
  }
  if (!root || root->kind != YamlNode::Kind::kMap) {
    FailField(name, "", "the top level is not a map of named fields",
              "write fields as \"name: value\" lines; expected " + std::string(what));
  }
  return std::move(*root);
}

void YamlField::Fail(std::string_view reason, std::string_view fix) const { FailField(*file, path, reason, fix); }

YamlField YamlField::Member(std::string_view key) const {
  const std::string child = path.empty() ? std::string(key) : path + "." + std::string(key);
  if (!node) return {nullptr, child, file};
  if (node->kind != YamlNode::Kind::kMap) Fail("expected a map, got " + Describe(), "write \"name: value\" lines under it");
  for (const auto& [k, v] : node->members) {
    if (k == key) return {&v, child, file};
  }
  return {nullptr, child, file};
}

std::string YamlField::Describe() const {
  if (!node) return "nothing";
  switch (node->kind) {
    case YamlNode::Kind::kMap:
      return "a map";
    case YamlNode::Kind::kSequence:
      return "a sequence of " + std::to_string(node->items.size());
    case YamlNode::Kind::kScalar:
      break;
  }
  std::string shown = node->scalar.size() > 40 ? node->scalar.substr(0, 40) + "…" : node->scalar;
  return (node->plain && IsNumberText(node->scalar) ? "\"" : "the string \"") + shown + "\"";
}

void YamlField::Require(std::string_view fix) const {
  if (!node) Fail("missing field", fix);
}

double YamlField::Number() const {
  Require("write a finite number");
  if (node->kind == YamlNode::Kind::kScalar && node->plain) {
    // YAML's spellings of NaN and ±∞ (.nan, -.inf, .Inf, …) are numbers, and not finite ones.
    std::string lower = node->scalar;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (lower == ".nan" || lower == ".inf" || lower == "+.inf" || lower == "-.inf") {
      Fail("the number " + node->scalar + " is not finite", "write a finite number");
    }
  }
  if (node->kind != YamlNode::Kind::kScalar || !node->plain || !IsNumberText(node->scalar)) {
    Fail("expected a number, got " + Describe(), "write a finite decimal number");
  }
  const std::string& s = node->scalar;
  // YAML 1.1 (PyYAML, so Kalibr) reads 010 as octal 8: a leading zero is refused, not guessed.
  const size_t digits = s.find_first_not_of("+-");
  if (digits != std::string::npos && s[digits] == '0' && digits + 1 < s.size() && s[digits + 1] >= '0' &&
      s[digits + 1] <= '9') {
    Fail("the number " + s + " has a leading zero, which YAML 1.1 reads as octal", "drop the leading zero");
  }
  double v = 0;
  const char* begin = s.data() + (s[0] == '+');
  const auto [end, ec] = std::from_chars(begin, s.data() + s.size(), v);
  if (ec == std::errc::result_out_of_range) Fail("the number " + s + " is beyond the doubles", "write a finite number");
  if (ec != std::errc() || end != s.data() + s.size()) Fail("expected a number, got " + Describe(), "write a decimal number");
  if (!std::isfinite(v)) Fail("the number is not finite", "write a finite number");
  return v;
}

int YamlField::Integer(std::string_view fix) const {
  const double v = Number();
  if (v != std::floor(v) || std::abs(v) > 2147483647.0) Fail("expected a whole number, got " + ShortestDecimal(v), fix);
  return static_cast<int>(v);
}

std::string YamlField::String() const {
  Require("write a string");
  if (node->kind != YamlNode::Kind::kScalar) Fail("expected a string, got " + Describe(), "write a string");
  return node->scalar;
}

YamlField YamlField::Item(size_t i) const { return {&node->items[i], path + "[" + std::to_string(i) + "]", file}; }

std::vector<double> YamlField::Numbers(int n, std::string_view fix) const {
  Require(fix);
  if (node->kind != YamlNode::Kind::kSequence) Fail("expected a sequence [ ... ], got " + Describe(), fix);
  if (n >= 0 && node->items.size() != static_cast<size_t>(n)) {
    Fail("expected " + std::to_string(n) + " numbers, got " + std::to_string(node->items.size()), fix);
  }
  std::vector<double> out;
  for (size_t i = 0; i < node->items.size(); ++i) out.push_back(Item(i).Number());
  return out;
}

std::string YamlFloat(double v) {
  std::string s = ShortestDecimal(v);
  const size_t e = s.find_first_of("eE");
  if (s.find('.') == std::string::npos) s.insert(e == std::string::npos ? s.size() : e, ".0");
  return s;
}

std::string YamlString(std::string_view s) {
  bool plain = !s.empty() && !IsNumberText(s);
  for (const char c : s) {
    const bool safe = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
                      c == '/' || c == '.' || c == '-';
    plain = plain && safe;
  }
  // YAML 1.1 reads these plain words as booleans or null.
  for (const std::string_view word : {"y", "Y", "yes", "Yes", "YES", "n", "N", "no", "No", "NO", "true", "True", "TRUE",
                                      "false", "False", "FALSE", "on", "On", "ON", "off", "Off", "OFF", "null", "Null",
                                      "NULL"}) {
    plain = plain && s != word;
  }
  // Starting with a letter, '/' or '_': never a number in YAML 1.1 (which reads 1_000 as 1000).
  const char first = s.empty() ? ' ' : s.front();
  if (plain && ((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z') || first == '/' || first == '_')) {
    return std::string(s);
  }
  // Double-quoted: what YAML allows printed is copied, everything else escaped (\xXX, \uXXXX,
  // \UXXXXXXXX), so that libyaml reads back the same string whatever it holds.
  std::string out = "\"";
  char buffer[16];
  for (size_t i = 0; i < s.size();) {
    const auto byte = static_cast<unsigned char>(s[i]);
    if (byte < 0x80) {
      if (byte == '"' || byte == '\\') {
        out += '\\';
        out += static_cast<char>(byte);
      } else if (byte >= 0x20 && byte < 0x7F) {
        out += static_cast<char>(byte);
      } else {
        std::snprintf(buffer, sizeof buffer, "\\x%02X", byte);
        out += buffer;
      }
      ++i;
      continue;
    }
    // A UTF-8 sequence (the readers give valid UTF-8: libyaml and nlohmann check it).
    const int length = byte >= 0xF0 ? 4 : byte >= 0xE0 ? 3 : byte >= 0xC0 ? 2 : 1;
    uint32_t code = length == 1 ? byte : byte & (0x7F >> length);
    for (int k = 1; k < length && i + k < s.size(); ++k) code = (code << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    const bool printable = code == 0x85 || (code >= 0xA0 && code <= 0xD7FF) ||
                           (code >= 0xE000 && code <= 0xFFFD && code != 0xFEFF) || (code >= 0x10000 && code <= 0x10FFFF);
    if (printable && length > 1 && i + length <= s.size()) {
      out.append(s.substr(i, length));
    } else if (code <= 0xFFFF && !(code >= 0xD800 && code <= 0xDFFF)) {
      std::snprintf(buffer, sizeof buffer, "\\u%04X", static_cast<unsigned>(code));
      out += buffer;
    } else {
      out += "\\uFFFD";  // not a character: the replacement character
    }
    i += length;
  }
  return out + "\"";
}

}  // namespace vstcal
