// Rendered captures with their ground truth: a target shown at the template positions of a
// calibration volume (seed 000 §4.1, the geometry of calib-synth, synthetic_volume.h) or at
// planar-view poses (synthetic_views.h), drawn by render.h. The test data for detection.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/scene/calibrated_camera.h"
#include "vstcal/scene/correspondences.h"
#include "vstcal/image/image.h"
#include "vstcal/capture/render.h"
#include "vstcal/capture/synthetic_views.h"
#include "vstcal/capture/synthetic_volume.h"
#include "vstcal/capture/target.h"

namespace vstcal {

struct SceneSpec {
  Rig rig = Rig::kVolume;
  // Volume: near, far, interval, camera_distance, tilt_deg, tilt_direction_deg, roll_deg are used
  // (the grid fields are the target's). World frame = the board frame of the template at offset
  // 0; the template at offset z is the board moved by z along its Z axis (away from the camera);
  // the camera looks at the centre of the corners at mid-depth as calib-synth's does.
  VolumeSpec volume;
  // Planar views: num_views, distance, max_tilt_deg, seed are used; view k's pose is
  // PlanarViewPose's, aimed at the centre of the target's corners.
  PlanarViewsSpec views;
  RenderOptions render;
  unsigned threads = 0;  // 0: all cores; the images do not depend on it
};

struct RenderedScene {
  std::vector<std::string> names;  // "plane-00", … or "view-00", …; the images are <name>.png
  std::vector<GrayImage> images;
  std::vector<Rigid3d> camera_from_board;
  Correspondences truth;  // every corner that projects into the image, exact (no noise); views named as the images
  CalibratedCamera truth_camera;  // method "synthetic": the camera and camera_from_world (volume) or the views' poses
};

// Throws InputError for impossible requests: more than 1,000 images, 100 megapixels an image or
// 1,000 megapixels in all, the camera inside the volume, a view without any visible corner.
RenderedScene RenderScene(const Camera& camera, const Target& target, const SceneSpec& spec);

// Throws InputError when images of `size` are too large to render (more than 100 megapixels),
// naming `camera_file` (the camera file the size comes from; "" for none).
void CheckRenderSize(ImageSize size, std::string_view camera_file);

// The number of template positions of a volume spec: near, near + interval, … ≤ far.
int NumPlanes(const VolumeSpec& spec);

}  // namespace vstcal
