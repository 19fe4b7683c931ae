// Writing JSON: ordered objects (fields in the order the format documents them), Eigen helpers,
// and an atomic file write so a failing tool never leaves a partial output behind.
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "vstcal/geometry/rigid3.h"

namespace vstcal::io {

using OrderedJson = nlohmann::ordered_json;

// A matrix as an array of rows; a vector as a flat array.
template <typename Derived>
OrderedJson MatrixToJson(const Eigen::MatrixBase<Derived>& m) {
  OrderedJson rows = OrderedJson::array();
  if (m.cols() == 1) {
    for (Eigen::Index i = 0; i < m.rows(); ++i) rows.push_back(static_cast<double>(m(i)));
    return rows;
  }
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    OrderedJson row = OrderedJson::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(static_cast<double>(m(r, c)));
    rows.push_back(std::move(row));
  }
  return rows;
}

// {"R": [[...]], "t": [...]}
OrderedJson RigidToJson(const Rigid3d& a_from_b);

// A double in the shortest decimal form that reads back to the same bits, as every vstcal file
// writes numbers ("0.1", "1e-12", "640.0").
inline std::string ShortestDecimal(double v) { return OrderedJson(v).dump(); }

// Two-space indented text with a final newline; doubles in shortest round-trip form.
std::string DumpJson(const OrderedJson& json);
// The same on one line (and a final newline): for machine-to-machine files whose size matters
// (err-sim's shard files), where the indentation would triple it.
std::string DumpJsonCompact(const OrderedJson& json);

// Writes text to `path` through a temporary file in the same directory and a rename, so the
// path either holds the complete new file or is untouched. Throws InputError when the directory
// does not exist or is not writable.
void WriteFileAtomically(const std::filesystem::path& path, const std::string& text);

// Writes several files all-or-nothing: every text goes to a temporary file first; only when all
// are written are they renamed into place, so a failure leaves none of the outputs behind (if a
// rename fails midway, the outputs already renamed are removed). Refuses, before writing, an
// empty name or one file named for two outputs.
void WriteFilesAtomically(const std::vector<std::pair<std::filesystem::path, std::string>>& files);

inline void WriteJsonFile(const std::filesystem::path& path, const OrderedJson& json) {
  WriteFileAtomically(path, DumpJson(json));
}

}  // namespace vstcal::io
