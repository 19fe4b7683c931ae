#include "vstcal/handeye/synthetic.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "vstcal/core/error.h"
#include "vstcal/random/philox.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// The camera's path in the board's frame: around the board's centre at about `distance`, turning
// by up to ~17° about each axis at incommensurate rates.
Rigid3d BoardFromCamera(const HandEyeSpec& s, double tau) {
  const double w = (s.grid_cols - 1) * s.spacing, h = (s.grid_rows - 1) * s.spacing, d = s.distance;
  const Eigen::Vector3d turn = s.one_axis ? Eigen::Vector3d(0, 0, 0.4 * std::sin(0.5 * tau + 2))
                                          : Eigen::Vector3d(0.25 * std::sin(0.7 * tau), 0.25 * std::sin(1.1 * tau + 1), 0.3 * std::sin(0.5 * tau + 2));
  return Rigid3d::FromRotvec(turn, Eigen::Vector3d(w / 2 + d / 6 * std::sin(0.6 * tau), h / 2 + d / 10 * std::sin(0.9 * tau),
                                                   -d + d / 7.5 * std::sin(0.4 * tau)));
}

}  // namespace

HandEyeRecording SynthesizeHandEye(const Camera& camera, const HandEyeSpec& s) {
  if (!(s.duration > 0 && s.rate_hz > 0 && s.spacing > 0 && s.distance > 0) || s.grid_cols < 2 || s.grid_rows < 2) {
    throw InputError("handeye: the duration, the tracker's rate, the spacing, the distance and the grid must be positive");
  }
  if (s.views < 2) throw InputError("views: a hand-eye recording needs at least 2 views");
  // Less than the views' spacing, so that they keep their order, and within the last 5 % of the
  // recording that follows the last view.
  if (!(s.view_jitter >= 0 && s.view_jitter < std::min(0.9 * s.duration / (s.views - 1), 0.05 * s.duration))) {
    throw InputError(VSTCAL_OPT("view_jitter") ": must be at least 0 and less than both the views' spacing (0.9 × duration / (views − 1)) "
                     "and 5 % of the duration; lower it");
  }
  if (s.duration * s.rate_hz > 1e6) throw InputError("duration × rate: more than 1,000,000 tracker reports; shorten the recording or lower the rate");
  // Deterministic draws keyed by (seed, stream, index): the same recording on every machine.
  const CounterRng tracker_rng(s.seed, 1), corner_rng(s.seed, 2);
  HandEyeRecording r;
  const auto reports = static_cast<int>(std::floor(s.duration * s.rate_hz + 1e-9));
  for (int k = 0; k <= reports; ++k) {
    const double tau = k / s.rate_hz;
    Rigid3d H = s.tracker_from_board * BoardFromCamera(s, tau) * s.hmd_from_camera.inverse();
    if (s.tracker_noise_deg > 0 || s.tracker_noise > 0) {
      const auto i = static_cast<uint64_t>(k);
      const auto a = tracker_rng.Normal2(i, 0), b = tracker_rng.Normal2(i, 1), c = tracker_rng.Normal2(i, 2);
      const Eigen::Vector3d w(a[0], a[1], b[0]), t(b[1], c[0], c[1]);
      H = Rigid3d{RotationFromRotvec(Eigen::Vector3d(w * (s.tracker_noise_deg * M_PI / 180))) * H.R, H.t + s.tracker_noise * t};
    }
    r.log.push_back({tau, H});
  }
  const ImageSize size = camera.image_size;
  // One camera's view at its true pose: the corners inside the image, with noise from `rng`.
  const auto view_of = [&](const Rigid3d& camera_from_board, const CounterRng& rng, int i, TimedView* v) {
    for (int row = 0; row < s.grid_rows; ++row) {
      for (int col = 0; col < s.grid_cols; ++col) {
        const Eigen::Vector3d P(s.spacing * col, s.spacing * row, 0);
        const uint64_t index = (static_cast<uint64_t>(i) * static_cast<uint64_t>(s.grid_rows) + static_cast<uint64_t>(row)) *
                                   static_cast<uint64_t>(s.grid_cols) + static_cast<uint64_t>(col);
        const auto draw = rng.Normal2(index, 0);
        const Eigen::Vector2d noise(draw[0], draw[1]);
        const auto q = camera.Project(camera_from_board * P);
        if (!q || q->x() < 1 || q->y() < 1 || q->x() > size.width - 2 || q->y() > size.height - 2) continue;
        v->observations.push_back({P, *q + s.noise_px * noise, 1.0});
      }
    }
  };
  const CounterRng right_rng(s.seed, 3), jitter_rng(s.seed, 4);
  const std::string prefix = s.right_from_left ? "left-frame-" : "frame-";
  for (int i = 0; i < s.views; ++i) {
    TimedView v;
    v.name = prefix + std::to_string(i);
    v.time = s.duration * (0.05 + 0.9 * i / (s.views - 1));
    if (s.view_jitter > 0) v.time += s.view_jitter * jitter_rng.Uniform2(static_cast<uint64_t>(i), 0)[0];
    const Rigid3d camera_from_board = BoardFromCamera(s, v.time + s.time_offset).inverse();
    if (s.right_from_left) {
      TimedView right{"right-frame-" + std::to_string(i), v.time, {}};
      const Rigid3d right_from_board = *s.right_from_left * camera_from_board;
      view_of(right_from_board, right_rng, i, &right);
      if (right.observations.size() >= 4) {
        r.right_views.push_back(std::move(right));
        r.right_camera_from_board.push_back(right_from_board);
      }
    }
    view_of(camera_from_board, corner_rng, i, &v);
    if (v.observations.size() >= 4) {
      r.views.push_back(std::move(v));
      r.camera_from_board.push_back(camera_from_board);
    }
  }
  if (r.views.size() < 2) throw InputError("handeye: fewer than 2 views see the board; move the camera farther (" VSTCAL_OPT("distance") ") or use a smaller board");
  return r;
}

}  // namespace vstcal
