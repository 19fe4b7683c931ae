#include "vstcal/errsim/schema.h"

#include "vstcal/core/error.h"
#include "vstcal/geometry/rotation.h"

namespace vstcal {
namespace {

constexpr std::array<std::string_view, 3> kXyz = {"x", "y", "z"};
constexpr std::array<std::string_view, 2> kUv = {"u", "v"};

// How many items a term has (test points, fiducials, or 1) and the components of each.
int Items(const TermDecl& d, const ChainShape& shape) {
  switch (d.extent) {
    case TermExtent::kPerTestPoint: return static_cast<int>(shape.test_points.size());
    case TermExtent::kPerFiducial: return static_cast<int>(shape.fiducials);
    case TermExtent::kFixed:
    case TermExtent::kLens: return 1;
  }
  return 1;
}

int Components(const TermDecl& d, const ChainShape& shape, int eye) {
  return d.extent == TermExtent::kLens ? LensModelNumParams(shape.renderer_lens[eye]) : d.components;
}

// Names are built by appending: GCC 12's -Wrestrict misfires on "literal" + std::string.
std::string ItemName(const TermDecl& d, const ChainShape& shape, int item) {
  if (d.extent == TermExtent::kPerTestPoint) return std::string("[").append(shape.test_points[item]).append("]");
  if (d.extent == TermExtent::kPerFiducial) return std::string("[").append(std::to_string(item)).append("]");
  return "";
}

std::string ComponentName(const TermDecl& d, const ChainShape& shape, int eye, int component) {
  if (d.extent == TermExtent::kLens) return std::string(LensModelParamNames(shape.renderer_lens[eye])[component]);
  if (d.components == 3) return std::string(kXyz[component]);
  if (d.components == 2) return std::string(kUv[component]);
  return "";
}

}  // namespace

std::string FileUnit(TermUnit unit, LengthUnit length_unit, int component) {
  switch (unit) {
    case TermUnit::kAngle: return "deg";
    case TermUnit::kLength: return std::string(LengthUnitName(length_unit));
    case TermUnit::kTime: return "s";
    case TermUnit::kPixel: return "px";
    case TermUnit::kRelative: return "1";
    case TermUnit::kLensParameter: return component < kNumIntrinsicParams ? "px" : "1";
  }
  return "1";
}

double FilePerInternal(TermUnit unit) { return unit == TermUnit::kAngle ? 180.0 / kPi : 1.0; }

ParameterLayout::ParameterLayout(const ChainShape& shape) {
  int at = 0;
  for (const TermDecl& d : kTerms) {
    const int t = static_cast<int>(d.term);
    const int eyes = d.scope == TermScope::kPerEye ? kNumEyes : 1;
    for (int eye = 0; eye < kNumEyes; ++eye) {
      if (eye >= eyes) {  // a term that exists once: both eyes read its one block
        offset_[t][eye] = offset_[t][0];
        size_[t][eye] = size_[t][0];
        continue;
      }
      offset_[t][eye] = at;
      const int items = Items(d, shape), components = Components(d, shape, eye);
      for (int item = 0; item < items; ++item) {
        for (int c = 0; c < components; ++c) {
          std::string name(SourceKey(d.source));
          if (d.scope == TermScope::kPerEye) name.append(".").append(kEyeNames[eye]);
          if (!d.group.empty()) name.append(".").append(d.group);
          if (!d.name.empty()) name.append(".").append(d.name);
          name.append(ItemName(d, shape, item));
          const std::string component = ComponentName(d, shape, eye, c);
          if (!component.empty()) name.append(".").append(component);
          slots_.push_back({std::move(name), d.term, eye, FileUnit(d.unit, shape.length_unit, c), FilePerInternal(d.unit)});
        }
      }
      size_[t][eye] = items * components;
      at += size_[t][eye];
    }
  }
  size_total_ = at;
  VSTCAL_CHECK(static_cast<int>(slots_.size()) == size_total_, "slot names and layout disagree");
}

int ParameterLayout::Begin(Source source) const {
  for (const TermDecl& d : kTerms) {
    if (d.source == source) return Offset(d.term);
  }
  return size_total_;
}

int ParameterLayout::End(Source source) const {
  const int next = static_cast<int>(source) + 1;
  return next == kNumSources ? size_total_ : Begin(static_cast<Source>(next));
}

}  // namespace vstcal
