// The parameter vector θ of the VST chain, declared once (docs/math/vst-chain.md#parameters).
//
// Every error term is one row of kTerms: its source, where it sits in a chain file, how many
// components it has, its unit, and whether it exists once, once per eye, once per test point or
// once per fiducial. Everything else is derived from that table and the chain's shape:
//  - ParameterLayout: θ's offsets (the chain reads θ through Offset(term, eye)),
//  - the parameter names ("tracking.rotation.x", "camera_intrinsic.left.fx"), used by the sweep,
//    Sobol and linear outputs and by --parameter,
//  - the file terms the sources reader accepts (errsim/formats/sources_reader.cc),
//  - units and the file ↔ internal conversion.
// Adding an error term is one row here and its use in chain.h.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "vstcal/camera/camera.h"
#include "vstcal/core/units.h"
#include "vstcal/errsim/eyes.h"
#include "vstcal/errsim/sources.h"

namespace vstcal {

enum class Term : int {
  kTrackerAlignmentRotation,
  kTrackerAlignmentTranslation,
  kTrackingRotation,
  kTrackingTranslation,
  kTrackingLatency,
  kCameraRotation,
  kCameraTranslation,
  kBaseline,
  kRigRotation,
  kRigTranslation,
  kLens,
  kRenderLatency,
  kDisparity,
  kEyepoint,
  kScreenShift,
  kMagnification,
  kLensK1,
  kEyeOffset,
  kIpd,
  kDisplayLatency,
  kObjectRotation,
  kObjectTranslation,
  kFiducial,
  kCount
};
inline constexpr int kNumTerms = static_cast<int>(Term::kCount);

// Units of a term in files (the internal unit in brackets): kAngle deg [rad], kLength the chain's
// length unit, kTime s, kPixel px, kRelative 1, kLensParameter px for fx, fy, cx, cy, s and 1 for
// the distortion coefficients.
enum class TermUnit { kAngle, kLength, kTime, kPixel, kRelative, kLensParameter };
enum class TermScope { kOnce, kPerEye };
// How many times a term repeats: once, per test point, per fiducial; kLens has as many components
// as the eye's renderer lens has parameters.
enum class TermExtent { kFixed, kPerTestPoint, kPerFiducial, kLens };

struct TermDecl {
  Term term;
  Source source;
  // In the file, sources.<source>[.<eye>|.both][.<group>].<file_key>; in names,
  // <source>[.<eye>][.<group>].<name>[<item>][.<axis>].
  std::string_view group;
  std::string_view name;
  std::string_view file_key;
  int components;  // 3: x, y, z; 2: u, v; 1: a scalar (kLens: set by the lens)
  TermUnit unit;
  TermScope scope;
  TermExtent extent;
};

// clang-format off
inline constexpr std::array<TermDecl, kNumTerms> kTerms = {{
    // tracker_alignment: left perturbation of tracker_from_virtual, tracker frame (seed 001 §4.1).
    {Term::kTrackerAlignmentRotation,    Source::kTrackerAlignment, "", "rotation",      "rotation_deg",    3, TermUnit::kAngle,  TermScope::kOnce,   TermExtent::kFixed},
    {Term::kTrackerAlignmentTranslation, Source::kTrackerAlignment, "", "translation",   "translation",     3, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    // tracking: left perturbation of the measured hmd_from_tracker, hmd frame; the pose's age (§4.2).
    {Term::kTrackingRotation,            Source::kTracking,         "", "rotation",      "rotation_deg",    3, TermUnit::kAngle,  TermScope::kOnce,   TermExtent::kFixed},
    {Term::kTrackingTranslation,         Source::kTracking,         "", "translation",   "translation",     3, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    {Term::kTrackingLatency,             Source::kTracking,         "", "latency",       "latency_s",       1, TermUnit::kTime,   TermScope::kOnce,   TermExtent::kFixed},
    // camera_extrinsic: per eye a left perturbation of camera_from_hmd (camera frame); the
    // baseline error; the stereo head's mount, shared by both cameras (hmd frame) (§4.3).
    {Term::kCameraRotation,              Source::kCameraExtrinsic,  "", "rotation",      "rotation_deg",    3, TermUnit::kAngle,  TermScope::kPerEye, TermExtent::kFixed},
    {Term::kCameraTranslation,           Source::kCameraExtrinsic,  "", "translation",   "translation",     3, TermUnit::kLength, TermScope::kPerEye, TermExtent::kFixed},
    {Term::kBaseline,                    Source::kCameraExtrinsic,  "", "baseline",      "baseline",        1, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    {Term::kRigRotation,                 Source::kCameraExtrinsic,  "rig", "rotation",   "rotation_deg",    3, TermUnit::kAngle,  TermScope::kOnce,   TermExtent::kFixed},
    {Term::kRigTranslation,              Source::kCameraExtrinsic,  "rig", "translation", "translation",    3, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    // camera_intrinsic: the renderer's lens parameters per eye, in the lens model's order (§4.4).
    {Term::kLens,                        Source::kCameraIntrinsic,  "", "",              "",                0, TermUnit::kLensParameter, TermScope::kPerEye, TermExtent::kLens},
    // rendering: render latency; the stereo matcher's disparity error at each test point (§4.5).
    {Term::kRenderLatency,               Source::kRendering,        "", "latency",       "latency_s",       1, TermUnit::kTime,   TermScope::kOnce,   TermExtent::kFixed},
    {Term::kDisparity,                   Source::kRendering,        "", "disparity",     "disparity_px",    1, TermUnit::kPixel,  TermScope::kOnce,   TermExtent::kPerTestPoint},
    // display: per eye the eyepoint's offset from its design position (hmd frame), screen shift,
    // magnification and the HMD lens's residual k1; both eyes' common offset (how the HMD sits);
    // the user's IPD minus the design IPD; video-to-photon latency (§4.6).
    {Term::kEyepoint,                    Source::kDisplay,          "", "eyepoint",      "eyepoint",        3, TermUnit::kLength, TermScope::kPerEye, TermExtent::kFixed},
    {Term::kScreenShift,                 Source::kDisplay,          "", "screen_shift",  "screen_shift_px", 2, TermUnit::kPixel,  TermScope::kPerEye, TermExtent::kFixed},
    {Term::kMagnification,               Source::kDisplay,          "", "magnification", "magnification",   1, TermUnit::kRelative, TermScope::kPerEye, TermExtent::kFixed},
    {Term::kLensK1,                      Source::kDisplay,          "", "lens_k1",       "lens_k1",         1, TermUnit::kRelative, TermScope::kPerEye, TermExtent::kFixed},
    {Term::kEyeOffset,                   Source::kDisplay,          "", "eye_offset",    "eye_offset",      3, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    {Term::kIpd,                         Source::kDisplay,          "", "ipd",           "ipd",             1, TermUnit::kLength, TermScope::kOnce,   TermExtent::kFixed},
    {Term::kDisplayLatency,              Source::kDisplay,          "", "latency",       "latency_s",       1, TermUnit::kTime,   TermScope::kOnce,   TermExtent::kFixed},
    // virtual_object_alignment: pose form, left perturbation of virtual_from_object (virtual
    // frame); fiducial form, each fiducial's localization error (virtual frame) (§4.7).
    {Term::kObjectRotation,              Source::kVirtualObjectAlignment, "", "rotation",    "rotation_deg", 3, TermUnit::kAngle,  TermScope::kOnce, TermExtent::kFixed},
    {Term::kObjectTranslation,           Source::kVirtualObjectAlignment, "", "translation", "translation",  3, TermUnit::kLength, TermScope::kOnce, TermExtent::kFixed},
    {Term::kFiducial,                    Source::kVirtualObjectAlignment, "", "fiducial",    "fiducials",    3, TermUnit::kLength, TermScope::kOnce, TermExtent::kPerFiducial},
}};
// clang-format on

constexpr const TermDecl& Declaration(Term term) { return kTerms[static_cast<int>(term)]; }

namespace detail {
constexpr bool TermsInOrder() {
  for (int i = 0; i < kNumTerms; ++i) {
    if (static_cast<int>(kTerms[i].term) != i) return false;
    if (i > 0 && static_cast<int>(kTerms[i].source) < static_cast<int>(kTerms[i - 1].source)) return false;
  }
  return true;
}
}  // namespace detail
// Rows in Term order, grouped by source: a source's slots are contiguous in θ.
static_assert(detail::TermsInOrder(), "kTerms must list every Term in order, grouped by source");

// What the layout depends on besides the table.
struct ChainShape {
  std::vector<std::string> test_points;                  // names, in order
  size_t fiducials = 0;                                  // 0: the pose form of virtual_object_alignment
  std::array<AnyLensModel, kNumEyes> renderer_lens{};    // the renderer's lens model per eye
  LengthUnit length_unit = LengthUnit::kMillimetre;
};

// One slot of θ.
struct SlotInfo {
  std::string name;        // "tracking.rotation.x", "camera_intrinsic.left.fx", "rendering.disparity[base]"
  Term term;
  int eye = 0;             // 0 for terms that exist once
  std::string file_unit;   // "deg", "mm", "s", "px", "1"
  double file_per_internal = 1;  // 180/π for angles, 1 otherwise
};

// θ's offsets, derived from kTerms and a ChainShape. Every term always has its slots (a term the
// chain does not use is fixed at 0), so the chain reads fixed offsets and never branches on
// configuration.
class ParameterLayout {
 public:
  ParameterLayout() = default;
  explicit ParameterLayout(const ChainShape& shape);

  int Offset(Term term, int eye = 0) const { return offset_[static_cast<int>(term)][eye]; }
  int Size(Term term, int eye = 0) const { return size_[static_cast<int>(term)][eye]; }
  int size() const { return size_total_; }
  // A source's slots are [Begin, End).
  int Begin(Source source) const;
  int End(Source source) const;
  // Name, unit and term of every slot, in θ order.
  const std::vector<SlotInfo>& slots() const { return slots_; }

 private:
  std::array<std::array<int, kNumEyes>, kNumTerms> offset_{}, size_{};
  int size_total_ = 0;
  std::vector<SlotInfo> slots_;
};

// The file unit of a term's component ("deg", "mm", …) and its file-per-internal factor.
std::string FileUnit(TermUnit unit, LengthUnit length_unit, int component);
double FilePerInternal(TermUnit unit);

}  // namespace vstcal
