// The Monte Carlo behind docs/math/handeye.md#delta-bootstrap's table: recordings of
// handeye_noise_test's DeltaMonteCarlo (16 views, 0.05° and 0.2 mm a report, 0.2 px, every view at
// one fraction s of its report interval: δ = 30, 32.5, 35 ms), each solved and bootstrapped
// (BootstrapHandEye, B replicates); prints the spread of δ̂, the mean sandwich σ_δ, the bootstrap's
// mean and RMS σ_δ, the spread over the RMS with its standard error, the RMS z by each and the
// bootstrap's mean bias. Not a test: B + 1 solves per recording (~80 s of one core at the
// defaults), past what a test may take.
//
//   mc_handeye_bootstrap [recordings = 40] [replicates = 30] [first seed = 3000] [s = all: 0, 0.25, 0.5]
//                        [views = 16] [centre = estimate] [view jitter = 0 ms] [tracker noise = 0.05 °] [= 0.2 mm]
//                        [tracker rate = 100 Hz: 100 × 2ᵏ, so that the views at δ = 30 ms sit on a report]
//                        [δ = instrumented (calib-handeye's), or cost: δ minimising the cost, w following it (up to stop 39)]
//
// centre: where the bootstrap's world is put — `estimate` (what calib-handeye does), or with the
// truth in place of one plug-in value to measure what that value's error costs: `true-noise` (the
// tracker's and the corners' σ's), `true-delta` (δ, hence where the views fall between the
// reports), `true-both`, or `truth` (both, and the truth's motion, hand-eye and board: the bootstrap's
// world is then the Monte Carlo's own, and the ratio must be 1 within its standard error — a check
// of the simulation). It also prints the mean estimated σ's over the truth's. `envelope`: three
// bootstraps at the estimate with δ̂ and δ̂ ± the sandwich's σ_δ (the same draws), the largest δ
// variance of the three. `curvature`: the same three, δ's variance 2v₀ − ½(v₊ + v₋) — the centre's
// less half its second difference: the plug-in's average over δ̂'s scatter, V + ½σ²V'', undone to
// second order (linear in the three, so unbiased at any B; it may be negative in one recording).
// `larger`: the larger of the first-order and the bootstrap's δ variance (judge it at a realistic B:
// a maximum is biased upward by B's noise).
//
// view jitter: each view's time moved later by a uniform draw in [0, jitter) ms (HandEyeSpec::view_jitter):
// 10 ms (one report interval) puts the views at random phases, as a camera whose clock is not locked
// to the tracker's; s then only sets δ.
//
// The standard error of spread/RMS: the ratio is √(mean e² / mean σ_b²) over recordings (e = δ̂ − δ
// less its mean), so by the delta method Var log(ratio) = ¼ Var(e²/E e² − σ_b²/E σ_b²)/n, the
// covariance of a recording's e² and σ_b² included. VSTCAL_MC_DUMP=file appends each recording's
// δ̂ − δ and first-order σ_δ, in report intervals, for a histogram. The sample variance of B replicates is
// unbiased for the bootstrap's variance at any B ≥ 2, so B sets only σ_b²'s noise, not its mean.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <ctime>
#include <vector>

#include "support/handeye_scenes.h"
#include "vstcal/handeye/bootstrap.h"
#include "vstcal/handeye/refine.h"

int main(int argc, char** argv) {
  using namespace vstcal;
  const int runs = argc > 1 ? std::atoi(argv[1]) : 40;
  const int replicates = argc > 2 ? std::atoi(argv[2]) : 30;
  const uint64_t first_seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 3000;
  std::vector<double> fractions = {0, 0.25, 0.5};
  if (argc > 4) fractions = {std::atof(argv[4])};
  const int views = argc > 5 ? std::atoi(argv[5]) : 16;
  const std::string centre = argc > 6 ? argv[6] : "estimate";
  const double jitter_ms = argc > 7 ? std::atof(argv[7]) : 0;
  const double noise_deg = argc > 8 ? std::atof(argv[8]) : 0.05, noise_mm = argc > 9 ? std::atof(argv[9]) : 0.2;
  const double rate_hz = argc > 10 ? std::atof(argv[10]) : 100;
  const std::string estimator = argc > 11 ? argv[11] : "instrumented";
  const bool envelope = centre == "envelope", curvature = centre == "curvature", larger = centre == "larger";
  const bool truth = centre == "truth";
  const bool true_noise = centre == "true-noise" || centre == "true-both" || truth;
  const bool true_delta = centre == "true-delta" || centre == "true-both" || truth;
  if (runs < 2 || replicates < 2 || views < 3 || fractions[0] < 0 || fractions[0] >= 1 ||
      !(centre == "estimate" || envelope || curvature || larger || true_noise || true_delta) || !(jitter_ms >= 0 && jitter_ms <= 10) ||
      !(noise_deg > 0 && noise_mm > 0) || !(rate_hz == 100 || rate_hz == 200 || rate_hz == 400) || !(estimator == "instrumented" || estimator == "cost")) {
    std::fprintf(stderr, "usage: mc_handeye_bootstrap [recordings ≥ 2] [replicates ≥ 2] [first seed] [s in [0, 1)] [views ≥ 3] "
                         "[centre: estimate | true-noise | true-delta | true-both | truth | envelope | curvature | larger] [jitter, 0 … 10 ms] [tracker noise > 0 °] [> 0 mm] [rate: 100, 200 or 400 Hz] [δ: instrumented | cost]\n");
    return 2;
  }
  const double noise_rad = noise_deg * M_PI / 180, noise_length = noise_mm, noise_px = 0.2;
  std::printf("s     spread_ms  sandwich_ms  spread/sandwich  boot_mean_ms  boot_rms_ms  spread/boot_rms (se)  rms_z_sandwich  rms_z_boot  "
              "boot_bias_ms  cpu_s\n");
  for (const double s_fraction : fractions) {
    const double delta = 0.03 + s_fraction / rate_hz;  // the views at s = 0 with δ = 30 ms
    const std::clock_t start = std::clock();  // CPU, not wall: the machine is shared
    std::vector<double> error, sandwich, boot_var, bias;
    double rotation = 0, translation = 0, corners = 0;  // mean estimated σ over the truth's
    double slope_excess = 0, concentration = 0;          // means: HandEyeSolution's, and its report_phases'
    int without_noise = 0;
    for (int run = 0; run < runs; ++run) {
      HandEyeSpec spec = testing::HandEyeTestSpec(delta, 0.2, first_seed + static_cast<uint64_t>(run));
      spec.tracker_noise_deg = noise_rad * 180 / M_PI;
      spec.tracker_noise = noise_length;
      spec.views = views;
      spec.view_jitter = jitter_ms * 1e-3;
      spec.rate_hz = rate_hz;
      const testing::HandEyeRecording r = testing::RecordHandEye(spec);
      HandEyeOptions options;
      options.instrumented_offset = estimator == "instrumented";
      const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views, options);
      HandEyeSolution at = s;
      if (s.tracker_noise) {
        rotation += s.tracker_noise->rotation.sigma / noise_rad / runs;
        translation += s.tracker_noise->translation.sigma / noise_length / runs;
        corners += s.tracker_noise->corner_px.sigma / noise_px / runs;
        if (true_noise) {
          at.tracker_noise->rotation.sigma = noise_rad;
          at.tracker_noise->translation.sigma = noise_length;
          at.tracker_noise->corner_px.sigma = noise_px;
        }
      } else {
        ++without_noise;
      }
      if (true_delta) at.time_offset = delta;
      std::vector<TrackedPose> motion = r.log;
      if (truth) {
        at.hmd_from_camera = testing::kHmdFromCamera;
        at.tracker_from_board = testing::kTrackerFromBoard;
        HandEyeSpec exact = spec;
        exact.tracker_noise_deg = exact.tracker_noise = 0;
        motion = testing::RecordHandEye(exact).log;
      }
      HandEyeBootstrap b = BootstrapHandEye(r.camera, motion, r.views, at, options, {replicates, 77 + static_cast<uint64_t>(run), 1});
      double variance = b.covariance(12, 12);
      if (envelope || curvature) {
        double sides = 0;
        for (const double side : {-1.0, 1.0}) {
          HandEyeSolution moved = at;
          moved.time_offset += side * std::sqrt(s.covariance(12, 12));
          const HandEyeBootstrap other = BootstrapHandEye(r.camera, motion, r.views, moved, options, {replicates, 77 + static_cast<uint64_t>(run), 1});
          sides += other.covariance(12, 12);
          if (envelope && other.covariance(12, 12) > variance) variance = other.covariance(12, 12);
        }
        if (curvature) variance = 2 * b.covariance(12, 12) - 0.5 * sides;
      }
      slope_excess += s.slope_excess / runs;
      concentration += s.report_phases.concentration / runs;
      if (larger) variance = std::max(variance, s.covariance(12, 12));
      error.push_back(s.time_offset - delta);
      sandwich.push_back(std::sqrt(s.covariance(12, 12)));
      boot_var.push_back(variance);
      bias.push_back(b.mean[12]);  // mean δ̂* less the bootstrap world's δ
    }
    const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    const double n = runs;
    std::vector<double> boot;  // σ's for the mean and the z's; a negative variance (curvature) counts as 0 there
    int negative = 0;
    for (double v : boot_var) {
      boot.push_back(std::sqrt(std::max(v, 0.0)));
      negative += v <= 0;
    }
    double mean_error = 0, spread = 0, mean_sandwich = 0, mean_boot = 0, boot_ms = 0, z_sandwich = 0, z_boot = 0, mean_bias = 0;
    for (int k = 0; k < runs; ++k) {
      mean_error += error[k] / n;
      mean_sandwich += sandwich[k] / n;
      mean_boot += boot[k] / n;
      boot_ms += boot_var[k] / n;
      z_sandwich += error[k] * error[k] / (sandwich[k] * sandwich[k]) / n;
      if (boot_var[k] > 0) z_boot += error[k] * error[k] / boot_var[k] / (n - negative);
      mean_bias += bias[k] / n;
    }
    for (double e : error) spread += (e - mean_error) * (e - mean_error) / (n - 1);
    const double e2_mean = spread * (n - 1) / n;
    double log_var = 0;
    for (int k = 0; k < runs; ++k) {
      const double e = error[k] - mean_error;
      const double u = e * e / e2_mean - boot_var[k] / boot_ms;
      log_var += u * u / (n - 1);
    }
    const double ratio_se = 0.5 * std::sqrt(log_var / n);  // relative
    spread = std::sqrt(spread);
    const double boot_rms = std::sqrt(boot_ms);
    const double ratio = spread / boot_rms;
    std::printf("%-5.3g %9.3f  %11.3f  %15.3f  %12.3f  %11.3f  %9.3f (%.3f)  %14.3f  %10.3f  %12.3f  %5.0f\n", s_fraction, spread * 1e3,
                mean_sandwich * 1e3, spread / mean_sandwich, mean_boot * 1e3, boot_rms * 1e3, ratio, ratio * ratio_se, std::sqrt(z_sandwich),
                std::sqrt(z_boot), mean_bias * 1e3, seconds);
    std::printf("      δ %s; centre %s, view jitter %g ms, tracker noise %g° and %g mm at %g Hz; mean estimated σ / truth's: rotation %.3f, translation %.3f, corners %.3f (over the %d of %d "
                "recordings with a noise estimate); %d bootstrap variances ≤ 0\n", estimator.c_str(), centre.c_str(), jitter_ms, noise_deg, noise_mm, rate_hz, rotation * runs / (runs - without_noise),
                translation * runs / (runs - without_noise), corners * runs / (runs - without_noise), runs - without_noise, runs, negative);
    std::printf("      mean slope excess N Ī⁻¹_δδ %.3f (over the views %.4f), mean report-phase concentration %.3f\n", slope_excess,
                slope_excess / views, concentration);
    // The shape of δ̂'s scatter: a Gaussian's robust spread (1.4826 MAD) equals its standard deviation,
    // its kurtosis is 3, and 4.55 % and 0.27 % of it lie beyond 2 and 3 σ.
    std::vector<double> centred;
    for (double e : error) centred.push_back(std::abs(e - mean_error));
    std::nth_element(centred.begin(), centred.begin() + runs / 2, centred.end());
    const double mad = 1.4826 * centred[runs / 2];
    double fourth = 0;
    int beyond2 = 0, beyond3 = 0;
    for (double e : error) {
      const double u = (e - mean_error) / spread;
      fourth += u * u * u * u / n;
      beyond2 += std::abs(u) > 2;
      beyond3 += std::abs(u) > 3;
    }
    std::printf("      robust spread (1.4826 MAD) %.3f ms = %.3f of the sandwich's; kurtosis %.2f; beyond 2 and 3 spreads %.2f %% and %.2f %%\n",
                mad * 1e3, mad / mean_sandwich, fourth, 100.0 * beyond2 / n, 100.0 * beyond3 / n);
    if (const char* dump = std::getenv("VSTCAL_MC_DUMP")) {  // one line a recording: δ̂ − δ and σ_δ (first order), in report intervals
      if (FILE* f = std::fopen(dump, "a")) {
        for (int k = 0; k < runs; ++k) std::fprintf(f, "%g %.6f %.6f\n", s_fraction, error[k] * rate_hz, sandwich[k] * rate_hz);
        std::fclose(f);
      }
    }
    std::fflush(stdout);
  }
  return 0;
}
