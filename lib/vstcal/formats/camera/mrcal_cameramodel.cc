#include "vstcal/formats/camera/mrcal_cameramodel.h"

#include <cmath>

#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/python_literal.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

constexpr std::string_view kUnitKey = "vstcal_length_unit";
// Longer rotation vectors are refused: the angle's square would overflow near 1e154 rad, and
// rounding has long since made the rotation meaningless.
constexpr double kMaxRotvecNorm = 1e6;

const MrcalLensModel* FindLensModel(std::string_view name) {
  for (const MrcalLensModel& m : kMrcalLensModels) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

const MrcalLensModel* FindLensModelWithLength(int n) {
  for (const MrcalLensModel& m : kMrcalLensModels) {
    if (m.opencv_length == n) return &m;
  }
  return nullptr;
}

// The shortest of kMrcalLensModels that holds the coefficient at `index`.
const MrcalLensModel& ShortestHolding(int index) {
  for (const MrcalLensModel& m : kMrcalLensModels) {
    if (m.opencv_length > index) return m;
  }
  VSTCAL_CHECK(false, "no mrcal lens model holds coefficient " + std::to_string(index));
  return kMrcalLensModels[0];
}

std::string KnownLensModels() {
  std::string names;
  for (const MrcalLensModel& m : kMrcalLensModels) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

// The names of an OpenCV vector's first n coefficients (k1, k2, p1, p2, ...).
std::vector<std::string_view> OpenCvNames(int n) {
  const auto model = LensModelForOpenCvLength(n);
  VSTCAL_CHECK(model.has_value(), "no lens model holds this OpenCV length");
  const auto names = LensModelParamNames(*model);
  return {names.begin() + kNumIntrinsicParams, names.begin() + kNumIntrinsicParams + n};
}

std::string List(const std::vector<double>& values) {
  std::string s = "[ ";
  for (size_t i = 0; i < values.size(); ++i) s += (i ? ", " : "") + ShortestDecimal(values[i]);
  return s + " ]";
}

// An image side: an integer literal (mrcal writes them so) from 1 to limits::kMaxImageSide.
int ImageSide(const PyNode& node, std::string_view what) {
  const double v = node.Number();
  if (!node.value().integral) {
    node.Fail("must be a positive integer, got " + node.value().text, "give the image " + std::string(what) + " in pixels");
  }
  if (const auto problem = ImageSideProblem(v, what)) node.Fail(problem->reason, problem->fix);
  return static_cast<int>(v);
}

const MrcalLensModel& ReadLensModel(const PyNode& root, const std::string& name) {
  const auto node = root.find("lensmodel");
  if (!node) {
    for (const std::string_view legacy : {"lens_model", "distortion_model"}) {
      if (root.find(legacy)) {
        FailField(name, "lensmodel", "missing key; the file has the older key '" + std::string(legacy) + "'",
                  "rename it to 'lensmodel', the key mrcal 2 reads and writes");
      }
    }
    FailField(name, "lensmodel", "missing key", "add 'lensmodel', e.g. 'lensmodel': 'LENSMODEL_OPENCV8'");
  }
  const std::string lensmodel = node->String();
  const MrcalLensModel* model = FindLensModel(lensmodel);
  if (!model) {
    node->Fail(
        "'" + lensmodel + "' is not a lens model vstcal reads (" + KnownLensModels() + ")",
        "fit one of them with mrcal's own tool, e.g. mrcal-convert-lensmodel --sampled LENSMODEL_OPENCV8 " + name);  // house-plan: names a command
  }
  return *model;
}

LengthUnit ReadUnit(const PyNode& root, const std::string& name, std::optional<LengthUnit> given,
                    const Eigen::Vector3d& t, std::vector<std::string>* notes) {
  std::optional<LengthUnit> in_file;
  if (const auto node = root.find(kUnitKey)) {
    const std::string s = node->String();
    in_file = LengthUnitFromName(s);
    if (!in_file) node->Fail("unknown unit '" + s + "'", "use one of 'mm', 'cm', 'm'");
    if (given && *given != *in_file) {
      node->Fail("the file's lengths are in " + s + ", but " + std::string(LengthUnitName(*given)) + " was given",
                 "leave the length unit out: the file records its own");
    }
  }
  if (!given && !in_file && !t.isZero(0)) {
    notes->push_back(name +
                     ": extrinsics: mrcal files carry no length unit; the translation is taken to be in mm "
                     "(give the length unit if it is not)");
  }
  return given ? *given : in_file.value_or(LengthUnit::kMillimetre);
}

}  // namespace

ImportedCamera MrcalCameramodelFromText(std::string_view text, const std::string& name,
                                        std::optional<LengthUnit> length_unit) {
  if (IsBlank(text)) {
    throw InputError(name + ": the file is empty; expected a mrcal camera model { 'lensmodel': ..., ... }");
  }
  const PyValue doc = ParsePythonDict(text, name);
  const PyNode root(&doc, "", &name);
  const MrcalLensModel& model = ReadLensModel(root, name);

  const PyNode intrinsics = root.at("intrinsics", "add 'intrinsics': [fx, fy, cx, cy, distortion...]");
  const size_t count = 4 + model.opencv_length;
  if (intrinsics.ListSize() != count) {
    intrinsics.Fail(std::string(model.name) + " has " + std::to_string(count) + " intrinsics, got " +
                        std::to_string(intrinsics.ListSize()),
                    "give fx, fy, cx, cy and the " + std::to_string(model.opencv_length) + " distortion coefficients");
  }
  std::vector<double> p(count);
  for (size_t i = 0; i < count; ++i) p[i] = intrinsics.at(i).Number();
  for (size_t i = 0; i < 2; ++i) {
    if (!(p[i] > 0)) {
      intrinsics.at(i).Fail(
          std::string(i == 0 ? "fx" : "fy") + " must be positive, got " + intrinsics.at(i).value().text,
          "check the focal lengths' signs");
    }
  }

  const PyNode extrinsics = root.at("extrinsics", "add 'extrinsics': [0, 0, 0, 0, 0, 0] for a camera at the reference");
  if (extrinsics.ListSize() != 6) {
    extrinsics.Fail("expected 6 numbers, got " + std::to_string(extrinsics.ListSize()),
                    "write rt_cam_ref as [rx, ry, rz, tx, ty, tz]: rotation vector (radians), translation");
  }
  Eigen::Matrix<double, 6, 1> rt;
  for (int i = 0; i < 6; ++i) rt(i) = extrinsics.at(i).Number();
  // stableNorm: a component beyond 1e154 would overflow norm()'s sum of squares to ∞.
  if (const double angle = rt.head<3>().stableNorm(); !(angle <= kMaxRotvecNorm)) {
    extrinsics.Fail("the rotation vector's length, its angle, is " + ShortestDecimal(angle) + " rad",
                    "give the rotation with an angle of at most " + ShortestDecimal(kMaxRotvecNorm) +
                        " rad (mrcal writes it in [0, π])");
  }

  const PyNode imagersize =
      root.at("imagersize", "add 'imagersize': [width, height], the size in pixels of the calibration images");
  if (imagersize.ListSize() != 2) {
    imagersize.Fail("expected 2 integers, got " + std::to_string(imagersize.ListSize()),
                    "write [width, height] in pixels");
  }
  const ImageSize size{ImageSide(imagersize.at(0), "width"), ImageSide(imagersize.at(1), "height")};

  ImportedCamera out;
  CalibratedCamera& c = out.camera;
  Eigen::Matrix3d K;
  K << p[0], 0, p[2], 0, p[1], p[3], 0, 0, 1;
  c.camera = CameraFromOpenCv(K, size, std::span<const double>(p).subspan(4));
  c.method = "mrcal";
  c.length_unit = ReadUnit(root, name, length_unit, rt.tail<3>(), &out.notes);
  // All zeros is mrcal's "this camera is the reference frame": no pose of its own.
  if (!rt.isZero(0)) {
    c.camera_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(rt.head<3>()), Eigen::Vector3d(rt.tail<3>()));
    out.rotation_vector = rt.head<3>();
    if (const auto problem = PoseProblem(K, *c.camera_from_world)) extrinsics.Fail(problem->reason, problem->fix);
  }
  return out;
}

ImportedCamera ReadMrcalCameramodel(const std::filesystem::path& path, std::optional<LengthUnit> length_unit) {
  return MrcalCameramodelFromText(ReadInputFile(path, "a mrcal .cameramodel file"), path.string(), length_unit);
}

ExportedCamera MrcalCameramodelText(const CalibratedCamera& camera, std::string_view source,
                                    const MrcalWriteOptions& options, const Provenance& provenance) {
  const Camera& c = camera.camera;
  RefuseSkew(c, source, "mrcal");
  // mrcal 2.2 has no Kannala–Brandt model (docs/tools/calib-convert.md#fisheye): the nearest,
  // LENSMODEL_SPLINED_STEREOGRAPHIC, is a fit to the corners, not a conversion of the coefficients.
  RefuseNonOpenCvModel(c, source, "mrcal 2.2, which has no Kannala–Brandt model",
                       "calibrate the same corners with mrcal-calibrate-cameras --lensmodel "  // house-plan: names a command
                       "LENSMODEL_SPLINED_STEREOGRAPHIC_order=3_Nx=16_Ny=12_fov_x_deg=<the lens's field>, its nearest "
                       "model, or write it as OpenCV YAML (distortion_model: fisheye)");
  const MrcalLensModel* model = FindLensModelWithLength(ShortestOpenCvLength(c));
  VSTCAL_CHECK(model != nullptr, "no mrcal lens model for this camera's distortion");
  if (options.lensmodel) {
    model = FindLensModel(*options.lensmodel);
    if (!model) {
      throw InputError("lens model: unknown mrcal model \"" + *options.lensmodel + "\"; use one of " +
                       KnownLensModels());
    }
  }
  if (const auto i = FirstCoefficientBeyond(c, model->opencv_length)) {
    const std::string coefficient(LensModelParamNames(c.model)[kNumIntrinsicParams + *i]);
    throw InputError(std::string(source) + ": distortion." + coefficient + ": " + std::string(model->name) +
                     " has no " + coefficient + ", and this camera's is " + ShortestDecimal(c.distortion()[*i]) +
                     "; write " + std::string(ShortestHolding(*i).name) + ", which holds it");
  }
  const LengthUnit unit = options.length_unit.value_or(camera.length_unit);
  Eigen::Matrix<double, 6, 1> rt = Eigen::Matrix<double, 6, 1>::Zero();
  if (camera.camera_from_world) {
    // The rotation vector read with this pose, when it still gives R exactly: RotvecFromRotation
    // and RotationFromRotvec are inverse only to rounding, and a file read and written again
    // must keep its bits.
    const auto& r = options.rotation_vector;
    const bool as_read = r && RotationFromRotvec(Eigen::Vector3d(*r)) == camera.camera_from_world->R;
    rt.head<3>() = as_read ? *r : RotvecFromRotation(camera.camera_from_world->R);
    rt.tail<3>() = camera.camera_from_world->t;
    if (unit != camera.length_unit) rt.tail<3>() *= MetresPer(camera.length_unit) / MetresPer(unit);
    if (!rt.allFinite()) {
      throw InputError(std::string(source) + ": camera_from_world.t: too large to be written in " +
                       std::string(LengthUnitName(unit)) + "; write the .cameramodel in a larger length unit");
    }
  }

  const Eigen::Matrix3d K = c.K();
  std::vector<double> intrinsics = {K(0, 0), K(1, 1), K(0, 2), K(1, 2)};
  const std::vector<double> distortion = OpenCvDistortion(c, model->opencv_length);
  intrinsics.insert(intrinsics.end(), distortion.begin(), distortion.end());
  std::string names = "fx, fy, cx, cy";
  for (const std::string_view n : OpenCvNames(model->opencv_length)) names += ", " + std::string(n);

  ExportedCamera out;
  NoteUnwrittenName(camera, source, &out.notes);
  out.text = "# " + ProvenanceComment(provenance) + "\n{\n";
  out.text += "    'lensmodel': '" + std::string(model->name) + "',\n";
  out.text += "    # " + names + "\n";
  out.text += "    'intrinsics': " + List(intrinsics) + ",\n";
  out.text += "    # rt_cam_ref: rotation vector (radians), then translation; x_cam = R(r) x_ref + t\n";
  out.text += "    'extrinsics': " + List(std::vector<double>(rt.data(), rt.data() + 6)) + ",\n";
  out.text += "    'imagersize': [ " + std::to_string(c.image_size.width) + ", " + std::to_string(c.image_size.height) +
              " ],\n";
  out.text += "    # unit of the translation above: mrcal files carry none, and vstcal reads it back\n";
  out.text += "    '" + std::string(kUnitKey) + "': '" + std::string(LengthUnitName(unit)) + "',\n}\n";
  return out;
}

}  // namespace vstcal
