// Corner detection on a NumPy image, reproj-report's statistics and report, and err-sim runs, from
// Python (docs/python.md): each returns what the tool writes, as Python objects.
#include <optional>
#include <string>
#include <tuple>
#include <vector>

#include <pybind11/stl.h>

#include "bindings.h"
#include "vstcal/app/err_sim.h"
#include "vstcal/capture/detect.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/correspondences_io.h"
#include "vstcal/formats/capture/target_io.h"
#include "vstcal/formats/report/report_format.h"
#include "vstcal/formats/stereo/stereo_io.h"
#include "vstcal/report/statistics.h"

namespace vstcal::python {
namespace {

// An 8-bit grey image: a C-contiguous uint8 array of shape (H, W).
GrayImage CheckedImage(const py::handle& h) {
  if (!py::isinstance<py::array>(h)) {
    throw InputError("image: expected a NumPy uint8 array of shape (H, W), got a " +
                     std::string(py::str(h.get_type().attr("__name__"))));
  }
  const py::array a = py::reinterpret_borrow<py::array>(h);
  if (a.dtype().kind() != 'u' || a.dtype().itemsize() != 1) {
    throw InputError("image: expected dtype uint8, got " + a.dtype().attr("name").cast<std::string>() +
                     "; convert with cv2.cvtColor(..., cv2.COLOR_BGR2GRAY) or image.astype(np.uint8)");
  }
  if (a.ndim() != 2) {
    throw InputError("image: expected a grey image of shape (H, W), got " + std::to_string(a.ndim()) +
                     " dimensions; convert a colour image with cv2.cvtColor(image, cv2.COLOR_BGR2GRAY)");
  }
  if (!(a.flags() & py::array::c_style)) {
    throw InputError("image: the array is not C-contiguous (a slice or a transpose); pass np.ascontiguousarray(image)");
  }
  if (a.shape(0) < 1 || a.shape(1) < 1) throw InputError("image: empty; give an image of at least one pixel");
  GrayImage image(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  const auto* p = static_cast<const uint8_t*>(a.data());
  std::copy(p, p + image.pixels.size(), image.pixels.begin());
  return image;
}

py::dict DetectCorners(const py::handle& image_array, const py::object& target_source, const std::string& finder,
                       const std::string& refiner, int min_corners, double max_blur_px) {
  DetectorOptions options;
  if (finder == "classic") options.finder = ChessboardFinder::kClassic;
  else if (finder == "sector-based") options.finder = ChessboardFinder::kSectorBased;
  else if (finder == "classic+sector-based") options.finder = ChessboardFinder::kClassicThenSectorBased;
  else throw InputError("finder: unknown chessboard finder \"" + finder + "\"; use classic, sector-based or classic+sector-based");
  if (refiner == "symmetry") options.refiner = CornerRefiner::kSymmetry;
  else if (refiner == "cornersubpix") options.refiner = CornerRefiner::kCornerSubPix;
  else if (refiner == "none") options.refiner = CornerRefiner::kNone;
  else throw InputError("refiner: unknown corner refiner \"" + refiner + "\"; use symmetry, cornersubpix or none");
  if (min_corners < 1) throw InputError("min_corners: must be at least 1");
  if (!(max_blur_px > 0)) throw InputError("max_blur_px: must be a positive number of pixels");
  options.min_corners = min_corners;
  options.max_blur_px = max_blur_px;
  const GrayImage image = CheckedImage(image_array);
  const Target target = TargetFromJson(DocumentOf(target_source, "target"));
  Detection d;
  {
    py::gil_scoped_release unlocked;
    d = DetectTarget(image, target, options);
  }
  const py::ssize_t n = static_cast<py::ssize_t>(d.corners.size());
  py::array_t<int> ids(std::vector<py::ssize_t>{n});
  py::array_t<double> pixels = NewArray({n, 2}), points = NewArray({n, 3});
  for (py::ssize_t i = 0; i < n; ++i) {
    const DetectedCorner& c = d.corners[static_cast<size_t>(i)];
    const Eigen::Vector2d xy = CornerPosition(target, c.id);
    ids.mutable_data()[i] = c.id;
    pixels.mutable_data()[2 * i] = c.pixel.x(), pixels.mutable_data()[2 * i + 1] = c.pixel.y();
    points.mutable_data()[3 * i] = xy.x(), points.mutable_data()[3 * i + 1] = xy.y(), points.mutable_data()[3 * i + 2] = 0;
  }
  py::dict out;
  out["status"] = std::string(DetectionStatusName(d.status));
  out["reason"] = d.reason;
  out["ids"] = ids;
  out["pixels"] = pixels;
  out["points"] = points;
  out["blur_px"] = d.blur_px;
  return out;
}

py::object ErrorStatistics(const py::handle& values) {
  const Rows v = CheckedVector(values, "values");
  const std::optional<ErrorStats> s = ComputeErrorStats(std::span<const double>(v.data, static_cast<size_t>(v.n)));
  if (!s) return py::none();
  py::dict out;
  out["n"] = s->n;
  out["mean"] = s->mean;
  out["rms"] = s->rms;
  out["median"] = s->median;
  out["p95"] = s->p95;
  out["max"] = s->max;
  return out;
}

std::pair<int, int> CheckedGrid(const std::pair<int, int>& grid) {
  if (grid.first < 1 || grid.first > 64 || grid.second < 1 || grid.second > 64) {
    throw InputError("grid: (" + std::to_string(grid.first) + ", " + std::to_string(grid.second) +
                     ") cells; give (cols, rows), each from 1 to 64");
  }
  return grid;
}

py::object ReprojReportOf(const std::vector<py::object>& camera_files, const py::object& correspondences,
                          const std::pair<int, int>& grid) {
  if (camera_files.empty()) throw InputError("cameras: give at least one camera@1 file");
  std::vector<ReportCamera> cameras;
  for (const py::object& f : camera_files) cameras.push_back(ReadReportCamera(PathOf(f, "cameras")));
  const std::string name = py::isinstance<py::dict>(correspondences) ? "<correspondences>" : PathOf(correspondences, "correspondences");
  Correspondences c = CorrespondencesFromJson(DocumentOf(correspondences, "correspondences"));
  ReprojReportOptions options;
  std::tie(options.grid_cols, options.grid_rows) = CheckedGrid(grid);
  OrderedJson report;
  {
    py::gil_scoped_release unlocked;
    report = ReprojReportToJson(BuildReprojReport(cameras, std::move(c), name, options), PythonProvenance("reproj_report"));
  }
  return ToPython(report);
}

py::object StereoReportOf(const py::object& rig, const py::object& left, const py::object& right,
                          const std::string& match_views, const std::pair<int, int>& grid) {
  const std::string rig_file = PathOf(rig, "rig"), left_file = PathOf(left, "left"), right_file = PathOf(right, "right");
  StereoReportOptions options;
  options.view_key_pattern = match_views;
  std::tie(options.grid_cols, options.grid_rows) = CheckedGrid(grid);
  OrderedJson report;
  {
    py::gil_scoped_release unlocked;
    report = StereoReportToJson(BuildStereoReport(ReadStereoRig(rig_file), ReadCorrespondences(left_file),
                                                  ReadCorrespondences(right_file), rig_file, left_file, right_file, options),
                                PythonProvenance("reproj_report_stereo"));
  }
  return ToPython(report);
}

py::object ErrSim(const py::object& chain, std::optional<uint64_t> samples, std::optional<uint64_t> seed, unsigned threads,
                  bool budget, std::optional<uint64_t> budget_samples, const std::vector<std::string>& only,
                  const std::vector<std::string>& without) {
  app::RunRequest r;
  r.chain.chain = PathOf(chain, "chain");
  r.chain.samples = samples;
  r.chain.seed = seed;
  r.chain.threads = threads;
  r.chain.only = only;
  r.chain.without = without;
  r.budget = budget;
  r.budget_samples = budget_samples;
  if (samples && (*samples < 1 || *samples > app::kMaxSamples)) {
    throw InputError("samples: " + std::to_string(*samples) + " is out of range; give 1 to " + std::to_string(app::kMaxSamples));
  }
  if (threads > app::kMaxThreads) throw InputError("threads: at most " + std::to_string(app::kMaxThreads));
  app::ErrSimDocument document;
  {
    py::gil_scoped_release unlocked;
    document = app::RunErrSim(r, PythonProvenance("err_sim"));
  }
  return ToPython(document.json);
}

}  // namespace

void RegisterAnalysis(py::module_& m) {
  m.def("detect_corners", &DetectCorners, py::arg("image"), py::arg("target"), py::arg("finder") = "classic+sector-based",
        py::arg("refiner") = "symmetry", py::arg("min_corners") = 6, py::arg("max_blur_px") = 3.0,
        "The target's corners in an 8-bit grey image (H, W) uint8, as calib-capture detect finds them: a dict with "
        "status (found, not-found, rejected), reason, ids (N,), pixels (N, 2), points (N, 3: the corners in the "
        "board frame, Z = 0) and blur_px. `target`: a vstcal/target@1 file (path) or document (dict).");
  m.def("error_statistics", &ErrorStatistics, py::arg("values"),
        "reproj-report's statistics of error magnitudes (N,): n, mean, rms, median, p95 (NumPy's default "
        "interpolation), max; None for no values.");
  m.def("reproj_report", &ReprojReportOf, py::arg("cameras"), py::arg("correspondences"), py::arg("grid") = std::pair(8, 6),
        "reproj-report of camera@1 files against a correspondences@1 file or document: the vstcal/reproj-report@1 "
        "document as a dict.");
  m.def("reproj_report_stereo", &StereoReportOf, py::arg("rig"), py::arg("left"), py::arg("right"),
        py::arg("match_views") = "", py::arg("grid") = std::pair(8, 6),
        "reproj-report of a stereo@1 rig against the left and right correspondences@1 files: the triangulated 3-D "
        "error, as a dict.");
  m.def("err_sim", &ErrSim, py::arg("chain"), py::arg("samples") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = 0, py::arg("budget") = true, py::arg("budget_samples") = py::none(),
        py::arg("only") = std::vector<std::string>{}, py::arg("without") = std::vector<std::string>{},
        "err-sim run on a vstcal/vst-chain@1 file: the vstcal/err-sim-report@3 document as a dict (the same numbers "
        "as `err-sim run` for the same samples and seed). Raises vstcal.DegenerateError when a test point has no "
        "defined sample.");
}

}  // namespace vstcal::python
