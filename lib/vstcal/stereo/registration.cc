#include "vstcal/stereo/registration.h"

#include <string>

#include "vstcal/core/error.h"

namespace vstcal {

std::string_view RegistrationModeName(RegistrationMode mode) {
  return NameOf(kRegistrationModeNames, mode);
}

std::optional<RegistrationMode> RegistrationModeFromName(std::string_view name) {
  return FromName(kRegistrationModeNames, name);
}

namespace {

// The embedded points an eye tracked in this frame, with their pixels.
struct EyeData {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> pixels;
};

EyeData Tracked(std::span<const Eigen::Vector3d> embedded, const std::vector<std::optional<Eigen::Vector2d>>& pixels) {
  EyeData eye;
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (!pixels[i]) continue;
    eye.points.push_back(embedded[i]);
    eye.pixels.push_back(*pixels[i]);
  }
  return eye;
}

struct EyeSolve {
  PoseStatus status = PoseStatus::kNoSolution;
  Rigid3d camera_from_world;
  std::optional<Rigid3d> mirrored;  // a planar layout's other branch (pnp.h)
  int iterations = 0;
};

// The closed form (or `start`), checked for what no solver can overcome.
EyeSolve Start(const Camera& camera, const EyeData& eye, const std::optional<Rigid3d>& start) {
  if (eye.points.size() < kMinPnpPoints) return {PoseStatus::kTooFewPoints, {}, {}, 0};
  if (ClassifyLayout(eye.points) == PointLayout::kCollinear) return {PoseStatus::kCollinear, {}, {}, 0};
  if (start) return {PoseStatus::kOk, *start, std::nullopt, 0};
  const ClosedFormPose c = SolvePnpClosedForm(camera, eye.points, eye.pixels);
  return {c.status, c.camera_from_world, c.mirrored, 0};
}

// Refines the start (and a planar layout's mirrored start) over `sets`; keeps the lower cost.
EyeSolve Refine(std::span<const PoseObservations> sets, const EyeSolve& start, const PoseRefineOptions& refine) {
  const PoseRefinement best = RefineBranches(sets, start.camera_from_world, start.mirrored, refine);
  return {best.status, best.body_from_world, {}, best.iterations};
}

EyeSolve SolveEye(const Camera& camera, const EyeData& eye, const std::optional<Rigid3d>& start,
                  const PoseRefineOptions& refine) {
  const EyeSolve s = Start(camera, eye, start);
  if (s.status != PoseStatus::kOk) return s;
  const PoseObservations set{&camera, Rigid3d::Identity(), eye.points, eye.pixels};
  return Refine({&set, 1}, s, refine);
}

ResidualStats Reprojection(const Camera& camera, const Rigid3d& camera_from_world, const EyeData& eye) {
  std::vector<Eigen::Vector2d> residuals;
  for (size_t i = 0; i < eye.points.size(); ++i) {
    if (const auto px = camera.Project(camera_from_world * eye.points[i])) residuals.push_back(*px - eye.pixels[i]);
  }
  return Summarize(residuals);
}

std::vector<std::optional<Eigen::Vector2d>> ProjectAll(const Camera& camera, const Rigid3d& camera_from_world,
                                                       std::span<const Eigen::Vector3d> points) {
  std::vector<std::optional<Eigen::Vector2d>> out;
  out.reserve(points.size());
  for (const Eigen::Vector3d& p : points) out.push_back(camera.Project(camera_from_world * p));
  return out;
}

FrameRegistration Failed(PoseStatus status, const char* eye) {
  FrameRegistration f;
  f.status = status;
  f.failed_eye = eye;
  return f;
}

}  // namespace

FrameRegistration RegisterFrame(const StereoRig& rig, std::span<const Eigen::Vector3d> embedded, const TrackedFrame& frame,
                                std::span<const Eigen::Vector3d> virtual_points, RegistrationMode mode,
                                const std::optional<Rigid3d>& start, const PoseRefineOptions& refine) {
  VSTCAL_CHECK(frame.left.size() == embedded.size() && (frame.right.empty() || frame.right.size() == embedded.size()),
               "a frame has one pixel entry per embedded point");
  const Camera& left_camera = rig.left.camera;
  const Camera& right_camera = rig.right.camera;
  const EyeData left = Tracked(embedded, frame.left);
  const EyeData right = Tracked(embedded, frame.right);
  FrameRegistration f;
  switch (mode) {
    case RegistrationMode::kLeft: {
      const EyeSolve s = SolveEye(left_camera, left, start, refine);
      if (s.status != PoseStatus::kOk) return Failed(s.status, "left");
      f.left_from_world = s.camera_from_world;
      f.right_from_world = rig.right_from_left * s.camera_from_world;
      f.iterations = s.iterations;
      break;
    }
    case RegistrationMode::kPerEye: {
      const EyeSolve l = SolveEye(left_camera, left, start, refine);
      if (l.status != PoseStatus::kOk) return Failed(l.status, "left");
      const std::optional<Rigid3d> right_start =
          start ? std::optional<Rigid3d>(rig.right_from_left * *start) : std::nullopt;
      const EyeSolve r = SolveEye(right_camera, right, right_start, refine);
      if (r.status != PoseStatus::kOk) return Failed(r.status, "right");
      f.left_from_world = l.camera_from_world;
      f.right_from_world = r.camera_from_world;
      f.iterations = l.iterations + r.iterations;
      break;
    }
    case RegistrationMode::kJoint: {
      // Start from the eye that can be solved alone (the left one when both can).
      EyeSolve s = Start(left_camera, left, start);
      if (s.status != PoseStatus::kOk && !start) {
        const EyeSolve r = Start(right_camera, right, std::nullopt);
        if (r.status != PoseStatus::kOk) return Failed(s.status, "left");
        const Rigid3d left_from_right = rig.right_from_left.inverse();
        s = {PoseStatus::kOk, left_from_right * r.camera_from_world,
             r.mirrored ? std::optional<Rigid3d>(left_from_right * *r.mirrored) : std::nullopt, 0};
      }
      if (s.status != PoseStatus::kOk) return Failed(s.status, "left");
      const PoseObservations sets[2] = {{&left_camera, Rigid3d::Identity(), left.points, left.pixels},
                                        {&right_camera, rig.right_from_left, right.points, right.pixels}};
      const EyeSolve r = Refine(sets, s, refine);
      if (r.status != PoseStatus::kOk) return Failed(r.status, "left");
      f.left_from_world = r.camera_from_world;
      f.right_from_world = rig.right_from_left * r.camera_from_world;
      f.iterations = r.iterations;
      break;
    }
  }
  f.status = PoseStatus::kOk;
  f.left_fit = Reprojection(left_camera, f.left_from_world, left);
  if (!frame.right.empty()) f.right_fit = Reprojection(right_camera, f.right_from_world, right);
  f.virtual_left = ProjectAll(left_camera, f.left_from_world, virtual_points);
  f.virtual_right = ProjectAll(right_camera, f.right_from_world, virtual_points);
  return f;
}

namespace {

std::vector<Eigen::Vector3d> Points(const std::vector<NamedPoint>& points) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(points.size());
  for (const NamedPoint& p : points) out.push_back(p.point_in_world);
  return out;
}

std::string SizeText(const ImageSize& s) { return std::to_string(s.width) + "×" + std::to_string(s.height); }

}  // namespace

std::vector<FrameRegistration> RegisterSequence(const StereoRig& rig, const Tracks& tracks, const RegistrationOptions& options) {
  const std::vector<Eigen::Vector3d> embedded = Points(tracks.embedded), virtual_points = Points(tracks.virtual_points);
  std::vector<FrameRegistration> out;
  out.reserve(tracks.frames.size());
  std::optional<Rigid3d> previous;
  for (const TrackedFrame& frame : tracks.frames) {
    out.push_back(RegisterFrame(rig, embedded, frame, virtual_points, options.mode,
                                options.warm_start ? previous : std::nullopt, options.refine));
    previous = out.back().status == PoseStatus::kOk ? std::optional<Rigid3d>(out.back().left_from_world) : std::nullopt;
  }
  return out;
}

void CheckTracksAgainstRig(const StereoRig& rig, const Tracks& tracks, std::string_view rig_name,
                           std::string_view tracks_name) {
  const std::string t(tracks_name), r(rig_name);
  if (tracks.length_unit != rig.length_unit) {
    throw InputError(t + ": length_unit: \"" + std::string(LengthUnitName(tracks.length_unit)) + "\", but " + r +
                     " is in \"" + std::string(LengthUnitName(rig.length_unit)) +
                     "\"; give the embedded points in the rig's unit");
  }
  if (!(tracks.left_image_size == rig.left.camera.image_size)) {
    throw InputError(t + ": image_size.left: " + SizeText(tracks.left_image_size) + ", but the rig's left camera in " + r +
                     " is " + SizeText(rig.left.camera.image_size) + "; track the images the rig was calibrated at");
  }
  if (tracks.right_image_size && !(*tracks.right_image_size == rig.right.camera.image_size)) {
    throw InputError(t + ": image_size.right: " + SizeText(*tracks.right_image_size) + ", but the rig's right camera in " +
                     r + " is " + SizeText(rig.right.camera.image_size) + "; track the images the rig was calibrated at");
  }
  if (ClassifyLayout(Points(tracks.embedded)) == PointLayout::kCollinear) {
    throw DegenerateError(t + ": embedded_points: the points lie on one line, so the rotation about it is free and no "
                              "frame can be registered; embed at least 4 points not on one line");
  }
}

}  // namespace vstcal
