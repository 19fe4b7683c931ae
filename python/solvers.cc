// The solvers from Python (docs/python.md#solvers): DLT on NumPy arrays; a calibration of a
// correspondences@1 file or document as calib-dlt and calib-tsai make it (DLT, Tsai, planar views by
// Zhang's method, refined with covariance); a stereo rig as calib-stereo solve makes it. Failures
// raise the exception of the exit code the tool returns, with its one-line message.
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <pybind11/stl.h>
#include <structmember.h>

#include "bindings.h"
#include "vstcal/app/calib_stereo.h"
#include "vstcal/estimators/dlt.h"
#include "vstcal/calib/pipeline.h"
#include "vstcal/core/enum_names.h"
#include "vstcal/core/error.h"
#include "vstcal/estimators/decompose.h"
#include "vstcal/formats/calib/calibration_io.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal::python {
namespace {

// 3-D ↔ 2-D correspondences held in vstcal's own layout, so that a solver called many times on
// one set does not convert the arrays each time (what tests/bench/bench_dlt.cc times is the solve).
struct Observations {
  std::vector<Observation> list;
};

Observations MakeObservations(const py::handle& points, const py::handle& pixels, const py::object& weights) {
  return {ObservationsOf(points, pixels, weights)};
}

// SolveDlt and the decomposition of its P (what bench_dlt times), kept in C++ until read.
struct DltSolution {
  DltResult result;
  ProjectionDecomposition decomposition;
};

// The Python DltSolution: a CPython type holding the DltSolution inline (one allocation, freed with
// the object), not a pybind11 class, whose instances cost a type-map lookup, a second allocation
// and an entry in pybind11's instance map — about 0.1 µs of the 0.14–0.22 µs the binding still
// added to a 60-point DLT behind the fast entry below (docs/performance.md#python). Read-only
// attributes made when read, as the pybind11 class had; not subclassable from Python.
struct SolutionObject {
  PyObject_HEAD
  DltSolution value;
  PyObject* weak_references;
};
PyTypeObject* solution_type = nullptr;

// A new, default DltSolution object; nullptr with the Python error set.
SolutionObject* NewSolution() {
  SolutionObject* self = PyObject_New(SolutionObject, solution_type);
  if (self == nullptr) return nullptr;
  new (&self->value) DltSolution();
  self->weak_references = nullptr;
  return self;
}

void DeleteSolution(PyObject* object) {
  auto* self = reinterpret_cast<SolutionObject*>(object);
  if (self->weak_references != nullptr) PyObject_ClearWeakRefs(object);
  self->value.~DltSolution();
  PyTypeObject* type = Py_TYPE(object);
  type->tp_free(object);
  Py_DECREF(type);
}

PyObject* RefuseConstruction(PyTypeObject*, PyObject*, PyObject*) {
  PyErr_SetString(PyExc_TypeError, "vstcal.DltSolution: No constructor defined!");  // as a pybind11 class without py::init
  return nullptr;
}

// A C++ exception in flight as pybind11's dispatcher turns it into a Python one: the module's
// translators, then the global ones (module.cc's). Call inside a catch block; returns nullptr.
PyObject* RaiseTranslated() {
  try {
    throw;
  } catch (py::error_already_set& e) {
    e.restore();
    return nullptr;
#ifdef __GLIBCXX__
  } catch (abi::__forced_unwind&) {  // a cancelled thread unwinds through, as in pybind11's dispatcher
    throw;
#endif
  } catch (...) {
    if (py::detail::apply_exception_translators(py::detail::get_local_internals().registered_exception_translators)) return nullptr;
    if (py::detail::apply_exception_translators(py::detail::get_internals().registered_exception_translators)) return nullptr;
    PyErr_SetString(PyExc_SystemError, "Exception escaped from default exception translator!");
    return nullptr;
  }
}

template <auto kRead>
PyObject* Attribute(PyObject* object, void*) {
  try {
    auto value = kRead(reinterpret_cast<SolutionObject*>(object)->value);
    return py::detail::make_caster<decltype(value)>::cast(std::move(value), py::return_value_policy::move, py::handle()).ptr();
  } catch (...) {
    return RaiseTranslated();
  }
}

PyGetSetDef solution_attributes[] = {
    {"P", Attribute<[](const DltSolution& s) { return ToArray(s.result.P); }>, nullptr, nullptr, nullptr},
    {"K", Attribute<[](const DltSolution& s) { return ToArray(s.decomposition.K); }>, nullptr, nullptr, nullptr},
    {"R", Attribute<[](const DltSolution& s) { return ToArray(s.decomposition.camera_from_world.R); }>, nullptr,
     "camera_from_world's rotation", nullptr},
    {"t", Attribute<[](const DltSolution& s) { return ToVector(s.decomposition.camera_from_world.t); }>, nullptr,
     "camera_from_world's translation", nullptr},
    {"sigma_11", Attribute<[](const DltSolution& s) { return s.result.sigma_11; }>, nullptr, nullptr, nullptr},
    {"sigma_12", Attribute<[](const DltSolution& s) { return s.result.sigma_12; }>, nullptr, nullptr, nullptr},
    {"conditioning", Attribute<[](const DltSolution& s) { return s.result.conditioning; }>, nullptr, nullptr, nullptr},
    {"extents", Attribute<[](const DltSolution& s) { return s.result.extents; }>, nullptr, nullptr, nullptr},
    {"warnings", Attribute<[](const DltSolution& s) { return s.result.warnings; }>, nullptr, nullptr, nullptr},
    {"n_points", Attribute<[](const DltSolution& s) { return s.result.n_points; }>, nullptr, nullptr, nullptr},
    {nullptr, nullptr, nullptr, nullptr, nullptr}};

PyMemberDef solution_members[] = {
    {"__weaklistoffset__", T_PYSSIZET, offsetof(SolutionObject, weak_references), READONLY, nullptr},
    {nullptr, 0, 0, 0, nullptr}};

void RegisterSolutionType(py::module_& m) {
  static PyType_Slot slots[] = {
      {Py_tp_doc, const_cast<char*>("A DLT solve: P (normalized), its decomposition K, R, t, and diagnostics.")},
      {Py_tp_dealloc, reinterpret_cast<void*>(&DeleteSolution)},
      {Py_tp_new, reinterpret_cast<void*>(&RefuseConstruction)},
      {Py_tp_getset, solution_attributes},
      {Py_tp_members, solution_members},
      {0, nullptr}};
  static PyType_Spec spec = {"vstcal.DltSolution", sizeof(SolutionObject), 0, Py_TPFLAGS_DEFAULT, slots};
  PyObject* type = PyType_FromSpec(&spec);
  if (type == nullptr) throw py::error_already_set();
  solution_type = reinterpret_cast<PyTypeObject*>(type);  // held for the life of the process
  m.attr("DltSolution") = py::reinterpret_borrow<py::object>(type);
}

// The object pybind11 returns for solve_dlt's other calls, under the name signatures show.
struct SolutionHandle {
  py::object object;
};

}  // namespace
}  // namespace vstcal::python

namespace pybind11::detail {
template <>
struct type_caster<vstcal::python::SolutionHandle> {
  static constexpr auto name = const_name("vstcal.DltSolution");
  static handle cast(vstcal::python::SolutionHandle solution, return_value_policy, handle) { return solution.object.release(); }
};
}  // namespace pybind11::detail

namespace vstcal::python {
namespace {

// A string_view, not a std::string: "normal-equations" is longer than the small-string buffer, and
// its copy on every call was a tenth of the binding's cost on a 60-point DLT (docs/performance.md#python).
DltOptions::Solver SolverNamed(std::string_view name) {
  if (const auto solver = FromName(DltOptions::kSolverNames, name)) return *solver;
  throw InputError("solver: unknown DLT solver \"" + std::string(name) + "\"; use " + JoinedNames(DltOptions::kSolverNames));
}

// Raises the tool's exception when the DLT failed; otherwise P's decomposition.
void SolveInto(std::span<const Observation> observations, const DltOptions& options, DltSolution* s) {
  s->result = SolveDlt(observations, options);
  if (s->result.status != DltStatus::kOk) throw Error(DltStatusExitCode(s->result.status), s->result.message);
  const std::optional<ProjectionDecomposition> d = DecomposeProjection(s->result.P);
  if (!d) throw DegenerateError("P: its left 3×3 block is singular or mirrored; check the points' coordinates");
  s->decomposition = *d;
}

// A new DltSolution object of the observations' solve; raises as SolveInto.
SolutionHandle Solved(std::span<const Observation> observations, const DltOptions& options) {
  SolutionHandle solution{py::reinterpret_steal<py::object>(reinterpret_cast<PyObject*>(NewSolution()))};
  if (!solution.object) throw py::error_already_set();
  SolveInto(observations, options, &reinterpret_cast<SolutionObject*>(solution.object.ptr())->value);
  return solution;
}

// solve_dlt(points, pixels=None, solver="normal-equations", exact_diagnostics=False).
SolutionHandle SolveDltOf(const py::object& points, const py::object& pixels, std::string_view solver, bool exact_diagnostics) {
  DltOptions options;
  options.solver = SolverNamed(solver);
  options.exact_diagnostics = exact_diagnostics;
  if (py::isinstance<Observations>(points)) {
    if (!pixels.is_none()) throw InputError("pixels: already in the Observations; leave it out");
    return Solved(points.cast<const Observations&>().list, options);
  }
  if (pixels.is_none()) throw InputError("pixels: missing; give the (N, 2) pixels of the (N, 3) points");
  return Solved(MakeObservations(points, pixels, py::none()).list, options);
}

// vstcal.solve_dlt is a plain CPython function (METH_FASTCALL) in front of the pybind11 one
// (docs/performance.md#python). pybind11's dispatch (an argument tuple, the defaults filled in,
// four casters, a type-map lookup per isinstance and cast and one for the result) was most of the
// 0.3 µs the binding added to a 60-point DLT of 4.7 µs. The fast entry takes the calls whose
// arguments need no conversion — an Observations (exactly), pixels None, solver a str naming a
// solver, exact_diagnostics True or False, by position or keyword — and hands every other call to
// the pybind11 function unchanged, so that arrays, type errors and their messages stay pybind11's.
// Its result is the same DltSolution object; errors go through the same translators as pybind11's.
struct FastSolveDlt {
  PyObject* general = nullptr;  // the pybind11 solve_dlt, for every other call
  const py::detail::type_info* observations = nullptr;
  PyObject* keywords[4] = {};  // interned: points, pixels, solver, exact_diagnostics
  std::string doc;             // pybind11's docstring of `general`: the signature line and the text
  PyMethodDef method{};
};
FastSolveDlt fast_solve_dlt;

PyObject* SolveDltEntry(PyObject* /*self*/, PyObject* const* args, Py_ssize_t nargsf, PyObject* kwnames) {
  const FastSolveDlt& f = fast_solve_dlt;
  const Py_ssize_t nargs = PyVectorcall_NARGS(nargsf);
  const auto general = [&] { return PyObject_Vectorcall(f.general, args, nargsf, kwnames); };
  PyObject* given[4] = {};
  if (nargs > 4) return general();
  for (Py_ssize_t i = 0; i < nargs; ++i) given[i] = args[i];
  if (kwnames != nullptr) {
    const Py_ssize_t nkw = PyTuple_GET_SIZE(kwnames);
    for (Py_ssize_t k = 0; k < nkw; ++k) {
      PyObject* name = PyTuple_GET_ITEM(kwnames, k);
      int slot = 0;
      while (slot < 4 && f.keywords[slot] != name) ++slot;  // call sites' keywords are interned
      if (slot == 4 || given[slot] != nullptr) return general();
      given[slot] = args[nargs + k];
    }
  }
  if (given[0] == nullptr || Py_TYPE(given[0]) != f.observations->type) return general();
  if (given[1] != nullptr && given[1] != Py_None) return general();
  DltOptions options;
  if (given[2] != nullptr) {
    if (!PyUnicode_CheckExact(given[2])) return general();
    Py_ssize_t size = 0;
    const char* name = PyUnicode_AsUTF8AndSize(given[2], &size);
    if (name == nullptr) {
      PyErr_Clear();
      return general();
    }
    const auto solver = FromName(DltOptions::kSolverNames, std::string_view(name, static_cast<size_t>(size)));
    if (!solver) return general();
    options.solver = *solver;
  }
  if (given[3] != nullptr) {
    if (given[3] != Py_True && given[3] != Py_False) return general();
    options.exact_diagnostics = given[3] == Py_True;
  }
  const auto* observations =
      static_cast<const Observations*>(reinterpret_cast<py::detail::instance*>(given[0])->get_value_and_holder().value_ptr());
  if (observations == nullptr) return general();  // not initialised: pybind11 says so
  try {
    return Solved(observations->list, options).object.release().ptr();
  } catch (...) {
    return RaiseTranslated();
  }
}

void DefineSolveDlt(py::module_& m, const char* doc) {
  FastSolveDlt& f = fast_solve_dlt;
  py::cpp_function general(&SolveDltOf, py::name("solve_dlt"), py::scope(m), py::arg("points"), py::arg("pixels") = py::none(),
                           py::arg("solver") = "normal-equations", py::arg("exact_diagnostics") = false, doc);
  f.doc = py::str(general.attr("__doc__"));
  f.general = general.release().ptr();  // held for the life of the process, as module.cc's exception types
  f.observations = py::detail::get_type_info(typeid(Observations));
  const char* names[4] = {"points", "pixels", "solver", "exact_diagnostics"};
  for (int i = 0; i < 4; ++i) {
    f.keywords[i] = PyUnicode_InternFromString(names[i]);
    if (f.keywords[i] == nullptr) throw py::error_already_set();
  }
  f.method = {"solve_dlt", reinterpret_cast<PyCFunction>(reinterpret_cast<void (*)()>(&SolveDltEntry)), METH_FASTCALL | METH_KEYWORDS,
              f.doc.c_str()};
  PyObject* entry = PyCFunction_NewEx(&f.method, nullptr, m.attr("__name__").ptr());
  if (entry == nullptr) throw py::error_already_set();
  m.attr("solve_dlt") = py::reinterpret_steal<py::object>(entry);
}

// The refinement options as calib-dlt and calib-tsai read their flags (tools/common/calibration_flags.cc).
// distortion None: k1,k2,p1,p2, or a lens model of another family's own terms (calib-tsai --lens-model
// without --distortion).
RefineOptions RefineOptionsOf(const std::optional<std::string>& distortion, bool skew, const std::string& loss,
                         const std::optional<double>& loss_scale, int max_iterations, const std::string& lens_model = "") {
  RefineOptions o;
  o.lens_model = lens_model;
  const auto model = lens_model.empty() ? std::nullopt : LensModelFromName(lens_model);
  if (!lens_model.empty() && !model) {
    throw InputError("lens_model: unknown lens model \"" + lens_model + "\"; use one of " + KnownLensModelNames());
  }
  if (model && !distortion) {
    o.free_distortion.clear();
    const auto names = LensModelParamNames(*model);
    for (auto it = names.begin() + kNumIntrinsicParams; it != names.end(); ++it) o.free_distortion.emplace_back(*it);
  } else {
    o.free_distortion = DistortionTermsFromList(distortion.value_or("k1,k2,p1,p2"));
  }
  o.free_skew = skew;
  if (loss != "none" && loss != "huber" && loss != "cauchy") {
    throw InputError("loss: unknown robust loss \"" + loss + "\"; use none, huber or cauchy");
  }
  o.loss = loss == "huber" ? RefineOptions::Loss::kHuber : loss == "cauchy" ? RefineOptions::Loss::kCauchy : RefineOptions::Loss::kNone;
  if (loss_scale) {
    if (o.loss == RefineOptions::Loss::kNone) {
      throw InputError("loss_scale: has no effect with loss \"none\"; give loss=\"huber\" or \"cauchy\", or drop it");
    }
    if (!(*loss_scale > 0) || !std::isfinite(*loss_scale)) throw InputError("loss_scale: must be a positive number of pixels");
    o.loss_scale_px = *loss_scale;
  }
  if (max_iterations < 1 || max_iterations > 100000) throw InputError("max_iterations: must be in [1, 100000]");
  o.max_iterations = max_iterations;
  return o;
}

// The name a correspondences argument goes by in messages: its path, as the tools name their input.
std::string SourceName(const py::handle& source) {
  return py::isinstance<py::dict>(source) ? "<correspondences>" : PathOf(source, "correspondences");
}

py::object Calibrate(const py::object& source, const std::string& method, std::optional<bool> refine,
                     const std::optional<std::string>& distortion, bool skew, const std::string& loss, std::optional<double> loss_scale,
                     int max_iterations, const std::string& solver, const std::string& variant,
                     const std::optional<std::pair<double, double>>& principal_point, std::optional<double> sx,
                     const std::string& free_principal_point,
                     const std::map<std::string, std::pair<double, double>>& priors,
                     const std::vector<std::string>& hold, const std::string& lens_model) {
  if (method != "dlt" && method != "tsai") throw InputError("method: unknown method \"" + method + "\"; use dlt or tsai");
  const std::string input = SourceName(source);
  CalibrationOptions options;
  options.start = method == "dlt" ? CalibrationOptions::Start::kDlt : CalibrationOptions::Start::kTsai;
  options.refine = refine.value_or(method == "tsai");  // the tools' defaults: calib-dlt --refine, calib-tsai --no-refine
  options.refinement = RefineOptionsOf(distortion, skew, loss, loss_scale, max_iterations, lens_model);
  for (const auto& [name, prior] : priors) {
    options.refinement.priors.push_back(StatedPrior(name, prior.first, prior.second));
  }
  HoldIntrinsics(hold, &options.refinement);
  options.dlt.exact_diagnostics = true;  // as calib-dlt: the camera file reports sigma_11
  options.dlt.solver = SolverNamed(solver);
  if (variant != "auto" && variant != "coplanar" && variant != "non-coplanar") {
    throw InputError("variant: unknown Tsai variant \"" + variant + "\"; use auto, coplanar or non-coplanar");
  }
  options.tsai.variant = variant == "coplanar"       ? TsaiOptions::Variant::kCoplanar
                         : variant == "non-coplanar" ? TsaiOptions::Variant::kNonCoplanar
                                                     : TsaiOptions::Variant::kAuto;
  if (principal_point) options.tsai.principal_point = Eigen::Vector2d(principal_point->first, principal_point->second);
  if (sx) options.tsai.sx = *sx;
  const auto plane_principal_point = FromName(CalibrationOptions::kPlanePrincipalPointNames, free_principal_point);
  if (!plane_principal_point) {
    throw InputError("free_principal_point: \"" + free_principal_point + "\"; use no, yes or prior");
  }
  options.plane_principal_point = *plane_principal_point;
  Correspondences corners = CorrespondencesFromJson(DocumentOf(source, "correspondences"));
  if (method == "dlt" && corners.rig != Rig::kVolume) {
    throw InputError(input + ": rig: DLT needs one world frame (rig \"volume\"), got \"planar-views\"; "
                     "calibrate planar views with method \"tsai\"");
  }
  if (method == "tsai" && corners.rig == Rig::kPlanarViews && (variant != "auto" || principal_point || sx || free_principal_point != "prior")) {
    throw InputError("variant, principal_point, sx, free_principal_point: apply to rig \"volume\" only (planar views start "
                     "from Zhang's method); remove them");
  }
  OrderedJson camera;
  std::vector<std::string> warnings;
  {
    py::gil_scoped_release unlocked;
    const CalibrationResult result = vstcal::Calibrate(std::move(corners), options);
    if (result.exit_code != ExitCode::kOk) throw Error(result.exit_code, input + ": " + result.message);
    OrderedJson blocks = CalibrationBlocksToJson(result, options);
    if (result.camera.covariance) blocks["projection_uncertainty"] = UncertaintyToJson(result.camera, UncertaintyRequest{});
    camera = CameraToJson(result.camera, PythonProvenance("calibrate"), blocks);
    warnings = result.warnings;
  }
  // The tool prints these on stderr; Python's way is a warning each.
  for (const std::string& w : warnings) {
    if (PyErr_WarnEx(PyExc_UserWarning, ForPython(input + ": " + w).c_str(), 1) < 0) throw py::error_already_set();
  }
  return ToPython(camera);
}

py::object SolveStereoRig(const py::object& left, const py::object& right, const py::object& left_camera,
                          const py::object& right_camera, bool hold_left, bool hold_right, const std::string& match_views,
                          size_t min_common_views, const std::optional<std::string>& distortion, bool skew, int max_iterations,
                          const std::optional<double>& rectify_alpha) {
  app::SolveRequest r;
  r.left = PathOf(left, "left");
  r.right = PathOf(right, "right");
  r.output = "<stereo>";
  if (!left_camera.is_none()) r.left_camera = PathOf(left_camera, "left_camera");
  if (!right_camera.is_none()) r.right_camera = PathOf(right_camera, "right_camera");
  r.options.hold_left = hold_left;
  r.options.hold_right = hold_right;
  r.options.view_key_pattern = match_views;
  if (min_common_views < 1) throw InputError("min_common_views: must be at least 1");
  r.options.min_common_views = min_common_views;
  r.options.calibration.refinement = RefineOptionsOf(distortion, skew, "none", std::nullopt, max_iterations);
  if (rectify_alpha) r.rectify = RectifyOptions{*rectify_alpha, true};
  app::Outcome out;
  {
    py::gil_scoped_release unlocked;
    out = app::Solve(r, PythonProvenance("solve_stereo"));
  }
  return ToPython(OrderedJson::parse(out.files.front().second));
}

}  // namespace

void RegisterSolvers(py::module_& m) {
  py::class_<Observations>(m, "Observations",
                           "3-D points (N, 3) and their pixels (N, 2), optionally weighted, held in vstcal's layout.")
      .def(py::init(&MakeObservations), py::arg("points"), py::arg("pixels"), py::arg("weights") = py::none())
      .def("__len__", [](const Observations& o) { return o.list.size(); });

  RegisterSolutionType(m);

  DefineSolveDlt(m, "P from ≥ 6 non-coplanar world points (N, 3) and their pixels (N, 2), or from an Observations "
                    "(docs/math/dlt.md). Raises vstcal.DegenerateError (coplanar, collinear, ill-conditioned) or InputError.");

  m.def("calibrate", &Calibrate, py::arg("correspondences"), py::arg("method") = "tsai", py::arg("refine") = py::none(),
        py::arg("distortion") = py::none(), py::arg("skew") = false, py::arg("loss") = "none",
        py::arg("loss_scale") = py::none(), py::arg("max_iterations") = 100, py::arg("solver") = "normal-equations",
        py::arg("variant") = "auto", py::arg("principal_point") = py::none(), py::arg("sx") = py::none(),
        py::arg("free_principal_point") = "prior", py::arg("priors") = std::map<std::string, std::pair<double, double>>{},
        py::arg("hold") = std::vector<std::string>{}, py::arg("lens_model") = "",
        "A camera from a vstcal/correspondences@1 file (path) or document (dict), as calib-dlt (method \"dlt\", refine "
        "False by default) or calib-tsai (method \"tsai\": Tsai for a volume, Zhang for planar views; refined by "
        "default) write it: the vstcal/camera@1 document as a dict, with the covariance when refined; the tool's warnings "
        "as Python UserWarnings. priors={\"cx\": (value, sigma)}: Gaussian priors on lens parameters (calib-tsai --prior); "
        "hold=[\"cx\", \"cy\"]: parameters held at the start's values (--hold). lens_model=\"kannala-brandt\": solve a "
        "fisheye (--lens-model), its terms k1..k4 unless distortion names fewer; distortion None: k1,k2,p1,p2 or the lens "
        "model's own terms.");

  m.def("solve_stereo", &SolveStereoRig, py::arg("left"), py::arg("right"), py::arg("left_camera") = py::none(),
        py::arg("right_camera") = py::none(), py::arg("hold_left") = false, py::arg("hold_right") = false,
        py::arg("match_views") = "", py::arg("min_common_views") = 3, py::arg("distortion") = py::none(),
        py::arg("skew") = false, py::arg("max_iterations") = 100, py::arg("rectify_alpha") = py::none(),
        "calib-stereo solve: a rig from the left and right correspondences@1 files; the vstcal/stereo@1 document "
        "(right_from_left with its covariance) as a dict.");
}

}  // namespace vstcal::python
