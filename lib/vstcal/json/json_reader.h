// Validating JSON reader: every accessor knows its file and field path, so a bad value becomes a
// one-line InputError "<file>: <field>: <what is wrong>; <how to fix it>" (exit code 2).
#pragma once

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

namespace vstcal {

class JsonNode;

// A parsed JSON document and the name it is reported under.
class JsonDocument {
 public:
  // Reads and parses a file. Errors: cannot open, not valid JSON (with line and column; NaN and
  // Infinity get their own message), empty file.
  static JsonDocument Load(const std::filesystem::path& path);
  // Parses text already in memory; `name` is used in messages.
  static JsonDocument Parse(const std::string& text, std::string name);

  JsonNode root() const;
  const std::string& name() const { return name_; }

 private:
  std::string name_;
  nlohmann::json json_;
};

// A value inside a JsonDocument plus its path ("views[2].points[17][3]").
class JsonNode {
 public:
  JsonNode(const nlohmann::json* value, std::string path, const std::string* file)
      : value_(value), path_(std::move(path)), file_(file) {}

  // Required member of an object; missing → "missing field".
  JsonNode at(std::string_view key) const;
  // Optional member; nullopt when absent (a present null is returned, and fails its accessor).
  std::optional<JsonNode> find(std::string_view key) const;
  JsonNode at(size_t index) const;

  // Array length; fails unless the node is an array (of exactly `expected` items when given).
  size_t ArraySize(std::optional<size_t> expected = std::nullopt) const;
  void ExpectObject() const;

  double Number() const;  // finite
  double PositiveNumber() const;
  double NonNegativeNumber() const;
  int Integer() const;
  int PositiveInteger() const;
  bool Boolean() const;
  std::string String() const;
  // A string that must be one of `allowed`; the message lists them.
  std::string OneOf(std::initializer_list<std::string_view> allowed) const;
  std::string OneOf(std::span<const std::string_view> allowed) const;

  // Fixed-length numeric arrays and matrices given as arrays of rows.
  template <int N>
  Eigen::Matrix<double, N, 1> Vector() const {
    ArraySize(N);
    Eigen::Matrix<double, N, 1> v;
    for (int i = 0; i < N; ++i) v(i) = at(i).Number();
    return v;
  }
  template <int Rows, int Cols>
  Eigen::Matrix<double, Rows, Cols> Matrix() const {
    ArraySize(Rows);
    Eigen::Matrix<double, Rows, Cols> m;
    for (int r = 0; r < Rows; ++r) m.row(r) = at(r).Vector<Cols>().transpose();
    return m;
  }

  // Throws InputError "<file>: <path>: <reason>; <fix>".
  [[noreturn]] void Fail(std::string_view reason, std::string_view fix) const;

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  const nlohmann::json& json() const { return *value_; }

 private:
  std::string Describe() const;  // "a string", "null", "an array of 3", ...

  const nlohmann::json* value_;
  std::string path_;
  const std::string* file_;
};

}  // namespace vstcal
