// calib-compare: how far apart two cameras are (docs/tools/calib-compare.md).
#include <cstdio>
#include <iostream>
#include <optional>

#include "common/run_tool.h"
#include "common/validators.h"
#include "vstcal/calib/compare.h"
#include "vstcal/scene/measured_volume.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/camera/camera_io.h"
#include "vstcal/formats/camera/correspondences_io.h"

int main(int argc, char** argv) {
  CLI::App app{
      "Compares two vstcal/camera@1 files, REFERENCE (e.g. ground truth) and OTHER (e.g. an estimate): "
      "differences of K, of the pose, and the pixel disagreement over a 9x9 grid of the image at a depth.\n"
      "Exit codes: 0 ok, 1 internal error, 2 bad usage or input.",
      "calib-compare"};
  std::string reference, other;
  std::optional<double> depth;
  app.add_option("REFERENCE", reference, "camera@1 file taken as reference")->required();
  app.add_option("OTHER", other, "camera@1 file compared with it")->required();
  std::string points_file;
  app.add_option("--test-points", points_file,
                 "also compare the projections of this correspondences file's test points (registration error)");
  app.add_option("--depth", depth, "depth of the comparison grid (length unit; default: world origin's depth)")
      ->check(vstcal::tools::kPositiveFinite);
  return vstcal::tools::RunTool(app, argc, argv, [&] {
    using namespace vstcal;
    const CalibratedCamera a = ReadCamera(reference), b = ReadCamera(other);
    const CameraComparison c = [&] {
      try {
        return CompareCameras(a, b, depth);
      } catch (const InputError& e) {
        throw InputError(other + " vs " + reference + ": " + e.what());  // name the files
      }
    }();
    // Every input is read and checked before anything is printed: a refused --test-points file
    // leaves no half comparison on stdout.
    std::optional<std::vector<PointDisagreement>> at_points;
    if (!points_file.empty()) {
      const Correspondences corners = ReadCorrespondences(points_file);
      if (corners.test_points.empty()) throw InputError(points_file + ": test_points: none; give a file with test points");
      try {
        at_points = CompareAtTestPoints(a, b, corners);
      } catch (const InputError& e) {
        throw InputError(other + " vs " + reference + ": " + e.what());
      }
    }
    const Eigen::Matrix3d Ka = a.camera.K(), Kb = b.camera.K();
    const char* names[5] = {"fx", "fy", "cx", "cy", "skew"};
    const int rows[5] = {0, 1, 0, 1, 0}, cols[5] = {0, 1, 2, 2, 1};
    std::printf("%-6s %16s %16s %12s\n", "", "reference", "other", "difference");
    for (int i = 0; i < 5; ++i) {
      std::printf("%-6s %16.6f %16.6f %12.6f\n", names[i], Ka(rows[i], cols[i]), Kb(rows[i], cols[i]),
                  c.K_difference(rows[i], cols[i]));
    }
    const std::string unit(LengthUnitName(a.length_unit));
    if (c.rotation_deg) std::printf("rotation difference      %.6f deg\n", *c.rotation_deg);
    if (c.centre_distance) std::printf("camera centre distance   %.6f %s\n", *c.centre_distance, unit.c_str());
    std::printf("pixel disagreement at depth %.1f %s: RMS %.4f px, max %.4f px over %zu grid points\n", c.depth,
                unit.c_str(), c.rms_px, c.max_px, c.n_points);
    if (at_points) {
      std::printf("%-14s %-8s %s\n", "test point", "volume", "disagreement px");
      for (const PointDisagreement& d : *at_points) {
        const char* where = VolumeSideName(d.inside_volume);
        if (d.pixel_distance) {
          std::printf("%-14s %-8s %.4f\n", d.name.c_str(), where, *d.pixel_distance);
        } else {
          std::printf("%-14s %-8s (behind a camera)\n", d.name.c_str(), where);
        }
      }
    }
    return 0;
  });
}
