// Length units carried by every file (docs/conventions.md#units).
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace vstcal {

enum class LengthUnit { kMillimetre, kCentimetre, kMetre, kInch };

// Every unit, in the order messages list them.
inline constexpr std::array<LengthUnit, 4> kLengthUnits = {LengthUnit::kMillimetre, LengthUnit::kCentimetre,
                                                           LengthUnit::kMetre, LengthUnit::kInch};

constexpr std::string_view LengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre: return "mm";
    case LengthUnit::kCentimetre: return "cm";
    case LengthUnit::kMetre: return "m";
    case LengthUnit::kInch: return "in";
  }
  return "?";
}

// The names of kLengthUnits, in order: {"mm", "cm", "m", "in"}.
inline constexpr std::array<std::string_view, kLengthUnits.size()> kLengthUnitNames = {
    LengthUnitName(kLengthUnits[0]), LengthUnitName(kLengthUnits[1]), LengthUnitName(kLengthUnits[2]),
    LengthUnitName(kLengthUnits[3])};

constexpr std::optional<LengthUnit> LengthUnitFromName(std::string_view name) {
  for (const LengthUnit unit : kLengthUnits) {
    if (LengthUnitName(unit) == name) return unit;
  }
  return std::nullopt;
}

// Metres in one unit. The inch is exactly 25.4 mm (international yard and pound, 1959).
constexpr double MetresPer(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre: return 1e-3;
    case LengthUnit::kCentimetre: return 1e-2;
    case LengthUnit::kMetre: return 1.0;
    case LengthUnit::kInch: return 0.0254;
  }
  return 1.0;
}

}  // namespace vstcal
