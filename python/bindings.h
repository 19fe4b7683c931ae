// What the binding files of the `vstcal` Python module share (docs/python.md): checked NumPy
// arrays in and out, JSON documents to and from Python objects, and the registration function of
// each file. Every check failure is a vstcal::InputError naming the argument; module.cc turns
// vstcal's errors into the Python exceptions vstcal.InputError, vstcal.DegenerateError, … with the
// same one-line messages the tools print.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "vstcal/json/json_reader.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/json/provenance.h"
#include "vstcal/scene/correspondences.h"

namespace vstcal::python {

namespace py = pybind11;

// A float64 array of `cols` columns: shape (N, cols), or (cols,) as one row when `one_row_ok`.
// Refused with an InputError naming `name`: another dtype, another shape, a non-C-contiguous
// array (a slice or a transpose: pass np.ascontiguousarray(a)), and NaN or infinite values.
struct Rows {
  const double* data = nullptr;
  py::ssize_t n = 0;
  bool one_row = false;  // given as shape (cols,): results keep that form
};
Rows CheckedRows(const py::handle& array, const char* name, py::ssize_t cols, bool one_row_ok = true);
// A 1-D float64 array of `size` values (any size when size < 0), checked as above.
Rows CheckedVector(const py::handle& array, const char* name, py::ssize_t size = -1);
// The (N, 3) points and (N, 2) pixels, and optionally (N,) positive weights, checked as above and
// copied into vstcal's layout.
std::vector<Observation> ObservationsOf(const py::handle& points, const py::handle& pixels, const py::handle& weights);

// A new C-contiguous float64 array of the given shape, uninitialised.
py::array_t<double> NewArray(std::vector<py::ssize_t> shape);
// Copies of Eigen matrices (row-major in NumPy's sense).
template <typename Matrix>
py::array_t<double> ToArray(const Matrix& m) {
  py::array_t<double> a = NewArray({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  double* out = a.mutable_data();
  for (Eigen::Index r = 0; r < m.rows(); ++r)
    for (Eigen::Index c = 0; c < m.cols(); ++c) *out++ = m(r, c);
  return a;
}
template <typename Vector>
py::array_t<double> ToVector(const Vector& v) {
  py::array_t<double> a = NewArray({static_cast<py::ssize_t>(v.size())});
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(v.size()); ++i) a.mutable_data()[i] = v[i];
  return a;
}

// A JSON document as Python objects (dict, list, str, int, float, bool, None), in file order.
py::object ToPython(const OrderedJson& json);
py::object ToPython(const nlohmann::json& json);
// A document given as a path (str or os.PathLike: read as the tools read it, errors naming the
// file) or as a dict (a document in memory, named "<name>" in messages).
JsonDocument DocumentOf(const py::handle& source, const char* name);
// The path of a str or os.PathLike argument; InputError naming `name` otherwise.
std::string PathOf(const py::handle& source, const char* name);
// Provenance of a file a binding writes: the function called from Python.
Provenance PythonProvenance(const std::string& function);

// A library message as a Python caller reads it: the options it names (core/option_name.h) as the
// keyword arguments, "tilt_deg". Errors and warnings go through it.
std::string ForPython(std::string_view message);

void RegisterErrors(py::module_& m);
void RegisterCamera(py::module_& m);    // camera.cc: the lens models, project, unproject, Jacobians
void RegisterFiles(py::module_& m);     // files.cc: reading and writing the vstcal formats
void RegisterSolvers(py::module_& m);   // solvers.cc: DLT, Tsai, planar views, stereo
void RegisterAnalysis(py::module_& m);  // analysis.cc: corner detection, reproj-report, err-sim

}  // namespace vstcal::python
