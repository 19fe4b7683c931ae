#include "vstcal/calib/stereo_solve.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <set>
#include <tuple>

#include "vstcal/estimators/arrow_information.h"
#include "vstcal/estimators/free_intrinsics.h"
#include "vstcal/estimators/linear_manifold.h"
#include "vstcal/estimators/reprojection_cost.h"
#include "vstcal/estimators/chained_reprojection_cost.h"
#include "vstcal/scene/epipolar.h"
#include "vstcal/geometry/rotation_average.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

// The key of a board pose: the view's name (planar views) or the one world frame (volume).
std::string PoseKey(const Correspondences& c, const View& v) { return c.rig == Rig::kVolume ? std::string() : v.name; }

// One camera's part of the joint problem: its correspondences, the pose each view uses, and its
// lens (θ in the whole layout, moved along `free`; nothing free when held).
struct Side {
  const Correspondences* c = nullptr;
  std::vector<int> pose_of_view;
  AnyLensModel model;
  std::vector<double> params;
  FreeIntrinsics free;
};

// A camera calibrated alone: its intrinsics and camera_from_board per pose key.
struct Solo {
  Camera camera;
  Correspondences used;
  std::map<std::string, Rigid3d> camera_from_pose;
};

std::optional<Solo> CalibrateAlone(const Correspondences& c, const StereoSolveOptions& options, const std::string& file,
                                   StereoSolveResult* out) {
  CalibrationOptions calibration = options.calibration;
  calibration.refine = true;
  CalibrationResult r = Calibrate(c, calibration);
  if (r.exit_code != ExitCode::kOk) {
    out->exit_code = r.exit_code;
    out->message = file + ": calibrating this camera alone (the start of the joint solve) failed: " + r.message;
    return std::nullopt;
  }
  Solo solo;
  solo.camera = r.camera.camera;
  solo.used = std::move(r.used);
  if (solo.used.rig == Rig::kVolume) {
    solo.camera_from_pose[""] = *r.camera.camera_from_world;
  } else {
    for (size_t v = 0; v < solo.used.views.size(); ++v) solo.camera_from_pose[solo.used.views[v].name] = r.camera.views[v].camera_from_board;
  }
  for (const std::string& w : r.warnings) out->notes.push_back(file + ": " + w);
  return solo;
}

void CheckInputs(const Correspondences& left, const Correspondences& right, const StereoSolveOptions& options,
                 const std::string& left_file, const std::string& right_file) {
  if (left.length_unit != right.length_unit) {
    throw InputError(left_file + " and " + right_file + ": length_unit differs (" + std::string(LengthUnitName(left.length_unit)) +
                     " vs " + std::string(LengthUnitName(right.length_unit)) +
                     "); both cameras must see the same target in one unit: convert one file");
  }
  if (options.calibration.refinement.loss != RefineOptions::Loss::kNone) {
    throw InputError(VSTCAL_OPT("loss") ": the joint stereo solve is least squares; drop " VSTCAL_OPT("loss") " (outliers are listed by calib-tsai on each "
                     "camera's file)");
  }
  if (left.rig != right.rig) {
    throw InputError(left_file + " and " + right_file + ": rig differs (one planar-views, one volume); both files must "
                     "describe the same target poses");
  }
  for (const auto& [c, file] : {std::pair{&left, &left_file}, std::pair{&right, &right_file}}) {
    std::set<std::string> names;
    for (const View& v : c->views) {
      if (c->rig == Rig::kPlanarViews && !names.insert(v.name).second) {
        throw InputError(*file + ": views: two views have the key \"" + v.name + "\"; views are matched between the cameras by "
                         "name (or by their " VSTCAL_OPT("match_views") " key), so each must be unique");
      }
    }
  }
  const auto check_size = [](const std::optional<Camera>& camera, const Correspondences& c, const std::string& file) {
    if (camera && (camera->image_size.width != c.image_size.width || camera->image_size.height != c.image_size.height)) {
      throw InputError(file + ": image_size " + std::to_string(c.image_size.width) + "x" + std::to_string(c.image_size.height) +
                       " differs from the given camera's " + std::to_string(camera->image_size.width) + "x" +
                       std::to_string(camera->image_size.height) + "; give the camera calibrated at this resolution");
    }
  };
  check_size(options.left_camera, left, left_file);
  check_size(options.right_camera, right, right_file);
}

Side MakeSide(const Solo& solo, const std::optional<Camera>& given, bool hold, const RefineOptions& refinement,
              const std::map<std::string, int>& pose_index) {
  Side s;
  s.c = &solo.used;
  const Camera& start = given ? *given : solo.camera;
  s.model = hold ? start.model : RefinedModel(start.model, refinement);
  s.params = PromotedParams(start, s.model);
  if (!hold) s.free = MakeFreeIntrinsics(s.model, refinement);
  for (const View& v : solo.used.views) s.pose_of_view.push_back(pose_index.at(PoseKey(solo.used, v)));
  return s;
}

// The problem's variables: each side's θ, δ_rl and one δ per pose around reference values.
struct Variables {
  Rigid3d right_from_left;
  std::vector<Rigid3d> left_from_pose;
  std::array<double, 6> delta_rl{};
  std::vector<std::array<double, 6>> delta_pose;

  void Recentre() {
    const auto apply = [](const Rigid3d& T, std::array<double, 6>& d) {
      const Rigid3d out = PerturbLeft(T, Eigen::Vector3d(d[0], d[1], d[2]), Eigen::Vector3d(d[3], d[4], d[5]));
      d.fill(0.0);
      return out;
    };
    right_from_left = apply(right_from_left, delta_rl);
    for (size_t i = 0; i < left_from_pose.size(); ++i) left_from_pose[i] = apply(left_from_pose[i], delta_pose[i]);
  }
};

void AddSide(ceres::Problem* problem, Side* s, Variables* x, bool right) {
  std::visit(
      [&](auto model) {
        using Model = decltype(model);
        for (size_t v = 0; v < s->c->views.size(); ++v) {
          const int pose = s->pose_of_view[v];
          const auto& obs = s->c->views[v].observations;
          if (obs.empty()) continue;
          if (right) {
            problem->AddResidualBlock(new ChainedReprojectionCost<Model>(obs, x->right_from_left, x->left_from_pose[pose]), nullptr,
                                      s->params.data(), x->delta_rl.data(), x->delta_pose[pose].data());
          } else {
            problem->AddResidualBlock(new ReprojectionCost<Model>(obs, x->left_from_pose[pose]), nullptr, s->params.data(),
                                      x->delta_pose[pose].data());
          }
        }
      },
      s->model);
  if (s->free.size() == 0) {
    problem->SetParameterBlockConstant(s->params.data());
  } else {
    problem->SetManifold(s->params.data(), new LinearManifold(s->free.basis));
  }
}

// Rows of every observation of one side into the arrow at δ = 0 (the costs apply √w). Globals:
// [β_left | β_right | δ_rl]. Points behind a camera are left out.
void AddInformation(const Side& s, const Variables& x, bool right, int first_column, int rl_column, ArrowInformation* info) {
  const int m = s.free.size();
  std::vector<int> columns(static_cast<size_t>(m));
  std::iota(columns.begin(), columns.end(), first_column);
  if (right) {
    for (int k = 0; k < 6; ++k) columns.push_back(rl_column + k);
  }
  const int g = static_cast<int>(columns.size());
  std::visit(
      [&](auto model) {
        using Model = decltype(model);
        Eigen::Matrix<double, 2, Model::kNumParams, Eigen::RowMajor> d_params;
        Eigen::Matrix<double, 2, 6, Eigen::RowMajor> d_rl, d_pose;
        for (size_t v = 0; v < s.c->views.size(); ++v) {
          const int pose = s.pose_of_view[v];
          const auto& obs = s.c->views[v].observations;
          Eigen::MatrixXd J(2 * static_cast<Eigen::Index>(obs.size()), g + 6);
          Eigen::Index rows = 0;
          const auto add = [&](bool ok) {
            if (!ok) return;
            if (m > 0) J.block(rows, 0, 2, m) = d_params * s.free.basis;
            if (right) J.block<2, 6>(rows, m) = d_rl;
            J.block<2, 6>(rows, g) = d_pose;
            rows += 2;
          };
          double r[2];
          if (right) {
            const ChainedReprojectionCost<Model> cost(obs, x.right_from_left, x.left_from_pose[pose]);
            for (size_t k = 0; k < obs.size(); ++k) {
              add(cost.EvaluatePointAtReference(k, s.params.data(), r, d_params.data(), d_rl.data(), d_pose.data()));
            }
          } else {
            const ReprojectionCost<Model> cost(obs, x.left_from_pose[pose]);
            for (size_t k = 0; k < obs.size(); ++k) add(cost.EvaluatePointAtReference(k, s.params.data(), r, d_params.data(), d_pose.data()));
          }
          if (rows > 0) info->AddRows(columns, pose, J.topRows(rows));
        }
      },
      s.model);
}

// Σ w |r|² and the number of points that project, over one side at the optimum.
struct SideResiduals {
  double weighted_sum = 0, sum = 0;
  size_t n = 0;
};
SideResiduals Residuals(const Camera& camera, const Side& s, const std::vector<Rigid3d>& camera_from_pose) {
  SideResiduals out;
  for (size_t v = 0; v < s.c->views.size(); ++v) {
    for (const Observation& o : s.c->views[v].observations) {
      const auto q = camera.Project(camera_from_pose[s.pose_of_view[v]] * o.point);
      if (!q) continue;
      const double r2 = (*q - o.pixel).squaredNorm();
      out.weighted_sum += o.weight * r2;
      out.sum += r2;
      ++out.n;
    }
  }
  return out;
}

// Symmetric epipolar distance of matched pixels (docs/math/stereo.md#epipolar): each pixel's
// distance to the other's epipolar line on the normalized plane, times its camera's mean focal
// length, averaged over the two. Points match when their target coordinates are equal.
std::optional<StereoViewFit> EpipolarFit(const StereoRig& rig, const View& left, const View& right) {
  std::map<std::tuple<double, double, double>, Eigen::Vector2d> right_pixels;
  for (const Observation& o : right.observations) right_pixels[{o.point.x(), o.point.y(), o.point.z()}] = o.pixel;
  const Eigen::Matrix3d E = EssentialMatrix(rig.right_from_left);
  const Camera& cl = rig.left.camera;
  const Camera& cr = rig.right.camera;
  using namespace intrinsic;
  const double fl = 0.5 * (cl.params[kFx] + cl.params[kFy]), fr = 0.5 * (cr.params[kFx] + cr.params[kFy]);
  std::vector<Eigen::Vector2d> distances;
  for (const Observation& o : left.observations) {
    const auto it = right_pixels.find({o.point.x(), o.point.y(), o.point.z()});
    if (it == right_pixels.end()) continue;
    const auto xl = cl.Unproject(o.pixel);
    const auto xr = cr.Unproject(it->second);
    if (!xl || !xr) continue;
    const Eigen::Vector3d line_r = E * *xl, line_l = E.transpose() * *xr;
    const double algebraic = std::abs(xr->dot(line_r));
    const double d = 0.5 * (fr * algebraic / line_r.head<2>().norm() + fl * algebraic / line_l.head<2>().norm());
    distances.emplace_back(d, 0.0);
  }
  if (distances.empty()) return std::nullopt;
  return StereoViewFit{left.name, Summarize(distances)};
}

StereoFit ComputeEpipolarFit(const StereoRig& rig, const Correspondences& left, const Correspondences& right) {
  StereoFit fit;
  std::map<std::string, const View*> right_views;
  for (const View& v : right.views) right_views[v.name] = &v;
  std::vector<Eigen::Vector2d> all;
  double sum_squares = 0;
  for (const View& v : left.views) {
    const auto it = right_views.find(v.name);
    if (it == right_views.end()) continue;
    if (auto view = EpipolarFit(rig, v, *it->second)) {
      sum_squares += view->epipolar.rms_px * view->epipolar.rms_px * static_cast<double>(view->epipolar.n_points);
      fit.epipolar.max_px = std::max(fit.epipolar.max_px, view->epipolar.max_px);
      fit.epipolar.n_points += view->epipolar.n_points;
      fit.views.push_back(std::move(*view));
    }
  }
  if (fit.epipolar.n_points > 0) fit.epipolar.rms_px = std::sqrt(sum_squares / static_cast<double>(fit.epipolar.n_points));
  return fit;
}

CalibratedCamera RigCamera(const std::string& name, const Side& s, LengthUnit unit, const Eigen::MatrixXd& free_covariance) {
  CalibratedCamera c;
  c.name = name;
  c.camera.image_size = s.c->image_size;
  c.camera.model = s.model;
  c.camera.params = s.params;
  c.length_unit = unit;
  c.method = "stereo-solve";
  if (s.free.size() > 0 && free_covariance.size() > 0) {
    const Eigen::MatrixXd B = s.free.MovedBasis();
    ParameterCovariance cov;
    cov.parameters = s.free.MovedParams(s.model);
    cov.matrix = B * free_covariance * B.transpose();
    cov.matrix = (0.5 * (cov.matrix + cov.matrix.transpose())).eval();
    c.covariance = std::move(cov);
  }
  return c;
}

std::string List(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

}  // namespace

StereoSolveResult SolveStereo(Correspondences left, Correspondences right, const StereoSolveOptions& options,
                              const std::string& left_file, const std::string& right_file) {
  StereoSolveResult out;
  std::optional<ViewPairing> pairing;
  if (!options.view_key_pattern.empty()) {
    pairing = ViewPairing{options.view_key_pattern, ""};
  } else if (left.rig == Rig::kPlanarViews && !ShareAName(ViewNames(left), ViewNames(right))) {
    // No name in common: pair by the number in the names when they differ only by a left/right token.
    const DerivedPairing derived = DeriveViewPairing(ViewNames(left), ViewNames(right));
    if (!derived.pairing) {
      throw InputError(left_file + " and " + right_file + ": views: no view name is in both files and they cannot be paired by themselves: " +
                       derived.problem + "; " +
                       (derived.suggestion.empty() ? std::string("give " VSTCAL_OPT("match_views") " with a group that takes the key both names share, e.g. '([0-9]+)$'")
                                                   : "pair them by the number in their names with " VSTCAL_OPT("match_views") " '" + derived.suggestion + "'"));
    }
    pairing = derived.pairing;
    out.notes.push_back("paired " + std::to_string(derived.paired) + " views by themselves: " + pairing->rule + ", as " VSTCAL_OPT("match_views") " '" +
                        pairing->match_views + "'; the rig keeps this rule");
  }
  if (pairing) {
    KeyViews(pairing->match_views, left_file, &left);
    KeyViews(pairing->match_views, right_file, &right);
  }
  CheckInputs(left, right, options, left_file, right_file);
  out.rig.view_pairing = pairing;
  std::optional<Solo> solo_left = CalibrateAlone(left, options, left_file, &out);
  if (!solo_left) return out;
  std::optional<Solo> solo_right = CalibrateAlone(right, options, right_file, &out);
  if (!solo_right) return out;

  // Board poses: the union of both cameras' pose keys, in the left file's order then the right's.
  std::vector<std::string> keys;
  std::map<std::string, int> pose_index;
  for (const Solo* s : {&*solo_left, &*solo_right}) {
    for (const View& v : s->used.views) {
      const std::string key = PoseKey(s->used, v);
      if (pose_index.emplace(key, static_cast<int>(keys.size())).second) keys.push_back(key);
    }
  }
  std::vector<Eigen::Matrix3d> relative_rotations;
  std::vector<std::pair<Rigid3d, Rigid3d>> common_poses;  // left_from_board, right_from_board
  for (const std::string& key : keys) {
    const auto l = solo_left->camera_from_pose.find(key), r = solo_right->camera_from_pose.find(key);
    const bool in_left = l != solo_left->camera_from_pose.end(), in_right = r != solo_right->camera_from_pose.end();
    if (in_left && in_right) {
      out.common_views.push_back(key);
      relative_rotations.push_back(r->second.R * l->second.R.transpose());
      common_poses.emplace_back(l->second, r->second);
    } else {
      (in_left ? out.left_only_views : out.right_only_views).push_back(key);
    }
  }
  if (left.rig == Rig::kVolume) out.common_views = {"world"};
  const size_t needed = left.rig == Rig::kVolume ? 1 : options.min_common_views;
  if (common_poses.size() < needed) {
    out.exit_code = ExitCode::kDegenerate;
    out.message = left_file + " and " + right_file + ": " + std::to_string(common_poses.size()) +
                  " usable views are seen by both cameras (matched by name" +
                  (common_poses.empty() ? std::string() : ": " + List(out.common_views)) + "); right_from_left needs at least " +
                  std::to_string(needed) + ": capture the board in view of both cameras, or name the views alike";
    return out;
  }
  if (!out.left_only_views.empty()) {
    out.notes.push_back(std::to_string(out.left_only_views.size()) + " views seen by the left camera only (" +
                        List(out.left_only_views) + "): used for its intrinsics");
  }
  if (!out.right_only_views.empty()) {
    out.notes.push_back(std::to_string(out.right_only_views.size()) + " views seen by the right camera only (" +
                        List(out.right_only_views) + "): used for its intrinsics");
  }

  // The start (docs/math/stereo.md#rotation-average): the geodesic L1 mean of R_r,v R_l,vᵀ, then
  // t = mean(t_r,v − R t_l,v).
  Variables x;
  out.initial_rotation = GeodesicL1MeanRotation(relative_rotations);
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  for (const auto& [l, r] : common_poses) t += r.t - out.initial_rotation * l.t;
  x.right_from_left = Rigid3d{out.initial_rotation, t / static_cast<double>(common_poses.size())};
  for (const std::string& key : keys) {
    const auto l = solo_left->camera_from_pose.find(key);
    x.left_from_pose.push_back(l != solo_left->camera_from_pose.end() ? l->second
                                                                       : x.right_from_left.inverse() * solo_right->camera_from_pose.at(key));
  }
  x.delta_pose.assign(keys.size(), std::array<double, 6>{});

  const RefineOptions& refinement = options.calibration.refinement;
  Side sl = MakeSide(*solo_left, options.left_camera, options.hold_left, refinement, pose_index);
  Side sr = MakeSide(*solo_right, options.right_camera, options.hold_right, refinement, pose_index);
  const size_t n = NumObservations(solo_left->used) + NumObservations(solo_right->used);
  const int free = sl.free.size() + sr.free.size() + 6 + 6 * static_cast<int>(keys.size());
  if (2 * n <= static_cast<size_t>(free)) {
    out.exit_code = ExitCode::kDegenerate;
    out.message = left_file + " and " + right_file + ": " + std::to_string(n) + " points give " + std::to_string(2 * n) +
                  " residuals for " + std::to_string(free) + " free parameters; add views or hold a camera (" VSTCAL_OPT("hold_left") ")";
    return out;
  }

  // The joint problem: every board pose in the first elimination group, the globals last, so the
  // reduced system is the intrinsics' and right_from_left's alone, whatever the number of views.
  // Each global has a group of its own: Ceres orders the blocks of one group by their addresses,
  // and these three are separate allocations, so in one group the reduced system's block order —
  // and the last digits of the solution — followed the heap's layout (an input path one character
  // longer changed fx in its 16th digit). The board poses are one array, in view order.
  ceres::Problem problem;
  AddSide(&problem, &sl, &x, false);
  AddSide(&problem, &sr, &x, true);
  ceres::Solver::Options solver;
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  for (auto& d : x.delta_pose) ordering->AddElementToGroup(d.data(), 0);
  int group = 1;
  for (double* global : {sl.params.data(), sr.params.data(), x.delta_rl.data()}) ordering->AddElementToGroup(global, group++);
  solver.linear_solver_type = ceres::DENSE_SCHUR;
  solver.linear_solver_ordering = ordering;
  solver.max_num_iterations = refinement.max_iterations;
  // The tolerances and strategy of the single-camera refinement (calib/refine.cc says why).
  solver.function_tolerance = 1e-10;
  solver.parameter_tolerance = 1e-10;
  solver.gradient_tolerance = 1e-14;
  solver.num_threads = 1;
  solver.trust_region_strategy_type = ceres::DOGLEG;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  if (summary.termination_type != ceres::CONVERGENCE) {
    out.exit_code = ExitCode::kDegenerate;
    out.message = left_file + " and " + right_file + ": the joint refinement " +
                  (summary.termination_type == ceres::NO_CONVERGENCE ? "did not converge in " + std::to_string(refinement.max_iterations) +
                                                                          " iterations"
                                                                    : "failed: " + summary.message) +
                  "; check that both files hold the same target poses under the same view names";
    return out;
  }
  x.Recentre();

  // One camera's views given for both (two copies of one file) solve to cameras at one place, a
  // baseline at the solver's tolerance: no rig. Compared with the board's distance, so that the
  // test does not depend on the length unit.
  double distance = 0;
  for (const Rigid3d& T : x.left_from_pose) distance = std::max(distance, T.t.norm());
  if (!(x.right_from_left.t.norm() > 1e-9 * distance)) {
    char numbers[160];
    std::snprintf(numbers, sizeof numbers, "baseline %.3g %s, the board %.3g %s away", x.right_from_left.t.norm(),
                  std::string(LengthUnitName(left.length_unit)).c_str(), distance,
                  std::string(LengthUnitName(left.length_unit)).c_str());
    out.exit_code = ExitCode::kDegenerate;
    out.message = left_file + " and " + right_file + ": the solved cameras coincide (" + numbers +
                  "): both files hold one camera's views; give the left camera's correspondences, then the right camera's";
    return out;
  }

  StereoRig& rig = out.rig;
  rig.length_unit = left.length_unit;
  rig.method = "stereo-solve";
  rig.right_from_left = x.right_from_left;

  // σ̂ over both cameras' points, and the covariance of the globals from the same information.
  std::vector<Rigid3d> right_from_pose;
  for (const Rigid3d& T : x.left_from_pose) right_from_pose.push_back(x.right_from_left * T);
  Camera camera_left{sl.c->image_size, sl.model, sl.params}, camera_right{sr.c->image_size, sr.model, sr.params};
  const SideResiduals rl = Residuals(camera_left, sl, x.left_from_pose), rr = Residuals(camera_right, sr, right_from_pose);
  out.rms_left_px = std::sqrt(rl.sum / static_cast<double>(std::max<size_t>(rl.n, 1)));
  out.rms_right_px = std::sqrt(rr.sum / static_cast<double>(std::max<size_t>(rr.n, 1)));
  out.dof = 2 * static_cast<int>(rl.n + rr.n) - free;
  if (out.dof <= 0) {
    out.exit_code = ExitCode::kDegenerate;
    out.message = left_file + " and " + right_file + ": too few points project in front of the solved cameras to estimate the noise";
    return out;
  }
  out.sigma_px = std::sqrt((rl.weighted_sum + rr.weighted_sum) / out.dof);
  const int g = sl.free.size() + sr.free.size() + 6;
  ArrowInformation information(g, static_cast<int>(keys.size()));
  AddInformation(sl, x, false, 0, 0, &information);
  AddInformation(sr, x, true, sl.free.size(), sl.free.size() + sr.free.size(), &information);
  const ArrowInverse inverse = InvertArrow(information, out.sigma_px * out.sigma_px);
  Eigen::MatrixXd cov_left, cov_right;
  if (inverse.observability.observable) {
    const Eigen::MatrixXd& global = inverse.covariance.global;
    cov_left = global.topLeftCorner(sl.free.size(), sl.free.size());
    cov_right = global.block(sl.free.size(), sl.free.size(), sr.free.size(), sr.free.size());
    ParameterCovariance relative;
    relative.parameters.assign(RelativePoseTangentNames().begin(), RelativePoseTangentNames().end());
    relative.matrix = global.bottomRightCorner(6, 6);
    relative.matrix = (0.5 * (relative.matrix + relative.matrix.transpose())).eval();
    rig.covariance = std::move(relative);
    // The same information's joint covariance, cross-covariances kept (err-sim draws a rig's
    // errors from it as one): each camera's free parameters mapped to the lens parameters they
    // move, as RigCamera does for the marginals, so that its blocks are those marginals.
    const int nl = sl.free.size(), nr = sr.free.size();
    const Eigen::MatrixXd bl = nl > 0 ? sl.free.MovedBasis() : Eigen::MatrixXd(0, 0);
    const Eigen::MatrixXd br = nr > 0 ? sr.free.MovedBasis() : Eigen::MatrixXd(0, 0);
    Eigen::MatrixXd basis = Eigen::MatrixXd::Zero(bl.rows() + br.rows() + 6, g);
    if (nl > 0) basis.block(0, 0, bl.rows(), nl) = bl;
    if (nr > 0) basis.block(bl.rows(), nl, br.rows(), nr) = br;
    basis.bottomRightCorner(6, 6).setIdentity();
    ParameterCovariance joint;
    if (nl > 0) {
      for (const std::string& p : sl.free.MovedParams(sl.model)) joint.parameters.push_back(JointCovarianceName(0, p));
    }
    if (nr > 0) {
      for (const std::string& p : sr.free.MovedParams(sr.model)) joint.parameters.push_back(JointCovarianceName(1, p));
    }
    joint.parameters.insert(joint.parameters.end(), RelativePoseTangentNames().begin(), RelativePoseTangentNames().end());
    joint.matrix = basis * global * basis.transpose();
    joint.matrix = (0.5 * (joint.matrix + joint.matrix.transpose())).eval();
    rig.joint_covariance = std::move(joint);
  } else {
    out.notes.push_back("no covariance written: the joint problem's information is singular (smallest scaled eigenvalue " +
                        std::to_string(inverse.observability.smallest_eigenvalue) + "); hold a camera or add views");
  }
  rig.left = RigCamera(left.camera.empty() ? "left" : left.camera, sl, rig.length_unit, cov_left);
  rig.right = RigCamera(right.camera.empty() ? "right" : right.camera, sr, rig.length_unit, cov_right);
  rig.fit = ComputeEpipolarFit(rig, solo_left->used, solo_right->used);
  return out;
}

}  // namespace vstcal
