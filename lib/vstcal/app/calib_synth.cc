#include "vstcal/app/calib_synth.h"

#include <filesystem>

#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

namespace vstcal::app {

std::string DefaultTruthPath(const std::string& output) {
  return std::filesystem::path(output).replace_extension(".truth.json").string();
}

Outcome Synthesize(SynthRequest request, const Provenance& provenance) {
  if (request.truth.empty()) request.truth = DefaultTruthPath(request.output);
  const Camera camera =
      request.camera_file.empty() ? MakeSyntheticCamera(request.camera) : ReadCamera(request.camera_file).camera;
  const VolumeSpec& spec = request.volume;
  Outcome outcome;
  CalibratedCamera truth;
  Correspondences corners;
  if (request.planar_views) {
    PlanarViewsSpec views = request.views;
    views.grid_cols = spec.grid_cols;
    views.grid_rows = spec.grid_rows;
    views.spacing = spec.spacing;
    views.noise_px = spec.noise_px;
    views.seed = spec.seed;
    views.length_unit = spec.length_unit;
    views.camera_name = spec.camera_name;
    const SyntheticViews synthetic = SynthesizePlanarViews(camera, views);
    for (const std::string& w : synthetic.warnings) outcome.warnings.push_back("calib-synth: warning: " + w);
    truth = PlanarViewsTruthCamera(camera, views, synthetic);
    corners = synthetic.correspondences;
  } else {
    const SyntheticVolume volume =
        SynthesizeVolume(camera, spec, request.test_points ? Seed000TestPoints(spec) : std::vector<TestPoint>{});
    truth = VolumeTruthCamera(camera, spec, volume);
    corners = volume.correspondences;
  }
  outcome.files = {{request.output, DumpJson(CorrespondencesToJson(corners, provenance))},
                   {request.truth, DumpJson(CameraToJson(truth, provenance))}};
  outcome.summary += "calib-synth: " + std::to_string(NumObservations(corners)) + " points in " +
                     std::to_string(corners.views.size()) + " views, " + std::to_string(corners.test_points.size()) +
                     " test points; wrote " + request.output + " and " + request.truth;
  return outcome;
}

}  // namespace vstcal::app
