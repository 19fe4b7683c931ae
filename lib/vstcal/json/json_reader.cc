#include "vstcal/json/json_reader.h"

#include <cctype>
#include <cmath>
#include <iterator>
#include <vector>

#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
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

bool IsNonFiniteToken(const std::string& token) {
  for (const char* word : {"NaN", "nan", "Infinity", "-Infinity", "inf", "-inf", "Inf", "-Inf", "-NaN", "-nan"}) {
    if (token == word) return true;
  }
  return false;
}

// A pointer into the text that records how far nlohmann's lexer has read: the SAX callbacks carry
// no position, and a duplicate key or a too-deep bracket is reported by line and column.
class TrackedIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackedIterator(const char* p, const char** read_to) : p_(p), read_to_(read_to) {}
  reference operator*() const { return *p_; }
  TrackedIterator& operator++() {
    *read_to_ = ++p_;
    return *this;
  }
  TrackedIterator operator++(int) {
    TrackedIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const TrackedIterator& o) const { return p_ == o.p_; }
  bool operator!=(const TrackedIterator& o) const { return p_ != o.p_; }

 private:
  const char* p_;
  const char** read_to_;
};

// Builds the document as nlohmann's own DOM parser does, but strictly: a key given twice in one
// object, nesting deeper than limits::kMaxNesting and more than limits::kMaxJsonValues values
// stop the parse (nlohmann alone keeps the last duplicate silently).
class StrictBuilder {
 public:
  using Json = nlohmann::json;
  using number_integer_t = Json::number_integer_t;
  using number_unsigned_t = Json::number_unsigned_t;
  using number_float_t = Json::number_float_t;
  using string_t = Json::string_t;
  using binary_t = Json::binary_t;

  enum class Problem { kNone, kSyntax, kDuplicateKey, kTooDeep, kTooManyValues };

  explicit StrictBuilder(Json* root) : root_(root) {}

  bool null() { return Add(nullptr); }
  bool boolean(bool v) { return Add(v); }
  bool number_integer(number_integer_t v) { return Add(v); }
  bool number_unsigned(number_unsigned_t v) { return Add(v); }
  bool number_float(number_float_t v, const string_t&) { return Add(v); }
  bool string(string_t& v) { return Add(std::move(v)); }
  bool binary(binary_t&) { return Fail(Problem::kSyntax); }  // not produced by JSON text
  bool start_object(std::size_t) { return Open(Json::value_t::object); }
  bool start_array(std::size_t) { return Open(Json::value_t::array); }
  bool end_object() { return Close(); }
  bool end_array() { return Close(); }
  bool key(string_t& k) {
    Level& top = stack_.back();
    auto& members = top.node->get_ref<Json::object_t&>();
    const auto [it, inserted] = members.emplace(k, nullptr);
    if (!inserted) {
      duplicate_ = k;
      return Fail(Problem::kDuplicateKey);
    }
    top.key = &it->first;
    element_ = &it->second;
    return true;
  }
  bool parse_error(std::size_t position, const std::string&, const Json::exception& e) {
    error_position_ = position;
    error_id_ = e.id;
    return Fail(Problem::kSyntax);
  }

  Problem problem() const { return problem_; }
  size_t error_position() const { return error_position_; }
  int error_id() const { return error_id_; }
  const std::string& duplicate() const { return duplicate_; }
  // The path of the object being filled ("views[2]"), for the duplicate-key message.
  std::string Path() const {
    std::string path;
    for (size_t i = 1; i < stack_.size(); ++i) {
      const Level& parent = stack_[i - 1];
      if (parent.node->is_array()) {
        path += "[" + std::to_string(parent.node->size() - 1) + "]";
      } else {
        path += (path.empty() ? "" : ".") + *parent.key;
      }
    }
    return path;
  }

 private:
  struct Level {
    Json* node;
    const std::string* key = nullptr;  // the member being filled, for objects
  };

  bool Fail(Problem p) {
    problem_ = p;
    return false;
  }

  // Places a value where the parser is: the root, the next array item or the current member.
  template <typename Value>
  Json* Place(Value&& v) {
    if (++values_ > limits::kMaxJsonValues) return nullptr;
    if (stack_.empty()) {
      *root_ = Json(std::forward<Value>(v));
      return root_;
    }
    Json& top = *stack_.back().node;
    if (top.is_array()) {
      top.get_ref<Json::array_t&>().emplace_back(std::forward<Value>(v));
      return &top.get_ref<Json::array_t&>().back();
    }
    *element_ = Json(std::forward<Value>(v));
    return element_;
  }

  template <typename Value>
  bool Add(Value&& v) {
    return Place(std::forward<Value>(v)) != nullptr || Fail(Problem::kTooManyValues);
  }

  bool Open(Json::value_t type) {
    if (stack_.size() >= static_cast<size_t>(limits::kMaxNesting)) return Fail(Problem::kTooDeep);
    Json* node = Place(type);
    if (node == nullptr) return Fail(Problem::kTooManyValues);
    stack_.push_back({node});
    return true;
  }

  bool Close() {
    stack_.pop_back();
    return true;
  }

  Json* root_;
  std::vector<Level> stack_;
  Json* element_ = nullptr;
  size_t values_ = 0;
  Problem problem_ = Problem::kNone;
  size_t error_position_ = 0;
  int error_id_ = 0;
  std::string duplicate_;
};

// The byte where the string that ends at `close` (its closing quote) begins.
size_t StringStart(const std::string& text, size_t close) {
  for (size_t i = close; i-- > 0;) {
    if (text[i] != '"') continue;
    size_t backslashes = 0;
    while (backslashes < i && text[i - 1 - backslashes] == '\\') ++backslashes;
    if (backslashes % 2 == 0) return i;
  }
  return 0;
}

}  // namespace

JsonDocument JsonDocument::Load(const std::filesystem::path& path) {
  return Parse(ReadInputFile(path, "a JSON file"), path.string());
}

JsonDocument JsonDocument::Parse(const std::string& text, std::string name) {
  JsonDocument doc;
  doc.name_ = std::move(name);
  if (IsBlank(text)) throw InputError(doc.name_ + ": the file is empty; expected a JSON object");
  StrictBuilder first(&doc.json_);
  if (nlohmann::json::sax_parse(text.data(), text.data() + text.size(), &first)) return doc;
  // It failed: parse again, tracking how far the lexer reads, to say where (the fast path above
  // pays nothing for positions).
  nlohmann::json partial;
  StrictBuilder builder(&partial);
  const char* read_to = text.data();
  nlohmann::json::sax_parse(TrackedIterator(text.data(), &read_to), TrackedIterator(text.data() + text.size(), &read_to),
                            &builder);
  const size_t read = static_cast<size_t>(read_to - text.data());  // bytes the lexer consumed
  switch (builder.problem()) {
    case StrictBuilder::Problem::kDuplicateKey: {
      const std::string path = builder.Path();
      FailSyntax(doc.name_, text, StringStart(text, read - 1),
                 "duplicate key \"" + builder.duplicate() + "\" in " +
                     (path.empty() ? std::string("the top-level object") : path),
                 "keep one of them (JSON readers disagree on which one counts)");
    }
    case StrictBuilder::Problem::kTooDeep:
      FailSyntax(doc.name_, text, read - 1,
                 "nested more than " + std::to_string(limits::kMaxNesting) + " levels deep",
                 "vstcal's formats need a few levels; check that this is the right file");
    case StrictBuilder::Problem::kTooManyValues:
      FailSyntax(doc.name_, text, read > 0 ? read - 1 : 0,
                 "more than " + std::to_string(limits::kMaxJsonValues) + " values",
                 "split the data into smaller files");
    default:
      break;
  }
  // nlohmann reports the byte after the offending token; TokenNear finds the token and its start.
  const size_t position = builder.error_position();
  const auto [token, at] = TokenNear(text, position > 0 ? position - 1 : 0);
  if (builder.error_id() == 406) {  // out_of_range.406: a number too large for a double (1e999)
    FailSyntax(doc.name_, text, at, Quote(token) + " is too large for a double",
               "every value must be a finite number (remove or fix the point)");
  }
  if (IsNonFiniteToken(token)) {
    FailSyntax(doc.name_, text, at, Quote(token) + " is not a JSON number",
               "every value must be a finite number (remove or fix the point)");
  }
  // A camera in another format, given where vstcal's JSON is read: say what it is and what to do.
  const std::string extension = std::filesystem::path(doc.name_).extension().string();
  if (text.starts_with("%YAML") || extension == ".yaml" || extension == ".yml" || extension == ".cameramodel") {
    const bool yaml = extension != ".cameramodel";
    FailSyntax(doc.name_, text, at,
               std::string("not valid JSON: this is ") + (yaml ? "an OpenCV FileStorage YAML" : "a mrcal .cameramodel") +
                   " file, and vstcal's JSON formats are read here",
               "convert a camera with calib-convert (e.g. calib-convert " + doc.name_ +
                   " -o camera.json); calib-convert and calib-stereo read YAML and .cameramodel cameras directly");
  }
  FailSyntax(doc.name_, text, at, "not valid JSON", "fix the syntax there");
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
  if (v != std::floor(v)) Fail("expected an integer, got " + value_->dump(), "write a whole number");
  if (std::abs(v) > 2147483647.0) {
    Fail("the integer " + value_->dump() + " is out of range", "write a whole number from -2147483647 to 2147483647");
  }
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

}  // namespace vstcal
