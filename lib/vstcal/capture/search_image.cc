#include "vstcal/capture/search_image.h"

#include <opencv2/imgproc.hpp>

namespace vstcal {
namespace {

// Reduced images keep at least this many pixels a side (a strip of an image stays searchable).
constexpr int kMinSearchSide = 8;

}  // namespace

bool CanShrink(int width, int height, int by) { return width / by >= kMinSearchSide && height / by >= kMinSearchSide; }

int SearchFactor(int width, int height) {
  int f = 1;
  while (static_cast<double>(width / f) * (height / f) > kSearchPixels && CanShrink(width, height, f + 1)) ++f;
  return f;
}

SearchImage Shrink(const SearchImage& from, int by) {
  if (by <= 1) return from;
  SearchImage out;
  out.factor = from.factor * by;
  // Cropped to whole blocks, so that INTER_AREA is the exact box average of each block.
  const cv::Mat whole = from.image(cv::Rect(0, 0, from.image.cols / by * by, from.image.rows / by * by));
  cv::resize(whole, out.image, cv::Size(whole.cols / by, whole.rows / by), 0, 0, cv::INTER_AREA);
  return out;
}

SearchImage ReduceForSearch(const cv::Mat& full) { return Shrink(SearchImage{full, 1}, SearchFactor(full.cols, full.rows)); }

}  // namespace vstcal
