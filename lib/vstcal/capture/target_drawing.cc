#include "vstcal/capture/target_drawing.h"

#include <array>
#include <cmath>
#include <cstdio>

#include <opencv2/core/mat.hpp>

#include "vstcal/capture/target_pattern.h"
#include "vstcal/core/error.h"
#include "vstcal/image/codecs.h"
#include "vstcal/json/json_writer.h"
#include "vstcal/core/option_name.h"

namespace vstcal {
namespace {

constexpr double kMaxMegapixels = 200;

// Millimetres per length unit.
double DrawingMillimetres(LengthUnit unit) { return MetresPer(unit) * 1000; }

std::string Mm(double v) {
  // Sub-micrometre precision, no exponent: SVG viewers differ on long or exponent forms.
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4f", std::abs(v) < 5e-5 ? 0.0 : v);
  std::string s = buf;
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  return s;
}

uint32_t Crc32(const uint8_t* data, size_t n, uint32_t crc = 0) {
  crc = ~crc;
  for (size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

void PutBigEndian(uint32_t v, std::string* out) {
  for (int shift = 24; shift >= 0; shift -= 8) out->push_back(static_cast<char>((v >> shift) & 0xFF));
}

// A ruler check for the print: a bar of a round length (the longest of 200, 100, 50 … mm that the
// pattern's width holds), ticked every tenth and labelled, in the outer half of the bottom margin,
// where it stays clear of the pattern's edge. Its length runs between the centres of its end
// ticks, which are the ends of the bar (butt caps): "h<length>" in its path.
std::string ScaleBar(const Rect& sheet, const Rect& pattern, double mm) {
  const double width = pattern.width() * mm, margin = (sheet.y1 - pattern.y1) * mm;
  double length = 0;
  for (double l : {200.0, 100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0}) {
    if (l <= width) {
      length = l;
      break;
    }
  }
  if (length == 0 || !(margin > 0)) return "";
  const double u = std::min(0.4 * margin, 8.0);  // height of the bar with its label
  const double x0 = (pattern.x0 - sheet.x0) * mm, top = (pattern.y1 - sheet.y0) * mm + 0.5 * margin;
  const double line = top + 0.45 * u, stroke = std::min(0.25, u / 20);
  std::string ticks;
  for (int k = 0; k <= 10; ++k) {
    const double x = x0 + length * k / 10;
    // Appended: GCC 12's -Wrestrict misfires on "literal" + std::string.
    ticks.append("M").append(Mm(x)).append(" ").append(Mm(k % 5 == 0 ? top : top + 0.2 * u)).append("V").append(Mm(line));
  }
  const std::string label = Mm(length) + " mm";
  return "<g id=\"scale-bar\" data-length-mm=\"" + Mm(length) + "\" stroke=\"#000\" stroke-width=\"" + Mm(stroke) +
         "\" stroke-linecap=\"butt\" fill=\"none\">\n<path id=\"scale-bar-line\" d=\"M" + Mm(x0) + " " + Mm(line) + "h" +
         Mm(length) + "\"/>\n<path id=\"scale-bar-ticks\" d=\"" + ticks + "\"/>\n<text x=\"" + Mm(x0 + 0.5 * length) + "\" y=\"" +
         Mm(top + u) + "\" font-family=\"sans-serif\" font-size=\"" + Mm(0.45 * u) +
         "\" text-anchor=\"middle\" stroke=\"none\" fill=\"#000\">" + label + " (check with a ruler)</text>\n</g>\n";
}

}  // namespace

std::string TargetSvg(const Target& t) {
  const Pattern pattern = TargetPattern(t);
  const Rect& sheet = pattern.sheet();
  const double mm = DrawingMillimetres(t.length_unit);
  const double w = sheet.width() * mm, h = sheet.height() * mm;
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + Mm(w) + "mm\" height=\"" + Mm(h) +
         "mm\" viewBox=\"0 0 " + Mm(w) + " " + Mm(h) + "\">\n";
  svg += "<title>vstcal target: " + DescribeTarget(t) + "</title>\n";
  svg += "<!-- Print at 100 % (actual size, no fit to page): the sheet is " + Mm(w) + " mm × " + Mm(h) +
         " mm. Measure a square after printing and put the measured size in the target file. -->\n";
  svg += "<rect x=\"0\" y=\"0\" width=\"" + Mm(w) + "\" height=\"" + Mm(h) + "\" fill=\"#fff\"/>\n";
  svg += "<path fill=\"#000\" shape-rendering=\"crispEdges\" d=\"";
  for (const Rect& r : pattern.black()) {
    const double x0 = (r.x0 - sheet.x0) * mm, y0 = (r.y0 - sheet.y0) * mm;
    svg.append("M").append(Mm(x0)).append(" ").append(Mm(y0)).append("H").append(Mm((r.x1 - sheet.x0) * mm));
    svg.append("V").append(Mm((r.y1 - sheet.y0) * mm)).append("H").append(Mm(x0)).append("Z");
  }
  svg += "\"/>\n";
  svg += ScaleBar(sheet, PatternExtent(t), mm);
  svg += "</svg>\n";
  return svg;
}

GrayImage RasterizeTarget(const Target& t, double dpi) {
  if (!(std::isfinite(dpi) && dpi > 0)) throw InputError(VSTCAL_OPT("dpi") ": must be a positive number of pixels per inch");
  const Pattern pattern = TargetPattern(t);
  const Rect& sheet = pattern.sheet();
  const double pitch = 25.4 / dpi / DrawingMillimetres(t.length_unit);  // one pixel in the target's unit
  const double cols = std::ceil(sheet.width() / pitch - 1e-9), rows = std::ceil(sheet.height() / pitch - 1e-9);
  if (cols * rows > kMaxMegapixels * 1e6) {
    char buf[200];
    std::snprintf(buf, sizeof buf, VSTCAL_OPT("dpi") ": %.0f dpi makes a %.0f × %.0f image (%.0f megapixels, more than %.0f); use a lower " VSTCAL_OPT("dpi"),
                  dpi, cols, rows, cols * rows / 1e6, kMaxMegapixels);
    throw InputError(buf);
  }
  GrayImage image(static_cast<int>(cols), static_cast<int>(rows), 255);
  const double area = pitch * pitch;
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const double x0 = sheet.x0 + u * pitch, y0 = sheet.y0 + v * pitch;
      const std::array<Eigen::Vector2d, 4> square = {Eigen::Vector2d(x0, y0), Eigen::Vector2d(x0 + pitch, y0),
                                                     Eigen::Vector2d(x0 + pitch, y0 + pitch), Eigen::Vector2d(x0, y0 + pitch)};
      const double black = std::min(1.0, pattern.BlackArea(square) / area);
      image.at(u, v) = static_cast<uint8_t>(std::lround(255 * (1 - black)));
    }
  }
  return image;
}

std::string EncodePng(const GrayImage& image, double dpi) {
  const cv::Mat mat(image.height, image.width, CV_8U, const_cast<uint8_t*>(image.pixels.data()));
  const std::vector<uint8_t> bytes = PngBytes(mat, "the target");
  std::string png(bytes.begin(), bytes.end());
  if (dpi <= 0) return png;
  // pHYs (pixels per metre, unit 1 = metre) right after IHDR, which ends at byte 8 + 25 = 33.
  constexpr size_t kAfterIhdr = 33;
  VSTCAL_CHECK(png.size() > kAfterIhdr && png.compare(12, 4, "IHDR") == 0, "unexpected PNG layout");
  const auto per_metre = static_cast<uint32_t>(std::lround(dpi / 0.0254));
  std::string chunk = "pHYs";
  PutBigEndian(per_metre, &chunk);
  PutBigEndian(per_metre, &chunk);
  chunk.push_back(1);
  std::string out = png.substr(0, kAfterIhdr);
  PutBigEndian(9, &out);
  out += chunk;
  PutBigEndian(Crc32(reinterpret_cast<const uint8_t*>(chunk.data()), chunk.size()), &out);
  out += png.substr(kAfterIhdr);
  return out;
}

}  // namespace vstcal
