#include "vstcal/capture/synthetic_volume.h"

#include <cmath>
#include <cstdio>

#include "vstcal/scene/fit.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/random/philox.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// Philox stream ids: one per view, one for the test points.
constexpr uint32_t kTestPointStream = 0xFFFFFFFFu;

void VolumeRequire(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

std::string VolumeNum(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace

Rigid3d VolumeCameraPose(const VolumeSpec& spec) {
  const Eigen::Vector3d centre(0, 0, 0.5 * (spec.near + spec.far));
  const double radius = spec.camera_distance + 0.5 * (spec.far - spec.near);
  const double tilt = DegToRad(spec.tilt_deg), dir = DegToRad(spec.tilt_direction_deg);
  const Eigen::Vector3d towards_camera(std::sin(tilt) * std::cos(dir), std::sin(tilt) * std::sin(dir), -std::cos(tilt));
  const Eigen::Vector3d camera_in_world = centre + radius * towards_camera;
  const Eigen::Vector3d z = -towards_camera;                                       // optical axis
  const Eigen::Vector3d y = (Eigen::Vector3d::UnitY() - z * z.y()).normalized();  // image down ≈ world +Y
  const Eigen::Vector3d x = y.cross(z);
  Eigen::Matrix3d world_axes_in_camera;
  world_axes_in_camera.row(0) = x.transpose();
  world_axes_in_camera.row(1) = y.transpose();
  world_axes_in_camera.row(2) = z.transpose();
  const Eigen::Matrix3d roll = RotationFromRotvec(Eigen::Vector3d(0, 0, DegToRad(spec.roll_deg)));
  Rigid3d camera_from_world;
  camera_from_world.R = roll * world_axes_in_camera;
  camera_from_world.t = -camera_from_world.R * camera_in_world;
  return camera_from_world;
}

std::vector<TestPoint> Seed000TestPoints(const VolumeSpec& spec) {
  const double mm = 1e-3 / MetresPer(spec.length_unit);  // one millimetre in the spec's unit
  const double half_w = 0.5 * (spec.grid_cols - 1) * spec.spacing;
  const double half_h = 0.5 * (spec.grid_rows - 1) * spec.spacing;
  const double depth = spec.far - spec.near;
  auto z_at = [&](double fraction) { return spec.near + fraction * depth; };
  return {
      {"Left", Eigen::Vector3d(-half_w - 440 * mm, 0, z_at(0.5)), std::nullopt},
      {"Right", Eigen::Vector3d(half_w + 160 * mm, 0, z_at(0.5)), std::nullopt},
      {"Middle 1", Eigen::Vector3d(-0.35 * half_w, -0.35 * half_h, z_at(0.25)), std::nullopt},
      {"Middle 2", Eigen::Vector3d(0.1 * half_w, 0.15 * half_h, z_at(0.5)), std::nullopt},
      {"Middle 3", Eigen::Vector3d(0.4 * half_w, 0.3 * half_h, z_at(0.75)), std::nullopt},
  };
}

SyntheticVolume SynthesizeVolume(const Camera& camera, const VolumeSpec& spec, std::vector<TestPoint> test_points) {
  VolumeRequire(spec.grid_cols >= 2 && spec.grid_rows >= 2, VSTCAL_OPT("grid") ": the template needs at least 2×2 corners");
  VolumeRequire(spec.spacing > 0, VSTCAL_OPT("spacing") ": must be positive, got " + VolumeNum(spec.spacing));
  VolumeRequire(spec.interval > 0, VSTCAL_OPT("interval") ": must be positive, got " + VolumeNum(spec.interval));
  VolumeRequire(spec.far >= spec.near, VSTCAL_OPT("far") ": must not be less than " VSTCAL_OPT("near") " (" + VolumeNum(spec.far) + " < " + VolumeNum(spec.near) + ")");
  VolumeRequire(spec.camera_distance > 0, VSTCAL_OPT("camera_distance") ": must be positive, got " + VolumeNum(spec.camera_distance));
  VolumeRequire(spec.noise_px >= 0, VSTCAL_OPT("noise") ": σ must not be negative, got " + VolumeNum(spec.noise_px));
  VolumeRequire(std::abs(spec.tilt_deg) < 80, VSTCAL_OPT("tilt_deg") ": must lie within ±80°, got " + VolumeNum(spec.tilt_deg));
  for (const auto& [flag, value] : {std::pair<const char*, double>{VSTCAL_OPT("spacing"), spec.spacing}, {VSTCAL_OPT("near"), spec.near},
                                    {VSTCAL_OPT("far"), spec.far}, {VSTCAL_OPT("interval"), spec.interval},
                                    {VSTCAL_OPT("camera_distance"), spec.camera_distance}, {VSTCAL_OPT("noise"), spec.noise_px}}) {
    VolumeRequire(std::abs(value) <= limits::kMaxSyntheticScale,
            std::string(flag) + ": " + VolumeNum(value) + " is beyond ±" + VolumeNum(limits::kMaxSyntheticScale) +
                " (docs/reliability.md#limits); give a realistic value");
  }
  // Counted in double before any loop: a tiny interval would otherwise ask for 1e300 planes.
  const double planes = std::floor((spec.far - spec.near) / spec.interval + 1e-9) + 1;
  VolumeRequire(planes <= static_cast<double>(limits::kMaxViews),
          VSTCAL_OPT("interval") ": " + VolumeNum(planes) + " template positions, more than the " + std::to_string(limits::kMaxViews) +
              " views a file may hold (docs/reliability.md#limits); use a larger interval");
  const size_t n_planes = static_cast<size_t>(planes);
  const double points = planes * spec.grid_cols * spec.grid_rows;
  VolumeRequire(points <= static_cast<double>(limits::kMaxPoints),
          VSTCAL_OPT("grid") ": " + std::to_string(spec.grid_cols) + "×" + std::to_string(spec.grid_rows) + " corners on " +
              std::to_string(n_planes) + " planes is " + VolumeNum(points) + " points, more than the " +
              std::to_string(limits::kMaxPoints) + " a file may hold (docs/reliability.md#limits); use fewer corners");

  SyntheticVolume out;
  out.camera_from_world = VolumeCameraPose(spec);
  Correspondences& c = out.correspondences;
  c.camera = spec.camera_name;
  c.image_size = camera.image_size;
  c.length_unit = spec.length_unit;
  c.rig = Rig::kVolume;

  const double x0 = -0.5 * (spec.grid_cols - 1) * spec.spacing;
  const double y0 = -0.5 * (spec.grid_rows - 1) * spec.spacing;
  for (size_t k = 0; k < n_planes; ++k) {
    const double offset = spec.near + static_cast<double>(k) * spec.interval;
    char name[32];
    std::snprintf(name, sizeof name, "plane-%02zu", k);
    View view;
    view.name = name;
    view.plane_offset = offset;
    const CounterRng rng(spec.seed, static_cast<uint32_t>(k));
    for (int j = 0; j < spec.grid_rows; ++j) {
      for (int i = 0; i < spec.grid_cols; ++i) {
        const Eigen::Vector3d p(x0 + i * spec.spacing, y0 + j * spec.spacing, offset);
        const Eigen::Vector3d p_cam = out.camera_from_world * p;
        VolumeRequire(p_cam.z() > 0, VSTCAL_OPT("camera_distance") ": the camera sits inside the volume (a corner of plane " +
                                   std::to_string(k) + " is behind it); move it back");
        const auto px = camera.Project(p_cam);
        if (!px || !camera.InImage(*px)) continue;
        // The draw is keyed by the corner's grid index, so dropping other corners never shifts it.
        const auto noise = rng.Normal2(static_cast<uint64_t>(j) * spec.grid_cols + i, 0);
        const Eigen::Vector2d noisy = *px + spec.noise_px * Eigen::Vector2d(noise[0], noise[1]);
        if (!camera.InImage(noisy)) continue;
        view.observations.push_back({p, noisy});
      }
    }
    if (!view.observations.empty()) c.views.push_back(std::move(view));
  }
  VolumeRequire(NumObservations(c) > 0, VSTCAL_OPT("camera_distance") "/" VSTCAL_OPT("tilt_deg") ": no corner is visible; point the camera at the template");

  const CounterRng test_rng(spec.seed, kTestPointStream);
  for (size_t i = 0; i < test_points.size(); ++i) {
    TestPoint& t = test_points[i];
    const auto px = camera.Project(out.camera_from_world * t.point_in_world);
    const auto noise = test_rng.Normal2(i, 0);
    const bool visible = px && camera.InImage(*px + spec.noise_px * Eigen::Vector2d(noise[0], noise[1]));
    VolumeRequire(visible, "test point \"" + t.name +
                         "\" is not visible (behind the camera or outside the image); widen the field of view, move "
                         "the camera back, or use " VSTCAL_OPT("no_test_points"));
    t.pixel = *px + spec.noise_px * Eigen::Vector2d(noise[0], noise[1]);
  }
  c.test_points = std::move(test_points);
  return out;
}

CalibratedCamera VolumeTruthCamera(const Camera& camera, const VolumeSpec& spec, const SyntheticVolume& volume) {
  CalibratedCamera truth = SyntheticTruth(camera, spec.camera_name, spec.length_unit);
  truth.camera_from_world = volume.camera_from_world;
  truth.fit = ComputeVolumeFit(camera, volume.camera_from_world, volume.correspondences);
  return truth;
}

}  // namespace vstcal
