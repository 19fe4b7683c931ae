#include "flags.h"

#include <string>

#include "common/validators.h"

namespace vstcal::tools {

void HandEyeFlags::Add(CLI::App& app) {
  app.require_subcommand(1);
  solve_app = app.add_subcommand(
      "solve",
      "hmd_from_camera (where the camera sits on the tracked body), tracker_from_board and the clocks' offset, by maximum "
      "likelihood over the board corners of timed views and the tracker's log, with their joint covariance "
      "(vstcal/handeye@1)");
  solve_app->add_option("CORNERS", solve.corners, "the board's corners in timed views (vstcal/correspondences@1, views[i].time)")
      ->required()
      ->check(kNonEmpty);
  solve_app->add_option("--poses", solve.poses, "the tracker's log: tracker_from_hmd (vstcal/poses@1 .json, or TUM text)")
      ->required()
      ->check(kNonEmpty);
  auto* camera = solve_app->add_option("--camera", solve.camera, "the camera that took the views (vstcal/camera@1; its intrinsics are held)")
                     ->check(kNonEmpty);
  auto* rig = solve_app->add_option("--rig", solve.rig,
                                    "a stereo rig instead (vstcal/stereo@1, from calib-stereo): CORNERS are its left camera's views, "
                                    "--right its right camera's; right_from_left and both cameras' intrinsics are held")
                  ->check(kNonEmpty);
  auto* right = solve_app->add_option("--right", solve.right_corners,
                                      "with --rig: the right camera's timed views (correspondences@1), paired with the left's by name or time")
                    ->check(kNonEmpty);
  camera->excludes(rig);
  rig->needs(right);
  right->needs(rig);
  solve_app->add_option("--tum-unit", solve.tum_unit, "length unit of a TUM log's translations")->capture_default_str();
  solve_app->add_option("--max-time-offset", solve.max_time_offset, "search the clocks' offset within ±this many seconds")
      ->capture_default_str();
  solve_app->add_option("-o,--output", solve.output, "the vstcal/handeye@1 file to write")->required()->check(kNonEmpty);
  solve_app->add_flag("--keep-all-views", solve.keep_all_views,
                      "do not drop views inconsistent with the others' noise (bad frames; dropped by default)");
  solve_app->add_flag("--tracker-exact", solve.tracker_exact,
                      "take the tracker's poses as exact instead of estimating their noise jointly and weighing the views by it");
  const std::string bootstrap_help =
      "also the parametric bootstrap's σ's from this many simulated recordings, each one more solve (default: none; the "
      "first-order σ of the instrumented time offset is as near its spread; docs/tools/calib-handeye.md#bootstrap)";
  auto* bootstrap = solve_app->add_option("--bootstrap", bootstrap_replicates, bootstrap_help);
  auto* seed = solve_app->add_option("--seed", solve.seed, "the bootstrap's seed (the output depends on it only through the bootstrap)")
                   ->check(kSeed)
                   ->capture_default_str();
  auto* threads = solve_app->add_option("--threads", solve.threads, "the bootstrap's threads (0: all cores, at most 256; the output does not depend on it)")
                      ->capture_default_str();
  // A seed or threads without a bootstrap would be silently ignored: refused instead.
  solve_app->parse_complete_callback([this, camera, rig, bootstrap, seed, threads] {
    if (camera->count() == 0 && rig->count() == 0) throw CLI::RequiredError("--camera (or --rig with --right)");
    if (bootstrap->count() > 0) solve.bootstrap = bootstrap_replicates;
    if (solve.bootstrap.value_or(0) == 0 && seed->count() + threads->count() > 0) {
      throw CLI::ValidationError(seed->count() > 0 ? "--seed" : "--threads", "applies to the bootstrap, which runs only with --bootstrap B (B ≥ 2)");
    }
  });
  solve_app->add_option("--opencv", solve.opencv, "also write X, Z and the offset as OpenCV YAML (calibrateHandEye's names)")->check(kNonEmpty);
  solve_app->add_flag("-q,--quiet", quiet, "print only errors");

  noise_app = app.add_subcommand("noise", "the tracker's jitter (rotation, translation σ with 95 % intervals) from a segment of its log in "
                                          "which the headset was held still (vstcal/tracker-noise@1)");
  noise_app->add_option("--poses", noise.poses, "the tracker's log (vstcal/poses@1 .json, or TUM text)")->required()->check(kNonEmpty);
  noise_app->add_option("--from", noise.from, "the static segment's start (s, the tracker's clock)")->required()->check(kFinite);
  noise_app->add_option("--to", noise.to, "the static segment's end (s)")->required()->check(kFinite);
  noise_app->add_option("--tum-unit", noise.tum_unit, "length unit of a TUM log's translations")->capture_default_str();
  noise_app->add_option("--max-motion", noise.max_motion, "mm: a report farther from the segment's mean means the headset moved")
      ->check(kPositiveFinite)
      ->capture_default_str();
  noise_app->add_option("-o,--output", noise.output, "also write vstcal/tracker-noise@1")->check(kNonEmpty);
  noise_app->add_flag("-q,--quiet", quiet, "print only errors");
}

}  // namespace vstcal::tools
