// Summary statistics of error magnitudes for the reports (docs/math/report-statistics.md): exact
// order statistics of a small sample held in memory (the Monte Carlo summaries of
// sensitivity/mc_summary.h stream instead and use histograms).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "vstcal/core/image_size.h"

namespace vstcal {

// Of n ≥ 1 values x (any unit; the caller names it), sorted ascending as x₍₀₎ ≤ … ≤ x₍ₙ₋₁₎:
//   mean = Σx/n,  rms = √(Σx²/n),  max = x₍ₙ₋₁₎,
//   quantile q at h = q·(n − 1): x₍⌊h⌋₎ + (h − ⌊h⌋)(x₍⌊h⌋+1₎ − x₍⌊h⌋₎)   (linear interpolation
//   between order statistics: Hyndman–Fan type 7, NumPy's default), median = q 0.5, p95 = q 0.95.
// Sums run in input order, so the same values give the same bits.
struct ErrorStats {
  size_t n = 0;
  double mean = 0, rms = 0, median = 0, p95 = 0, max = 0;
};

// nullopt for no values. Every value must be finite (a bug otherwise: callers exclude what they
// cannot measure and count it).
std::optional<ErrorStats> ComputeErrorStats(std::span<const double> values);

// A cols × rows grid over the image: cell (c, r) covers u ∈ [−0.5 + c·W/cols, −0.5 + (c+1)·W/cols)
// and likewise v (pixel centres at integers, docs/conventions.md); a pixel outside the image
// belongs to no cell.
struct ImageGrid {
  ImageSize image_size;
  int cols = 1, rows = 1;
  // Row-major cell index r·cols + c, or nullopt outside the image.
  std::optional<size_t> CellOf(const Eigen::Vector2d& pixel) const;
  size_t num_cells() const { return static_cast<size_t>(cols) * static_cast<size_t>(rows); }
  // The centre of cell (col, row), px.
  Eigen::Vector2d CellCentre(int col, int row) const;
};

// The statistics of `values[i]` per grid cell of `pixels[i]` (same length): one entry per cell,
// row-major, nullopt for cells that hold no value.
std::vector<std::optional<ErrorStats>> ComputeGridStats(const ImageGrid& grid, std::span<const Eigen::Vector2d> pixels,
                                                        std::span<const double> values);

}  // namespace vstcal
