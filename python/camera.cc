// vstcal.Camera: a lens model by name with its parameters [fx, fy, cx, cy, s, <distortion>], and
// the one projection (camera/lens_models.h) over NumPy arrays of points: project, unproject, and
// project with its Jacobians. A point behind the camera (z ≤ 0) projects to a NaN row; a pixel
// outside the lens's valid domain unprojects to a NaN row (docs/python.md#camera).
#include <algorithm>
#include <cmath>
#include <limits>

#include <pybind11/stl.h>

#include "bindings.h"
#include "vstcal/camera/camera.h"
#include "vstcal/core/error.h"

namespace vstcal::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

AnyLensModel ModelNamed(const std::string& name) {
  const std::optional<AnyLensModel> model = LensModelFromName(name);
  if (!model) throw InputError("model: unknown lens model \"" + name + "\"; use one of " + KnownLensModelNames());
  return *model;
}

ImageSize SizeOf(const std::pair<int, int>& size) {
  if (size.first <= 0 || size.second <= 0) {
    throw InputError("image_size: (" + std::to_string(size.first) + ", " + std::to_string(size.second) +
                     ") is not a size; give (width, height) in pixels, both positive");
  }
  return {size.first, size.second};
}

Camera MakeCamera(const std::string& model_name, const py::handle& params, const std::pair<int, int>& image_size) {
  Camera c;
  c.model = ModelNamed(model_name);
  c.image_size = SizeOf(image_size);
  const Rows p = CheckedVector(params, "params", LensModelNumParams(c.model));
  c.params.assign(p.data, p.data + p.n);
  if (!(c.params[0] > 0) || !(c.params[1] > 0)) {
    throw InputError("params: fx and fy (params[0], params[1]) must be positive; give focal lengths in pixels");
  }
  return c;
}

// An (N, cols) result, or (cols,) when the input was one row.
py::array_t<double> ResultRows(const Rows& in, py::ssize_t cols) {
  return in.one_row ? NewArray({cols}) : NewArray({in.n, cols});
}

py::array_t<double> Project(const Camera& c, const py::handle& points) {
  const Rows p = CheckedRows(points, "points", 3);
  py::array_t<double> out = ResultRows(p, 2);
  double* px = out.mutable_data();
  for (py::ssize_t i = 0; i < p.n; ++i, px += 2) {
    if (!ProjectWith(c.model, c.params.data(), p.data + 3 * i, px)) px[0] = px[1] = kNaN;
  }
  return out;
}

py::array_t<double> Unproject(const Camera& c, const py::handle& pixels) {
  const Rows q = CheckedRows(pixels, "pixels", 2);
  py::array_t<double> out = ResultRows(q, 3);
  double* ray = out.mutable_data();
  for (py::ssize_t i = 0; i < q.n; ++i, ray += 3) {
    const std::optional<Eigen::Vector3d> r = c.Unproject(Eigen::Vector2d(q.data[2 * i], q.data[2 * i + 1]));
    for (int k = 0; k < 3; ++k) ray[k] = r ? (*r)[k] : kNaN;
  }
  return out;
}

// (pixels, d_px_d_params, d_px_d_points): shapes (N, 2), (N, 2, P), (N, 2, 3); NaN rows behind the camera.
py::tuple ProjectJacobians(const Camera& c, const py::handle& points) {
  const Rows p = CheckedRows(points, "points", 3);
  const py::ssize_t np = static_cast<py::ssize_t>(c.params.size());
  py::array_t<double> px = ResultRows(p, 2);
  py::array_t<double> d_params = p.one_row ? NewArray({2, np}) : NewArray({p.n, 2, np});
  py::array_t<double> d_points = p.one_row ? NewArray({2, 3}) : NewArray({p.n, 2, 3});
  double* u = px.mutable_data();
  double* jp = d_params.mutable_data();
  double* jx = d_points.mutable_data();
  std::visit(
      [&](auto model) {
        using Model = decltype(model);
        for (py::ssize_t i = 0; i < p.n; ++i, u += 2, jp += 2 * np, jx += 6) {
          if (!Model::ProjectWithJacobians(c.params.data(), p.data + 3 * i, u, jp, jx)) {
            std::fill(u, u + 2, kNaN);
            std::fill(jp, jp + 2 * np, kNaN);
            std::fill(jx, jx + 6, kNaN);
          }
        }
      },
      c.model);
  return py::make_tuple(px, d_params, d_points);
}

}  // namespace

void RegisterCamera(py::module_& m) {
  m.def(
      "lens_models",
      [] {
        py::dict models;
        ForEachLensModel([&](auto model) {
          py::list names;
          for (std::string_view n : decltype(model)::kParamNames) names.append(py::str(n.data(), n.size()));
          models[py::str(decltype(model)::kName.data(), decltype(model)::kName.size())] = names;
        });
        return models;
      },
      "Every lens model by its file name, with its parameter names in order.");

  py::class_<Camera>(m, "Camera",
                     "A camera: image size, a lens model by name and its parameters [fx, fy, cx, cy, s, <distortion>] "
                     "(docs/conventions.md#intrinsics).")
      .def(py::init(&MakeCamera), py::arg("model"), py::arg("params"), py::arg("image_size"))
      .def_static(
          "from_K",
          [](const py::handle& K, const std::pair<int, int>& image_size, const std::string& model, const py::object& distortion) {
            const Rows k = CheckedRows(K, "K", 3, false);
            if (k.n != 3) throw InputError("K: expected shape (3, 3), got (" + std::to_string(k.n) + ", 3); give the 3×3 camera matrix");
            const Eigen::Matrix3d km = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data);
            if (km(1, 0) != 0 || km(2, 0) != 0 || km(2, 1) != 0 || km(2, 2) != 1 || !(km(0, 0) > 0) || !(km(1, 1) > 0)) {
              throw InputError("K: not a camera matrix; give an upper-triangular K with K[2][2] = 1 and fx, fy > 0");
            }
            const AnyLensModel lens = ModelNamed(model);
            std::vector<double> d;
            if (!distortion.is_none()) {
              const Rows r = CheckedVector(distortion, "distortion", LensModelNumParams(lens) - kNumIntrinsicParams);
              d.assign(r.data, r.data + r.n);
            }
            return Camera::FromK(km, SizeOf(image_size), lens, d);
          },
          py::arg("K"), py::arg("image_size"), py::arg("model") = "none", py::arg("distortion") = py::none(),
          "A camera from its 3×3 matrix K and the model's distortion coefficients (None: all zero).")
      .def_property_readonly("model", [](const Camera& c) { return std::string(LensModelName(c.model)); })
      .def_property_readonly("param_names",
                             [](const Camera& c) {
                               std::vector<std::string> names;
                               for (std::string_view n : LensModelParamNames(c.model)) names.emplace_back(n);
                               return names;
                             })
      .def_property_readonly("params", [](const Camera& c) { return ToVector(c.params); }, "A copy of the parameters.")
      .def_property_readonly("image_size", [](const Camera& c) { return std::pair(c.image_size.width, c.image_size.height); })
      .def_property_readonly("K", [](const Camera& c) { return ToArray(c.K()); })
      .def_property_readonly("distortion", [](const Camera& c) {
        const std::span<const double> d = c.distortion();
        return ToVector(std::vector<double>(d.begin(), d.end()));
      })
      .def("project", &Project, py::arg("points"),
           "Pixels (N, 2) of camera-frame points (N, 3); a point with z ≤ 0 gives a NaN row.")
      .def("unproject", &Unproject, py::arg("pixels"),
           "Rays (x, y, 1) (N, 3) through pixels (N, 2); a pixel outside the lens's valid domain gives a NaN row.")
      .def("project_jacobians", &ProjectJacobians, py::arg("points"),
           "(pixels (N, 2), d_px_d_params (N, 2, P), d_px_d_points (N, 2, 3)) of camera-frame points (N, 3).")
      .def("in_image",
           [](const Camera& c, const py::handle& pixels) {
             const Rows q = CheckedRows(pixels, "pixels", 2);
             py::array_t<bool> out(std::vector<py::ssize_t>{q.n});
             for (py::ssize_t i = 0; i < q.n; ++i) out.mutable_data()[i] = c.InImage({q.data[2 * i], q.data[2 * i + 1]});
             return out;
           },
           py::arg("pixels"), "Whether each pixel lies on the sensor: u in [-0.5, W - 0.5], v in [-0.5, H - 0.5].")
      .def("valid_radius_squared", &Camera::ValidRadiusSquared,
           "The largest r² = x² + y² (normalized) over which the lens maps rays to pixels one to one.")
      .def("__repr__", [](const Camera& c) {
        return "vstcal.Camera(model=\"" + std::string(LensModelName(c.model)) + "\", image_size=(" +
               std::to_string(c.image_size.width) + ", " + std::to_string(c.image_size.height) + "))";
      });
}

}  // namespace vstcal::python
