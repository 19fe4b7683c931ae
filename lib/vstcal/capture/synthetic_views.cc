#include "vstcal/capture/synthetic_views.h"

#include <cmath>
#include <cstdio>

#include "vstcal/scene/correspondences.h"
#include "vstcal/scene/fit.h"
#include "vstcal/capture/synthetic_camera.h"
#include "vstcal/core/error.h"
#include "vstcal/core/limits.h"
#include "vstcal/random/philox.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// Pose draws use their own stream id, apart from the per-view noise streams.
constexpr uint32_t kPoseStream = 0xFFFFFFFEu;

double Halton(int index, int base) {
  double f = 1, r = 0;
  for (int i = index; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

void ViewsRequire(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

}  // namespace

Rigid3d PlanarViewPose(const Camera& camera, const PlanarViewsSpec& spec, int view) {
  const CounterRng rng(spec.seed, kPoseStream);
  const auto a = rng.Uniform2(static_cast<uint64_t>(view), 0), b = rng.Uniform2(static_cast<uint64_t>(view), 1);
  // Where the board centre appears and how far it is.
  const double w = camera.image_size.width, h = camera.image_size.height;
  const Eigen::Vector2d aim(-0.5 + w * (0.15 + 0.7 * Halton(view + 1, 2)), -0.5 + h * (0.15 + 0.7 * Halton(view + 1, 3)));
  const double depth = spec.distance * (0.8 + 0.4 * a[0]);
  const auto ray = camera.Unproject(aim);
  const Eigen::Vector3d centre_in_camera = depth * ray.value_or(Eigen::Vector3d(0, 0, 1));
  // Tilt about an axis in the board plane, then a small roll about the board normal.
  const double tilt = DegToRad(spec.max_tilt_deg) * (0.3 + 0.7 * a[1]);
  const double axis_angle = 2 * kPi * b[0];
  const double roll = DegToRad(30.0) * (b[1] - 0.5);
  const Eigen::Matrix3d R = RotationFromRotvec(Eigen::Vector3d(tilt * std::cos(axis_angle), tilt * std::sin(axis_angle), 0)) *
                            RotationFromRotvec(Eigen::Vector3d(0, 0, roll));
  const Eigen::Vector3d board_centre(0.5 * (spec.grid_cols - 1) * spec.spacing, 0.5 * (spec.grid_rows - 1) * spec.spacing, 0);
  return Rigid3d{R, centre_in_camera - R * board_centre};
}

SyntheticViews SynthesizePlanarViews(const Camera& camera, const PlanarViewsSpec& spec) {
  ViewsRequire(spec.grid_cols >= 2 && spec.grid_rows >= 2, VSTCAL_OPT("grid") ": the board needs at least 2×2 corners");
  ViewsRequire(spec.spacing > 0, VSTCAL_OPT("spacing") ": must be positive");
  ViewsRequire(spec.num_views >= 1 && static_cast<size_t>(spec.num_views) <= limits::kMaxViews,
          VSTCAL_OPT("views") ": give 1 to " + std::to_string(limits::kMaxViews) + " views");
  ViewsRequire(spec.distance > 0, VSTCAL_OPT("distance") ": must be positive");
  for (const auto& [flag, value] : {std::pair<const char*, double>{VSTCAL_OPT("spacing"), spec.spacing},
                                    {VSTCAL_OPT("distance"), spec.distance}, {VSTCAL_OPT("noise"), spec.noise_px}}) {
    ViewsRequire(std::abs(value) <= limits::kMaxSyntheticScale,
            std::string(flag) + ": beyond ±1e9 (docs/reliability.md#limits); give a realistic value");
  }
  const double points = static_cast<double>(spec.num_views) * spec.grid_cols * spec.grid_rows;
  ViewsRequire(points <= static_cast<double>(limits::kMaxPoints),
          VSTCAL_OPT("grid") "/" VSTCAL_OPT("views") ": " + std::to_string(spec.grid_cols) + "×" + std::to_string(spec.grid_rows) + " corners in " +
              std::to_string(spec.num_views) + " views is more than the " + std::to_string(limits::kMaxPoints) +
              " points a file may hold (docs/reliability.md#limits); use fewer corners or views");
  ViewsRequire(spec.max_tilt_deg >= 0 && spec.max_tilt_deg < 80, VSTCAL_OPT("max_tilt_deg") ": must lie in [0, 80)");
  ViewsRequire(spec.noise_px >= 0, VSTCAL_OPT("noise") ": σ must not be negative");

  SyntheticViews out;
  Correspondences& c = out.correspondences;
  c.camera = spec.camera_name;
  c.image_size = camera.image_size;
  c.length_unit = spec.length_unit;
  c.rig = Rig::kPlanarViews;
  for (int k = 0; k < spec.num_views; ++k) {
    const Rigid3d camera_from_board = PlanarViewPose(camera, spec, k);
    char name[32];
    std::snprintf(name, sizeof name, "view-%02d", k);
    View view;
    view.name = name;
    const CounterRng noise(spec.seed, static_cast<uint32_t>(k));
    for (int j = 0; j < spec.grid_rows; ++j) {
      for (int i = 0; i < spec.grid_cols; ++i) {
        const Eigen::Vector3d p(i * spec.spacing, j * spec.spacing, 0);
        const auto px = camera.Project(camera_from_board * p);
        if (!px || !camera.InImage(*px)) continue;
        const auto e = noise.Normal2(static_cast<uint64_t>(j) * spec.grid_cols + i, 0);
        const Eigen::Vector2d noisy = *px + spec.noise_px * Eigen::Vector2d(e[0], e[1]);
        if (camera.InImage(noisy)) view.observations.push_back({p, noisy});
      }
    }
    if (view.observations.size() < kMinPointsPerPlanarView) {
      out.warnings.push_back("view \"" + view.name + "\" shows only " + std::to_string(view.observations.size()) +
                             " corners: left out");
      continue;
    }
    c.views.push_back(std::move(view));
    out.camera_from_board.push_back(camera_from_board);
  }
  ViewsRequire(!c.views.empty(), VSTCAL_OPT("distance") "/" VSTCAL_OPT("max_tilt_deg") ": no view shows the board; move it into the field of view");
  return out;
}

CalibratedCamera PlanarViewsTruthCamera(const Camera& camera, const PlanarViewsSpec& spec, const SyntheticViews& views) {
  CalibratedCamera truth = SyntheticTruth(camera, spec.camera_name, spec.length_unit);
  truth.fit = ComputeViewsFit(camera, views.camera_from_board, views.correspondences);
  for (size_t v = 0; v < views.camera_from_board.size(); ++v) {
    truth.views.push_back({views.correspondences.views[v].name, views.camera_from_board[v], truth.fit->views[v].stats.rms_px});
  }
  return truth;
}

}  // namespace vstcal
