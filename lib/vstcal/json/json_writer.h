// Writing JSON: ordered objects (fields in the order the format documents them), Eigen helpers,
// and WriteJsonFile (files/atomic_write.h: a failing tool never leaves a partial output behind).
#pragma once

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "vstcal/files/atomic_write.h"
#include "vstcal/geometry/rigid3.h"

namespace vstcal {

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

// A number, or null where it is undefined (NaN, ±∞: a quantity a report states is unknown, such
// as a standard error from one sample); the format's docs say which fields may be null.
inline OrderedJson NumberOrNull(double v) { return std::isfinite(v) ? OrderedJson(v) : OrderedJson(nullptr); }

// {"R": [[...]], "t": [...]}
OrderedJson RigidToJson(const Rigid3d& a_from_b);

// A double in the shortest decimal form that reads back to the same bits, as every vstcal file
// writes numbers ("0.1", "1e-12", "640.0"). A NaN or an infinity is a bug upstream (inputs are
// checked before they reach a writer): it throws InternalError instead of printing "null".
std::string ShortestDecimal(double v);

// Two-space indented text with a final newline; doubles in shortest round-trip form. Throws
// InternalError naming the field when a number is NaN or infinite (nlohmann would write null):
// the last line of defence behind the checks of every input.
std::string DumpJson(const OrderedJson& json);
// The same on one line (and a final newline): for machine-to-machine files whose size matters
// (err-sim's shard files), where the indentation would triple it.
std::string DumpJsonCompact(const OrderedJson& json);

inline void WriteJsonFile(const std::filesystem::path& path, const OrderedJson& json) {
  WriteFileAtomically(path, DumpJson(json));
}

}  // namespace vstcal
