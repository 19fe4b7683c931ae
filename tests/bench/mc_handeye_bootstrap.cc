// The Monte Carlo behind docs/math/handeye.md#delta-bootstrap's table: recordings of
// handeye_noise_test's DeltaMonteCarlo (16 views, 0.05° and 0.2 mm a report, 0.2 px, every view at
// one fraction s of its report interval: δ = 30, 32.5, 35 ms), each solved and bootstrapped
// (BootstrapHandEye, B replicates); prints the spread of δ̂, the mean sandwich σ_δ, the bootstrap's
// mean and RMS σ_δ, the RMS z by each and the bootstrap's mean bias. Not a test: B solves per
// recording (~80 s of one core at the defaults), past what a test may take.
//
//   mc_handeye_bootstrap [recordings = 40] [replicates = 30] [first seed = 3000]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "support/handeye_scenes.h"
#include "vstcal/handeye/bootstrap.h"
#include "vstcal/handeye/refine.h"

int main(int argc, char** argv) {
  using namespace vstcal;
  const int runs = argc > 1 ? std::atoi(argv[1]) : 40;
  const int replicates = argc > 2 ? std::atoi(argv[2]) : 30;
  const uint64_t first_seed = argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 3000;
  if (runs < 2 || replicates < 2) {
    std::fprintf(stderr, "usage: mc_handeye_bootstrap [recordings ≥ 2] [replicates ≥ 2] [first seed]\n");
    return 2;
  }
  std::printf("s     spread_ms  sandwich_ms  spread/sandwich  boot_mean_ms  boot_rms_ms  spread/boot_rms  rms_z_sandwich  rms_z_boot  boot_bias_ms\n");
  for (const double delta : {0.030, 0.0325, 0.035}) {
    std::vector<double> error, sandwich, boot, bias;
    for (int run = 0; run < runs; ++run) {
      HandEyeSpec spec = testing::HandEyeTestSpec(delta, 0.2, first_seed + static_cast<uint64_t>(run));
      spec.tracker_noise_deg = 0.05;
      spec.tracker_noise = 0.2;
      spec.views = 16;
      const testing::HandEyeRecording r = testing::RecordHandEye(spec);
      const HandEyeSolution s = SolveHandEye(r.camera, r.log, r.views);
      const HandEyeBootstrap b = BootstrapHandEye(r.camera, r.log, r.views, s, {}, {replicates, 77 + static_cast<uint64_t>(run), 1});
      error.push_back(s.time_offset - delta);
      sandwich.push_back(std::sqrt(s.covariance(12, 12)));
      boot.push_back(std::sqrt(b.covariance(12, 12)));
      bias.push_back(b.mean[12]);
    }
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
    spread = std::sqrt(spread);
    const double boot_rms = std::sqrt(boot_ms);
    std::printf("%-5.3g %9.3f  %11.3f  %15.3f  %12.3f  %11.3f  %15.3f  %14.3f  %10.3f  %12.3f\n", (delta - 0.03) / 0.01, spread * 1e3,
                mean_sandwich * 1e3, spread / mean_sandwich, mean_boot * 1e3, boot_rms * 1e3, spread / boot_rms, std::sqrt(z_sandwich),
                std::sqrt(z_boot), mean_bias * 1e3);
    std::fflush(stdout);
  }
  return 0;
}
