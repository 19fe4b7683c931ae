#include "vstcal/capture/render_scene.h"

#include <cmath>
#include <cstdio>

#include "vstcal/scene/fit.h"
#include "vstcal/image/image_io.h"
#include "vstcal/capture/target_pattern.h"
#include "vstcal/core/error.h"
#include "vstcal/core/parallel.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

constexpr int kMaxRenderedImages = 1000;

std::string Name(const char* prefix, int k) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s-%02d", prefix, k);
  return buf;
}

// The centre of the target's corners: where the camera aims.
Eigen::Vector3d CornerCentre(const Target& target) {
  Eigen::Vector2d lo = CornerPosition(target, 0), hi = lo;
  for (const TargetCorner& c : TargetCorners(target)) lo = lo.cwiseMin(c.xy), hi = hi.cwiseMax(c.xy);
  const Eigen::Vector2d m = 0.5 * (lo + hi);
  return Eigen::Vector3d(m.x(), m.y(), 0);
}

}  // namespace

int NumPlanes(const VolumeSpec& spec) {
  if (!(spec.interval > 0) || !(spec.far >= spec.near)) return 0;
  const double n = std::floor((spec.far - spec.near) / spec.interval + 1e-9) + 1;
  return n > kMaxRenderedImages ? kMaxRenderedImages + 1 : static_cast<int>(n);
}

void CheckRenderSize(ImageSize size, std::string_view camera_file) {
  if (static_cast<double>(size.width) * size.height > kMaxImageMegapixels * 1e6) {
    throw InputError((camera_file.empty() ? std::string() : std::string(camera_file) + ": ") + "image_size: " +
                     std::to_string(size.width) + "×" + std::to_string(size.height) +
                     " is more than 100 megapixels; render smaller images (give a camera of fewer pixels)");
  }
}

RenderedScene RenderScene(const Camera& camera, const Target& target, const SceneSpec& spec) {
  const ImageSize size = camera.image_size;
  CheckRenderSize(size, "");
  RenderedScene scene;
  Correspondences& truth = scene.truth;
  truth.image_size = size;
  truth.length_unit = target.length_unit;
  truth.rig = spec.rig;
  const Eigen::Vector3d centre = CornerCentre(target);
  std::vector<std::optional<double>> offsets;
  if (spec.rig == Rig::kVolume) {
    const VolumeSpec& v = spec.volume;
    if (!(v.interval > 0)) throw InputError(VSTCAL_OPT("interval") ": must be positive");
    if (!(v.far >= v.near)) throw InputError(VSTCAL_OPT("far") ": must not be less than " VSTCAL_OPT("near"));
    if (!(v.camera_distance > 0)) throw InputError(VSTCAL_OPT("camera_distance") ": must be positive");
    if (!(std::abs(v.tilt_deg) < 80)) throw InputError(VSTCAL_OPT("tilt_deg") ": must lie within ±80°");
    const int n = NumPlanes(v);
    if (n > kMaxRenderedImages) throw InputError(VSTCAL_OPT("interval") ": more than 1000 template positions; use a larger interval");
    const Rigid3d camera_from_world = VolumeCameraPose(v) * Rigid3d{Eigen::Matrix3d::Identity(), -centre};
    scene.truth_camera.camera_from_world = camera_from_world;
    for (int k = 0; k < n; ++k) {
      const double z = v.near + k * v.interval;
      scene.names.push_back(Name("plane", k));
      scene.camera_from_board.push_back(camera_from_world * Rigid3d{Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, z)});
      offsets.push_back(z);
    }
  } else {
    PlanarViewsSpec v = spec.views;
    if (v.num_views < 1 || v.num_views > kMaxRenderedImages) throw InputError(VSTCAL_OPT("views") ": give 1 to 1000 views");
    if (!(v.distance > 0)) throw InputError(VSTCAL_OPT("distance") ": must be positive");
    if (!(v.max_tilt_deg >= 0 && v.max_tilt_deg < 80)) throw InputError(VSTCAL_OPT("max_tilt_deg") ": must lie in [0, 80)");
    // PlanarViewPose aims the centre of a grid_cols × grid_rows grid of `spacing`; shift it to
    // the centre of this target's corners.
    v.grid_cols = v.grid_rows = 2;
    v.spacing = 1;
    const Eigen::Vector3d grid_centre(0.5, 0.5, 0);
    for (int k = 0; k < v.num_views; ++k) {
      scene.names.push_back(Name("view", k));
      scene.camera_from_board.push_back(PlanarViewPose(camera, v, k) * Rigid3d{Eigen::Matrix3d::Identity(), grid_centre - centre});
      offsets.push_back(std::nullopt);
    }
  }
  // Every image is held until all are written (all-or-nothing): at most 1000 megapixels in all.
  const double megapixels = static_cast<double>(scene.names.size()) * size.width * size.height / 1e6;
  if (megapixels > 1000) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s: %zu images of %d×%d are %.0f megapixels in all, more than 1000; render fewer or smaller images",
                  spec.rig == Rig::kVolume ? VSTCAL_OPT("interval") : VSTCAL_OPT("views"), scene.names.size(), size.width, size.height, megapixels);
    throw InputError(buf);
  }
  for (size_t k = 0; k < scene.names.size(); ++k) {
    View view;
    view.name = scene.names[k];
    view.image = scene.names[k] + ".png";
    view.plane_offset = offsets[k];
    for (const TargetCorner& c : TargetCorners(target)) {
      const Eigen::Vector3d p_board(c.xy.x(), c.xy.y(), 0);
      const Eigen::Vector3d p_cam = scene.camera_from_board[k] * p_board;
      if (!(p_cam.z() > 0)) throw InputError(VSTCAL_OPT("camera_distance") ": the camera sits inside the volume (" + view.name + "); move it back");
      const auto px = camera.Project(p_cam);
      if (!px || !camera.InImage(*px)) continue;
      view.observations.push_back({Eigen::Vector3d(c.xy.x(), c.xy.y(), offsets[k].value_or(0.0)), *px});
    }
    if (view.observations.empty()) {
      throw InputError(view.name + ": no corner of the target is in the image; move the camera or the target into view");
    }
    truth.views.push_back(std::move(view));
  }
  const Pattern pattern = TargetPattern(target);
  const PixelCornerRays rays(camera);
  scene.images.resize(scene.names.size());
  ParallelFor(scene.names.size(), spec.threads, [&](size_t k) {
    scene.images[k] = RenderView(rays, pattern, scene.camera_from_board[k], spec.render, static_cast<uint32_t>(k));
  });
  CalibratedCamera& cam = scene.truth_camera;
  cam.camera = camera;
  cam.length_unit = target.length_unit;
  cam.method = "synthetic";
  if (spec.rig == Rig::kVolume) {
    cam.fit = ComputeVolumeFit(camera, *cam.camera_from_world, truth);
  } else {
    for (size_t k = 0; k < scene.names.size(); ++k) cam.views.push_back({scene.names[k], scene.camera_from_board[k], 0});
    cam.fit = ComputeViewsFit(camera, scene.camera_from_board, truth);
  }
  return scene;
}

}  // namespace vstcal
