// Checked arrays and JSON ↔ Python conversion for the binding files (bindings.h). Its loops run
// once per value of the caller's arrays, so this file is compiled as the library is, not as glue
// (python/CMakeLists.txt).
#include <cmath>
#include <optional>

#include "bindings.h"
#include "vstcal/core/error.h"

namespace vstcal::python {
namespace {

std::string ShapeText(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s += (i ? ", " : "") + std::to_string(a.shape(i));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

// The array behind `h`, float64 and C-contiguous, or an InputError naming the argument and the fix.
py::array CheckedArray(const py::handle& h, const char* name, const std::string& wanted) {
  if (!py::isinstance<py::array>(h)) {
    throw InputError(std::string(name) + ": expected a NumPy array of shape " + wanted + ", got a " +
                     std::string(py::str(h.get_type().attr("__name__"))) + "; pass np.asarray(" + name +
                     ", dtype=np.float64)");
  }
  py::array a = py::reinterpret_borrow<py::array>(h);
  const py::dtype dtype = a.dtype();
  if (dtype.kind() != 'f' || dtype.itemsize() != 8 || dtype.byteorder() == '>') {
    throw InputError(std::string(name) + ": expected dtype float64, got " + dtype.attr("name").cast<std::string>() + "; pass " +
                     name + ".astype(np.float64)");
  }
  if (!(a.flags() & py::array::c_style)) {
    throw InputError(std::string(name) + ": the array is not C-contiguous (a slice or a transpose); pass "
                     "np.ascontiguousarray(" + name + ")");
  }
  return a;
}

// x·0 is 0 for a finite x and NaN for ±inf or NaN, so one sum tells whether every value is finite;
// unlike a test per value it vectorizes (a third of a 6,000-point DLT call went to the test per
// value, docs/performance.md#python). The slow loop then runs only to name the first bad value.
bool AllFinite(const double* data, py::ssize_t count) {
  double lanes[4] = {0, 0, 0, 0};
  py::ssize_t i = 0;
  for (; i + 4 <= count; i += 4) {
    for (int k = 0; k < 4; ++k) lanes[k] += data[i + k] * 0.0;
  }
  for (; i < count; ++i) lanes[0] += data[i] * 0.0;
  return lanes[0] + lanes[1] + lanes[2] + lanes[3] == 0.0;
}

void CheckFinite(const double* data, py::ssize_t count, py::ssize_t cols, const char* name) {
  if (AllFinite(data, count)) return;
  for (py::ssize_t i = 0; i < count; ++i) {
    if (std::isfinite(data[i])) continue;
    const std::string where = cols > 0 ? "[" + std::to_string(i / cols) + ", " + std::to_string(i % cols) + "]"
                                       : "[" + std::to_string(i) + "]";
    throw InputError(std::string(name) + where + ": " + (std::isnan(data[i]) ? "NaN" : "an infinite value") +
                     "; every value must be finite (drop or fix that row)");
  }
}

}  // namespace

Rows CheckedRows(const py::handle& h, const char* name, py::ssize_t cols, bool one_row_ok) {
  const std::string wanted = "(N, " + std::to_string(cols) + ")" + (one_row_ok ? " or (" + std::to_string(cols) + ",)" : "");
  const py::array a = CheckedArray(h, name, wanted);
  Rows rows;
  if (one_row_ok && a.ndim() == 1 && a.shape(0) == cols) {
    rows.n = 1;
    rows.one_row = true;
  } else if (a.ndim() == 2 && a.shape(1) == cols) {
    rows.n = a.shape(0);
  } else {
    throw InputError(std::string(name) + ": expected shape " + wanted + ", got " + ShapeText(a) +
                     "; one row per point, " + std::to_string(cols) + " coordinates each");
  }
  rows.data = static_cast<const double*>(a.data());
  CheckFinite(rows.data, rows.n * cols, cols, name);
  return rows;
}

Rows CheckedVector(const py::handle& h, const char* name, py::ssize_t size) {
  const std::string wanted = size < 0 ? "(N,)" : "(" + std::to_string(size) + ",)";
  const py::array a = CheckedArray(h, name, wanted);
  if (a.ndim() != 1 || (size >= 0 && a.shape(0) != size)) {
    throw InputError(std::string(name) + ": expected shape " + wanted + ", got " + ShapeText(a) +
                     (size >= 0 ? "; give " + std::to_string(size) + " values" : "; give a 1-D array"));
  }
  Rows rows{static_cast<const double*>(a.data()), a.shape(0), false};
  CheckFinite(rows.data, rows.n, 0, name);
  return rows;
}

std::vector<Observation> ObservationsOf(const py::handle& points, const py::handle& pixels, const py::handle& weights) {
  const Rows p = CheckedRows(points, "points", 3, false);
  const Rows q = CheckedRows(pixels, "pixels", 2, false);
  if (q.n != p.n) {
    throw InputError("pixels: " + std::to_string(q.n) + " rows for " + std::to_string(p.n) +
                     " points; give one pixel per point, in the same order");
  }
  std::optional<Rows> w;
  if (!weights.is_none()) {
    w = CheckedVector(weights, "weights", p.n);
    for (py::ssize_t i = 0; i < p.n; ++i) {
      if (!(w->data[i] > 0)) throw InputError("weights[" + std::to_string(i) + "]: must be positive; drop the point instead");
    }
  }
  const double* weight = w ? w->data : nullptr;
  std::vector<Observation> o(static_cast<size_t>(p.n));
  Observation* out = o.data();
  for (py::ssize_t i = 0; i < p.n; ++i) {
    out[i].point = Eigen::Vector3d::Map(p.data + 3 * i);
    out[i].pixel = Eigen::Vector2d::Map(q.data + 2 * i);
    out[i].weight = weight ? weight[i] : 1.0;
  }
  return o;
}

py::array_t<double> NewArray(std::vector<py::ssize_t> shape) { return py::array_t<double>(shape); }

namespace {

template <typename Json>
py::object Convert(const Json& j) {
  switch (j.type()) {
    case nlohmann::json::value_t::object: {
      py::dict d;
      for (auto it = j.begin(); it != j.end(); ++it) d[py::str(it.key())] = Convert(it.value());
      return d;
    }
    case nlohmann::json::value_t::array: {
      py::list l(j.size());
      size_t i = 0;
      for (const auto& item : j) l[i++] = Convert(item);
      return l;
    }
    case nlohmann::json::value_t::string:
      return py::str(j.template get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(j.template get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(j.template get<int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(j.template get<uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(j.template get<double>());
    default:
      return py::none();
  }
}

}  // namespace

py::object ToPython(const OrderedJson& json) { return Convert(json); }
py::object ToPython(const nlohmann::json& json) { return Convert(json); }

std::string PathOf(const py::handle& source, const char* name) {
  if (py::isinstance<py::str>(source)) return source.cast<std::string>();
  const py::module_ os = py::module_::import("os");
  if (py::isinstance(source, os.attr("PathLike"))) return py::str(os.attr("fspath")(source)).cast<std::string>();
  throw InputError(std::string(name) + ": expected a file path (str or os.PathLike), got a " +
                   std::string(py::str(source.get_type().attr("__name__"))));
}

JsonDocument DocumentOf(const py::handle& source, const char* name) {
  if (py::isinstance<py::dict>(source)) {
    std::string text;
    try {
      text = py::module_::import("json").attr("dumps")(source, py::arg("allow_nan") = false).cast<std::string>();
    } catch (py::error_already_set& e) {
      throw InputError(std::string(name) + ": not a JSON document: " + std::string(py::str(e.value())) +
                       "; give str, int, float (finite), bool, None, list and dict values only");
    }
    return JsonDocument::Parse(text, std::string("<") + name + ">");
  }
  if (py::isinstance<py::str>(source) || py::isinstance(source, py::module_::import("os").attr("PathLike"))) {
    return JsonDocument::Load(PathOf(source, name));
  }
  throw InputError(std::string(name) + ": expected a file path or a dict, got a " +
                   std::string(py::str(source.get_type().attr("__name__"))));
}

Provenance PythonProvenance(const std::string& function) {
  Provenance p;
  p.tool = "python:vstcal." + function;
  return p;
}

}  // namespace vstcal::python
