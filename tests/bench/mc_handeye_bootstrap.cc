// The Monte Carlo behind docs/math/handeye.md#delta-bootstrap's table: recordings of
// handeye_noise_test's DeltaMonteCarlo (16 views, 0.05° and 0.2 mm a report, 0.2 px, every view at
// one fraction s of its report interval: δ = 30, 32.5, 35 ms), each solved and bootstrapped
// (BootstrapHandEye, B replicates); prints the spread of δ̂, the mean sandwich σ_δ, the bootstrap's
// mean and RMS σ_δ, the spread over the RMS with its standard error, the RMS z by each and the
// bootstrap's mean bias. Not a test: B + 1 solves per recording (~80 s of one core at the
// defaults), past what a test may take.
//
//   mc_handeye_bootstrap [recordings = 40] [replicates = 30] [first seed = 3000] [s = all: 0, 0.25, 0.5]
//                        [views = 16]
//
// The standard error of spread/RMS: the ratio is √(mean e² / mean σ_b²) over recordings (e = δ̂ − δ
// less its mean), so by the delta method Var log(ratio) = ¼ Var(e²/E e² − σ_b²/E σ_b²)/n, the
// covariance of a recording's e² and σ_b² included. The sample variance of B replicates is
// unbiased for the bootstrap's variance at any B ≥ 2, so B sets only σ_b²'s noise, not its mean.
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
  if (runs < 2 || replicates < 2 || views < 3 || fractions[0] < 0 || fractions[0] >= 1) {
    std::fprintf(stderr, "usage: mc_handeye_bootstrap [recordings ≥ 2] [replicates ≥ 2] [first seed] [s in [0, 1)] [views ≥ 3]\n");
    return 2;
  }
  std::printf("s     spread_ms  sandwich_ms  spread/sandwich  boot_mean_ms  boot_rms_ms  spread/boot_rms (se)  rms_z_sandwich  rms_z_boot  "
              "boot_bias_ms  cpu_s\n");
  for (const double s_fraction : fractions) {
    const double delta = 0.03 + 0.01 * s_fraction;  // the tracker reports every 10 ms, the views at s = 0 with δ = 30 ms
    const std::clock_t start = std::clock();  // CPU, not wall: the machine is shared
    std::vector<double> error, sandwich, boot, bias;
    for (int run = 0; run < runs; ++run) {
      HandEyeSpec spec = testing::HandEyeTestSpec(delta, 0.2, first_seed + static_cast<uint64_t>(run));
      spec.tracker_noise_deg = 0.05;
      spec.tracker_noise = 0.2;
      spec.views = views;
      const testing::HandEyeRecording r = testing::RecordHandEye(spec);
      const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
      const HandEyeBootstrap b = BootstrapHandEye(r.camera, r.log, r.views, s, {}, {replicates, 77 + static_cast<uint64_t>(run), 1});
      error.push_back(s.time_offset - delta);
      sandwich.push_back(std::sqrt(s.covariance(12, 12)));
      boot.push_back(std::sqrt(b.covariance(12, 12)));
      bias.push_back(b.mean[12]);
    }
    const double seconds = static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    const double n = runs;
    double mean_error = 0, spread = 0, mean_sandwich = 0, mean_boot = 0, boot_ms = 0, z_sandwich = 0, z_boot = 0, mean_bias = 0;
    for (int k = 0; k < runs; ++k) {
      mean_error += error[k] / n;
      mean_sandwich += sandwich[k] / n;
      mean_boot += boot[k] / n;
      boot_ms += boot[k] * boot[k] / n;
      z_sandwich += error[k] * error[k] / (sandwich[k] * sandwich[k]) / n;
      z_boot += error[k] * error[k] / (boot[k] * boot[k]) / n;
      mean_bias += bias[k] / n;
    }
    for (double e : error) spread += (e - mean_error) * (e - mean_error) / (n - 1);
    const double e2_mean = spread * (n - 1) / n;
    double log_var = 0;
    for (int k = 0; k < runs; ++k) {
      const double e = error[k] - mean_error;
      const double u = e * e / e2_mean - boot[k] * boot[k] / boot_ms;
      log_var += u * u / (n - 1);
    }
    const double ratio_se = 0.5 * std::sqrt(log_var / n);  // relative
    spread = std::sqrt(spread);
    const double boot_rms = std::sqrt(boot_ms);
    const double ratio = spread / boot_rms;
    std::printf("%-5.3g %9.3f  %11.3f  %15.3f  %12.3f  %11.3f  %9.3f (%.3f)  %14.3f  %10.3f  %12.3f  %5.0f\n", s_fraction, spread * 1e3,
                mean_sandwich * 1e3, spread / mean_sandwich, mean_boot * 1e3, boot_rms * 1e3, ratio, ratio * ratio_se, std::sqrt(z_sandwich),
                std::sqrt(z_boot), mean_bias * 1e3, seconds);
    std::fflush(stdout);
  }
  return 0;
}
