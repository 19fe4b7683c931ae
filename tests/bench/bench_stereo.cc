// Binocular registration (issue 11 target: ≥ 20,000 binocular registrations/s on one core) beside
// OpenCV's solvePnP on the same frames, and PnP's cost against the number of points; the stereo
// solve (calib-stereo solve) beside cv::calibrateCamera ×2 + cv::stereoCalibrate on the same views.
//
// A "binocular registration" is one frame of `calib-stereo register`: the left pose from the
// tracked pixels, the right pose by composition (or its own PnP, or the joint solve), and the 8
// virtual points projected into both images. The OpenCV rows do the same work with OpenCV:
// solvePnP on the left pixels, composition with the rig, cv::projectPoints into both images.
#include <benchmark/benchmark.h>

#include <map>

#include <Eigen/Core>  // before opencv2/core/eigen.hpp, which needs it
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>

#include "support/opencv_views.h"
#include "support/scenes.h"
#include "support/stereo_rigs.h"
#include "vstcal/camera/opencv_distortion.h"
#include "vstcal/random/philox.h"
#include "vstcal/estimators/pnp.h"
#include "vstcal/estimators/pose_refine.h"
#include "vstcal/stereo/registration.h"
#include "vstcal/stereo/registration_accuracy.h"
#include "vstcal/calib/stereo_solve.h"
#include "vstcal/stereo/synthetic_tracks.h"

namespace {

using namespace vstcal;

// 1,000 frames of a ZED-like rig (distorted lenses) 1 m from seed 000's four coplanar points
// (range 0) or six points in space (range 1), 0.3 px noise.
struct Sequence {
  StereoRig rig = testing::ZedLikeRig();
  Tracks tracks;
  std::vector<Eigen::Vector3d> embedded, virtual_points;
};

Sequence MakeSequence(bool planar) {
  Sequence s;
  s.tracks = SyntheticTracks(s.rig, {.frames = 1000, .noise_px = 0.3, .seed = 1, .planar = planar});
  for (const auto& p : s.tracks.embedded) s.embedded.push_back(p.point_in_world);
  for (const auto& p : s.tracks.virtual_points) s.virtual_points.push_back(p.point_in_world);
  return s;
}

const Sequence& SequenceOf(bool planar) {
  static const Sequence planar_sequence = MakeSequence(true), spatial_sequence = MakeSequence(false);
  return planar ? planar_sequence : spatial_sequence;
}

void Register(benchmark::State& state, RegistrationMode mode, bool warm) {
  const Sequence& s = SequenceOf(state.range(0) == 0);
  std::optional<Rigid3d> previous;
  size_t k = 0, failed = 0;
  for (auto _ : state) {
    const TrackedFrame& frame = s.tracks.frames[k];
    const FrameRegistration r = RegisterFrame(s.rig, s.embedded, frame, s.virtual_points, mode, warm ? previous : std::nullopt);
    failed += r.status != PoseStatus::kOk;
    previous = r.left_from_world;
    benchmark::DoNotOptimize(r);
    if (++k == s.tracks.frames.size()) k = 0, previous.reset();
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["failed"] = static_cast<double>(failed);
}

void BM_RegisterLeft(benchmark::State& state) { Register(state, RegistrationMode::kLeft, false); }
void BM_RegisterLeftWarm(benchmark::State& state) { Register(state, RegistrationMode::kLeft, true); }
void BM_RegisterPerEye(benchmark::State& state) { Register(state, RegistrationMode::kPerEye, false); }
void BM_RegisterJoint(benchmark::State& state) { Register(state, RegistrationMode::kJoint, false); }

struct OpenCvRig {
  cv::Mat K1, D1, K2, D2;
  Rigid3d right_from_left;
  explicit OpenCvRig(const StereoRig& rig) {
    cv::eigen2cv(rig.left.camera.K(), K1);
    cv::eigen2cv(rig.right.camera.K(), K2);
    D1 = cv::Mat(OpenCvDistortion(rig.left.camera, 5), true);
    D2 = cv::Mat(OpenCvDistortion(rig.right.camera, 5), true);
    right_from_left = rig.right_from_left;
  }
};

// The same frame's work with OpenCV: solvePnP (method `flags`, optionally from the previous pose),
// composition with the rig, projectPoints into both images.
void OpenCv(benchmark::State& state, int flags, bool warm) {
  const Sequence& s = SequenceOf(state.range(0) == 0);
  const OpenCvRig cv_rig(s.rig);
  std::vector<cv::Point3d> virtual_points;
  for (const auto& p : s.virtual_points) virtual_points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<cv::Point3d>> objects;
  std::vector<std::vector<cv::Point2d>> images;
  for (const TrackedFrame& f : s.tracks.frames) {
    objects.emplace_back();
    images.emplace_back();
    for (size_t i = 0; i < f.left.size(); ++i) {
      if (!f.left[i]) continue;
      objects.back().emplace_back(s.embedded[i].x(), s.embedded[i].y(), s.embedded[i].z());
      images.back().emplace_back(f.left[i]->x(), f.left[i]->y());
    }
  }
  size_t k = 0, failed = 0;
  cv::Mat rvec, tvec;
  bool have_previous = false;
  std::vector<cv::Point2d> left_px, right_px;
  for (auto _ : state) {
    const bool ok = cv::solvePnP(objects[k], images[k], cv_rig.K1, cv_rig.D1, rvec, tvec, warm && have_previous, flags);
    failed += !ok;
    const Rigid3d left_from_world = Rigid3d::FromRotvec(Eigen::Vector3d(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2)),
                                                        Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
    const Rigid3d right_from_world = cv_rig.right_from_left * left_from_world;
    const Eigen::Vector3d r = RotvecFromRotation(right_from_world.R);
    cv::projectPoints(virtual_points, rvec, tvec, cv_rig.K1, cv_rig.D1, left_px);
    cv::projectPoints(virtual_points, cv::Vec3d(r.x(), r.y(), r.z()),
                      cv::Vec3d(right_from_world.t.x(), right_from_world.t.y(), right_from_world.t.z()), cv_rig.K2, cv_rig.D2, right_px);
    benchmark::DoNotOptimize(right_px.data());
    have_previous = ok;
    if (++k == objects.size()) k = 0, have_previous = false;
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
  state.counters["failed"] = static_cast<double>(failed);
}

void BM_OpenCvIterative(benchmark::State& state) { OpenCv(state, cv::SOLVEPNP_ITERATIVE, false); }
void BM_OpenCvIterativeWarm(benchmark::State& state) { OpenCv(state, cv::SOLVEPNP_ITERATIVE, true); }
void BM_OpenCvEpnp(benchmark::State& state) { OpenCv(state, cv::SOLVEPNP_EPNP, false); }
void BM_OpenCvIppe(benchmark::State& state) { OpenCv(state, cv::SOLVEPNP_IPPE, false); }

// Mono PnP (closed form + refinement) on N points spread in a box 1 m away, 0.3 px noise: how
// the cost grows with the number of points; OpenCV's SOLVEPNP_ITERATIVE on the same points (it
// needs 6 points or more when they are not coplanar: from 8).
struct Points {
  Camera camera = testing::ZedLikeRig().left.camera;
  std::vector<Eigen::Vector3d> world;
  std::vector<Eigen::Vector2d> pixels;
};

Points PointsOf(int n) {
  Points p;
  const Rigid3d pose = Rigid3d::FromRotvec(Eigen::Vector3d(0.2, -0.1, 0.05), Eigen::Vector3d(20, -10, 1000));
  const CounterRng rng(7, 0);
  for (int i = 0; i < n; ++i) {
    const auto a = rng.Uniform2(static_cast<uint64_t>(i), 0), b = rng.Uniform2(static_cast<uint64_t>(i), 1);
    const auto g = rng.Normal2(static_cast<uint64_t>(i), 2);
    p.world.emplace_back((a[0] - 0.5) * 600, (a[1] - 0.5) * 400, (b[0] - 0.5) * 400);
    p.pixels.push_back(*p.camera.Project(pose * p.world.back()) + 0.3 * Eigen::Vector2d(g[0], g[1]));
  }
  return p;
}

void BM_PnpPoints(benchmark::State& state) {
  const Points p = PointsOf(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const ClosedFormPose start = SolvePnpClosedForm(p.camera, p.world, p.pixels);
    const PoseObservations set{&p.camera, Rigid3d::Identity(), p.world, p.pixels};
    const PoseRefinement r = RefinePose({&set, 1}, start.camera_from_world);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

void BM_OpenCvPnpPoints(benchmark::State& state) {
  const Points p = PointsOf(static_cast<int>(state.range(0)));
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (size_t i = 0; i < p.world.size(); ++i) {
    object.emplace_back(p.world[i].x(), p.world[i].y(), p.world[i].z());
    image.emplace_back(p.pixels[i].x(), p.pixels[i].y());
  }
  cv::Mat K, rvec, tvec;
  cv::eigen2cv(p.camera.K(), K);
  const cv::Mat D(OpenCvDistortion(p.camera, 5), true);
  for (auto _ : state) {
    cv::solvePnP(object, image, K, D, rvec, tvec, false, cv::SOLVEPNP_ITERATIVE);
    benchmark::DoNotOptimize(tvec.data);
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}

// N views (the argument) of the 9×6 board by the ZED-like rig with k3 = 0, 0.3 px noise.
const testing::StereoViews& StereoViewsOf(int n) {
  static std::map<int, testing::StereoViews> cache;
  auto it = cache.find(n);
  if (it == cache.end()) {
    StereoRig rig = testing::ZedLikeRig();
    rig.left.camera.params.back() = rig.right.camera.params.back() = 0;
    testing::StereoViews v = testing::SyntheticStereoViews(rig, n, 21);
    v.left = testing::WithNoise(v.left, 0.3, 1);
    v.right = testing::WithNoise(v.right, 0.3, 2);
    it = cache.emplace(n, std::move(v)).first;
  }
  return it->second;
}

// The whole solve: both cameras calibrated alone, the rotation average, the joint refinement and
// the covariance.
void BM_StereoSolve(benchmark::State& state) {
  const testing::StereoViews& v = StereoViewsOf(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const StereoSolveResult r = SolveStereo(v.left, v.right, StereoSolveOptions{});
    if (r.exit_code != ExitCode::kOk) state.SkipWithError(r.message.c_str());
    benchmark::DoNotOptimize(r.rig.right_from_left.t.data());
  }
}

// OpenCV's equivalent: each camera calibrated (k1, k2, p1, p2), then stereoCalibrate from those
// intrinsics refining everything together (its covariance is not computed: OpenCV has none).
void BM_OpenCvStereoCalibrate(benchmark::State& state) {
  const testing::StereoViews& v = StereoViewsOf(static_cast<int>(state.range(0)));
  // OpenCV needs the same object points in both cameras: every corner of these views is in both images.
  const testing::OpenCvViews l = testing::ToOpenCvViews(v.left), r = testing::ToOpenCvViews(v.right);
  for (size_t k = 0; k < l.object.size(); ++k) {
    if (l.object[k] != r.object[k]) state.SkipWithError("a corner is outside one camera's image");
  }
  const cv::Size size(v.left.image_size.width, v.left.image_size.height);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-10);
  for (auto _ : state) {
    cv::Mat K1, D1, K2, D2, R, T, E, F;
    std::vector<cv::Mat> rvecs, tvecs;
    cv::calibrateCamera(l.object, l.image, size, K1, D1, rvecs, tvecs, cv::CALIB_FIX_K3, criteria);
    cv::calibrateCamera(r.object, r.image, size, K2, D2, rvecs, tvecs, cv::CALIB_FIX_K3, criteria);
    cv::stereoCalibrate(l.object, l.image, r.image, K1, D1, K2, D2, size, R, T, E, F,
                        cv::CALIB_USE_INTRINSIC_GUESS | cv::CALIB_FIX_K3, criteria);
    benchmark::DoNotOptimize(T.data);
  }
}

}  // namespace

BENCHMARK(BM_StereoSolve)->Arg(13)->Arg(100)->Arg(500)->Unit(benchmark::kMillisecond);
// OpenCV solves the views densely (6 unknowns a view in one Levenberg–Marquardt system): 100 views
// take 20 s, 500 would take most of an hour, so 500 is not run.
BENCHMARK(BM_OpenCvStereoCalibrate)->Arg(13)->Arg(100)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RegisterLeft)->Arg(0)->Arg(1);
BENCHMARK(BM_RegisterLeftWarm)->Arg(0)->Arg(1);
BENCHMARK(BM_RegisterPerEye)->Arg(0)->Arg(1);
BENCHMARK(BM_RegisterJoint)->Arg(0)->Arg(1);
BENCHMARK(BM_OpenCvIterative)->Arg(0)->Arg(1);
BENCHMARK(BM_OpenCvIterativeWarm)->Arg(0)->Arg(1);
BENCHMARK(BM_OpenCvEpnp)->Arg(0)->Arg(1);
BENCHMARK(BM_OpenCvIppe)->Arg(0);
BENCHMARK(BM_PnpPoints)->Arg(4)->Arg(8)->Arg(16)->Arg(64)->Arg(256)->Arg(1024);
BENCHMARK(BM_OpenCvPnpPoints)->Arg(8)->Arg(16)->Arg(64)->Arg(256)->Arg(1024);
BENCHMARK_MAIN();
