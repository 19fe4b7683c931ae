// Plain YAML (1.1, as ROS's camera_calibration and Kalibr write it) read through libyaml into a
// small tree, and the typed field access with the one-line errors of every vstcal reader
// (docs/formats.md#common). cv::FileStorage, the OpenCV reader's parser, needs "%YAML:1.0" and
// refuses a block sequence at its key's indentation, which PyYAML writes for Kalibr's T_cn_cnm1.
// Also the numbers and strings of the YAML that vstcal writes.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vstcal {

struct YamlNode {
  enum class Kind { kScalar, kSequence, kMap };
  Kind kind = Kind::kScalar;
  std::string scalar;  // kScalar: its text
  bool plain = true;   // kScalar: unquoted (only a plain scalar can be a number)
  std::vector<YamlNode> items;                           // kSequence
  std::vector<std::pair<std::string, YamlNode>> members;  // kMap, in file order
  size_t offset = 0;                                      // byte offset in the text, for messages

  // Declared here, defaulted in yaml_tree.cc, where the type is complete: clang 14 with libstdc++
  // 12 cannot instantiate `members`' destructor inside the definition of the type it holds.
  YamlNode();
  YamlNode(const YamlNode&);
  YamlNode(YamlNode&&) noexcept;
  YamlNode& operator=(const YamlNode&);
  YamlNode& operator=(YamlNode&&) noexcept;
  ~YamlNode();
};

// Parses one YAML document whose top level is a map. Throws InputError "<name>: line L, column C:
// <what>; <fix>" for a syntax error, an empty text, a text over limits::kMaxOpenCvYamlBytes, more
// than one document, an alias (*name), a key that is not a string, a key given twice, and nesting
// deeper than limits::kMaxNesting. `what` names the expected file ("a ROS camera_info file").
YamlNode ParseYamlMap(const std::string& text, const std::string& name, std::string_view what);

// A node and the field path it is reported under ("camera_matrix.data[3]").
struct YamlField {
  const YamlNode* node = nullptr;  // null: absent
  std::string path;
  const std::string* file = nullptr;

  [[noreturn]] void Fail(std::string_view reason, std::string_view fix) const;
  bool present() const { return node != nullptr; }
  // The member `key` of a map (absent when this is absent or `key` is not there); fails when this
  // is present but not a map.
  YamlField Member(std::string_view key) const;
  // "a map", "a sequence of 3", "the string \"x\"", "the number 2.5"
  std::string Describe() const;
  // Fails unless present; `fix` says what to add.
  void Require(std::string_view fix) const;
  // A plain scalar that is a finite decimal number (no .nan, .inf, hex).
  double Number() const;
  // A Number() that is a whole number within ±2³¹.
  int Integer(std::string_view fix) const;
  std::string String() const;
  // A sequence of `n` numbers (any count when n < 0).
  std::vector<double> Numbers(int n, std::string_view fix) const;
  YamlField Item(size_t i) const;
};

// The root of a parsed file as a field.
inline YamlField RootField(const YamlNode& root, const std::string& file) { return {&root, "", &file}; }

// A double as a YAML 1.1 float that reads back to the same bits: ShortestDecimal with a '.' in the
// mantissa ("1.0e-12", "640.0"), which PyYAML needs to read a float and not a string.
std::string YamlFloat(double v);
// A string plain when it cannot be read as anything else, else double-quoted with escapes.
std::string YamlString(std::string_view s);

}  // namespace vstcal
