// The `vstcal` Python module (docs/python.md): vstcal's errors as Python exceptions, and the
// registration of every binding file.
#include <glog/logging.h>

#include "bindings.h"
#include "vstcal/core/error.h"
#include "vstcal/core/option_name.h"
#include "vstcal/core/version.h"

namespace vstcal::python {

// vstcal.Error (exit_code 1, 2 or 3 as the tools exit), and one subclass per vstcal error type:
// InputError is also a ValueError, so code that catches ValueError for bad arguments keeps working.
std::string ForPython(std::string_view message) { return RenderOptionNames(message, OptionAsKeyword); }

void RegisterErrors(py::module_& m) {
  auto make = [&](const char* name, const py::object& bases, int exit_code, const char* doc) {
    PyObject* type = PyErr_NewExceptionWithDoc((std::string("vstcal.") + name).c_str(), doc, bases.ptr(), nullptr);
    if (type == nullptr) throw py::error_already_set();
    py::object t = py::reinterpret_steal<py::object>(type);
    t.attr("exit_code") = exit_code;
    m.attr(name) = t;
    return t;
  };
  // Held for the life of the process (a static py::object would be destroyed after the interpreter).
  static PyObject* error = make("Error", py::reinterpret_borrow<py::object>(PyExc_RuntimeError), 1,
                                 "A vstcal error: the one-line message a tool prints; exit_code as the tool exits.").release().ptr();
  const py::object base = py::reinterpret_borrow<py::object>(error);
  static PyObject* internal = make("InternalError", py::make_tuple(base), 1, "A bug in vstcal (exit code 1).").release().ptr();
  static PyObject* input = make("InputError", py::make_tuple(base, py::reinterpret_borrow<py::object>(PyExc_ValueError)), 2,
                                "Bad input: the message names the file or argument, the field and the fix (exit code 2).")
                               .release()
                               .ptr();
  static PyObject* degenerate = make("DegenerateError", py::make_tuple(base), 3,
                                     "Degenerate geometry: coplanar points for DLT, too few views, … (exit code 3).")
                                    .release()
                                    .ptr();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      PyErr_SetString(input, ForPython(e.what()).c_str());
    } catch (const DegenerateError& e) {
      PyErr_SetString(degenerate, ForPython(e.what()).c_str());
    } catch (const InternalError& e) {
      PyErr_SetString(internal, ForPython(e.what()).c_str());
    } catch (const Error& e) {  // an Error built from a status's exit code
      PyErr_SetString(e.code() == ExitCode::kBadInput ? input : e.code() == ExitCode::kDegenerate ? degenerate : error,
                      ForPython(e.what()).c_str());
    }
  });
}

}  // namespace vstcal::python

PYBIND11_MODULE(vstcal, m) {
  using namespace vstcal::python;
  m.doc() = "vstcal: camera calibration and AR error analysis (docs/python.md)";
  m.attr("__version__") = vstcal::kVersion;
  // Ceres logs through glog to stderr; as in the tools (tools/common/run_tool.cc), what a solve has
  // to say comes back in its result, as a Python exception or warning.
  FLAGS_minloglevel = google::GLOG_FATAL;
  RegisterErrors(m);
  RegisterCamera(m);
  RegisterFiles(m);
  RegisterSolvers(m);
  RegisterAnalysis(m);
}
