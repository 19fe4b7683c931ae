// Length units carried by every file (docs/conventions.md#units).
#pragma once

#include <optional>
#include <string_view>

namespace vstcal {

enum class LengthUnit { kMillimetre, kCentimetre, kMetre };

constexpr std::string_view LengthUnitName(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre: return "mm";
    case LengthUnit::kCentimetre: return "cm";
    case LengthUnit::kMetre: return "m";
  }
  return "?";
}

constexpr std::optional<LengthUnit> LengthUnitFromName(std::string_view name) {
  if (name == "mm") return LengthUnit::kMillimetre;
  if (name == "cm") return LengthUnit::kCentimetre;
  if (name == "m") return LengthUnit::kMetre;
  return std::nullopt;
}

// Metres in one unit.
constexpr double MetresPer(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre: return 1e-3;
    case LengthUnit::kCentimetre: return 1e-2;
    case LengthUnit::kMetre: return 1.0;
  }
  return 1.0;
}

}  // namespace vstcal
