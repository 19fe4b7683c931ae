// The Python-literal subset of mrcal's .cameramodel files: one dict holding strings, numbers,
// lists (and tuples), nested dicts, True/False/None, with '#' comments and trailing commas.
// mrcal's own reader evaluates the file as a Python literal; this parser takes the same subset
// but keeps where every value starts, so that a bad value is reported by file and field
// ("intrinsics[3]") and bad syntax by line and column (docs/formats.md#mrcal).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vstcal {

// A dict's key and value. Not std::pair: a pair of an incomplete PyValue inside PyValue is
// rejected by clang with libstdc++ (the fuzz build), a vector of a declared struct is not.
struct PyMember;

struct PyValue {
  enum class Kind { kNone, kBool, kNumber, kString, kList, kDict };
  Kind kind = Kind::kNone;
  double number = 0;           // kNumber (finite), kBool (0 or 1)
  bool integral = false;       // kNumber written as an integer (no '.', no exponent)
  std::string text;            // kString: the value (bytes and str alike); kNumber: as written
  std::vector<PyValue> items;  // kList: lists and tuples
  std::vector<PyMember> members;  // kDict: string keys, file order, unique
  size_t offset = 0;              // where the value starts in the text
};

struct PyMember {
  std::string first;  // the key
  PyValue second;
};

// Parses a text that holds exactly one dict. Throws InputError
// "<name>: line L, column C: <what is wrong>; <how to fix it>" for bad syntax, numbers that are
// not finite doubles (1e999), duplicate keys, non-string keys, and names other than True, False
// and None (nan, inf, float(...)).
PyValue ParsePythonDict(std::string_view text, const std::string& name);

// A value and its field path, for messages: accessors fail with
// "<file>: <path>: <what is wrong>; <how to fix it>".
class PyNode {
 public:
  PyNode(const PyValue* value, std::string path, const std::string* file)
      : value_(value), path_(std::move(path)), file_(file) {}

  std::optional<PyNode> find(std::string_view key) const;  // the node must be a dict
  PyNode at(std::string_view key, std::string_view fix_if_missing) const;
  PyNode at(size_t index) const;  // the node must be a list

  size_t ListSize() const;  // fails unless a list
  double Number() const;
  std::string String() const;

  [[noreturn]] void Fail(std::string_view reason, std::string_view fix) const;

  const std::string& path() const { return path_; }
  const PyValue& value() const { return *value_; }

 private:
  std::string Describe() const;  // "a string", "a list of 3", "the number 5"
  void ExpectDict() const;

  const PyValue* value_;
  std::string path_;
  const std::string* file_;
};

}  // namespace vstcal
