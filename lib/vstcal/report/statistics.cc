#include "vstcal/report/statistics.h"

#include "vstcal/sensitivity/bootstrap.h"

#include <algorithm>
#include <cmath>

#include "vstcal/core/error.h"

namespace vstcal {

std::optional<ErrorStats> ComputeErrorStats(std::span<const double> values) {
  if (values.empty()) return std::nullopt;
  double sum = 0, sum2 = 0;
  for (const double x : values) {
    VSTCAL_CHECK(std::isfinite(x), "statistics of finite values only");
    sum += x;
    sum2 += x * x;
  }
  std::vector<double> sorted(values.begin(), values.end());
  std::sort(sorted.begin(), sorted.end());
  const double n = static_cast<double>(values.size());
  return ErrorStats{values.size(), sum / n, std::sqrt(sum2 / n), SortedQuantile(sorted, 0.5),
                    SortedQuantile(sorted, 0.95), sorted.back()};
}

std::optional<size_t> ImageGrid::CellOf(const Eigen::Vector2d& pixel) const {
  VSTCAL_CHECK(cols > 0 && rows > 0 && image_size.width > 0 && image_size.height > 0, "a grid over an image");
  // Offsets from the image's top-left edge, in cells; the edges are half a pixel outside centre 0.
  const double cu = (pixel.x() + 0.5) * cols / image_size.width;
  const double cv = (pixel.y() + 0.5) * rows / image_size.height;
  if (!(cu >= 0 && cu < cols && cv >= 0 && cv < rows)) return std::nullopt;
  return static_cast<size_t>(cv) * static_cast<size_t>(cols) + static_cast<size_t>(cu);
}

Eigen::Vector2d ImageGrid::CellCentre(int col, int row) const {
  return {-0.5 + image_size.width * (col + 0.5) / cols, -0.5 + image_size.height * (row + 0.5) / rows};
}

std::vector<std::optional<ErrorStats>> ComputeGridStats(const ImageGrid& grid, std::span<const Eigen::Vector2d> pixels,
                                                        std::span<const double> values) {
  VSTCAL_CHECK(pixels.size() == values.size(), "one value per pixel");
  std::vector<std::vector<double>> cells(grid.num_cells());
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (const auto cell = grid.CellOf(pixels[i])) cells[*cell].push_back(values[i]);
  }
  std::vector<std::optional<ErrorStats>> stats;
  stats.reserve(cells.size());
  for (const std::vector<double>& cell : cells) stats.push_back(ComputeErrorStats(cell));
  return stats;
}

}  // namespace vstcal
