#include "vstcal/capture/paper.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace vstcal {
namespace {

const std::array<Paper, 3> kStandardPapers = {{{"A4", 210, 297}, {"Letter", 215.9, 279.4}, {"A3", 297, 420}}};

// Rounding can leave a fitted sheet a few ulps over the paper.
constexpr double kToleranceMm = 1e-9;

double Millimetres(LengthUnit unit) { return MetresPer(unit) * 1000; }

// Printable steps per unit: 0.1 mm, 0.01 cm, 0.0001 m, 0.001 in (a divisor, so that k / d is the
// decimal a user types).
double StepsPerUnit(LengthUnit unit) {
  switch (unit) {
    case LengthUnit::kMillimetre: return 10;
    case LengthUnit::kCentimetre: return 100;
    case LengthUnit::kMetre: return 10000;
    case LengthUnit::kInch: return 1000;
  }
  return 10;
}

bool PositiveNumber(std::string_view text, double* value) {
  if (text.empty() || text.size() > 30) return false;
  const std::string s(text);
  char* end = nullptr;
  *value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(*value) && *value > 0;
}

std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace

std::span<const Paper> StandardPapers() { return kStandardPapers; }

std::optional<Paper> PaperFromName(std::string_view text) {
  std::string lower(text);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const Paper& p : kStandardPapers) {
    std::string name = p.name;
    std::transform(name.begin(), name.end(), name.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (lower == name) return p;
  }
  const size_t x = lower.find('x');
  double w = 0, h = 0;
  if (x == std::string::npos || !PositiveNumber(std::string_view(lower).substr(0, x), &w) ||
      !PositiveNumber(std::string_view(lower).substr(x + 1), &h)) {
    return std::nullopt;
  }
  return Paper{Num(w) + " × " + Num(h) + " mm", std::min(w, h), std::max(w, h)};
}

bool SheetFitsPaper(double w_mm, double h_mm, const Paper& paper) {
  const double small = std::min(w_mm, h_mm), large = std::max(w_mm, h_mm);
  return small <= paper.width_mm + kToleranceMm && large <= paper.height_mm + kToleranceMm;
}

std::optional<Paper> SmallestStandardPaper(double w_mm, double h_mm) {
  for (const Paper& p : kStandardPapers) {
    if (SheetFitsPaper(w_mm, h_mm, p)) return p;
  }
  return std::nullopt;
}

Target WithSize(Target t, double size, const TargetLengths& given) {
  if (t.type == TargetType::kAprilGrid) {
    t.tag_size = size;  // tag_spacing is a fraction of it: the gaps and junction squares follow
    t.margin = given.margin.value_or(t.tag_spacing * size);
  } else if (t.type == TargetType::kAprilTagGrid) {
    t.tag_size = size;
    t.tag_gap = given.tag_gap.value_or(0.25 * size);
    t.margin = given.margin.value_or(t.tag_gap);
  } else {
    t.square_size = size;
    if (t.type == TargetType::kCharuco) t.marker_size = given.marker_size.value_or(0.75 * size);
    t.margin = given.margin.value_or(size);
  }
  return t;
}

std::optional<PaperFit> FitToPaper(const Target& target, const TargetLengths& given, const Paper& paper) {
  // The sheet is affine in the size: its slope and offset from two sizes.
  const double mm = Millimetres(target.length_unit);
  const Rect one = SheetExtent(WithSize(target, 1, given)), two = SheetExtent(WithSize(target, 2, given));
  const double ax = (two.width() - one.width()) * mm, bx = one.width() * mm - ax;
  const double ay = (two.height() - one.height()) * mm, by = one.height() * mm - ay;
  // Portrait: X along the paper's short side; landscape: along its long side.
  auto largest = [&](double across, double down) { return std::min((across - bx) / ax, (down - by) / ay); };
  const double portrait = largest(paper.width_mm, paper.height_mm), landscape = largest(paper.height_mm, paper.width_mm);
  const double steps = StepsPerUnit(target.length_unit);
  const double size = std::floor(std::max(portrait, landscape) * steps + 1e-9) / steps;
  if (!(size > 0)) return std::nullopt;
  PaperFit fit;
  fit.size = size;
  fit.landscape = landscape > portrait;
  const Rect sheet = SheetExtent(WithSize(target, size, given));
  fit.sheet_width_mm = sheet.width() * mm;
  fit.sheet_height_mm = sheet.height() * mm;
  return fit;
}

}  // namespace vstcal
