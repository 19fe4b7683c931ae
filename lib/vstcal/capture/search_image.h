// The reduced image the finders search (docs/tools/calib-capture.md#time-budget). OpenCV's
// chessboard finders and ArUco detector, and libapriltag's quad search, cannot be cancelled: they
// are bounded by what they are given. An image larger than kSearchPixels is box-averaged by the
// smallest whole factor that brings it under, the finders search that, and what they find is
// mapped back (an integer factor maps exactly) and refined at full resolution. A 12 MP or 100 MP
// image then costs the finders, in time and memory, what a 1 MP one does. Internal to the capture
// module.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

namespace vstcal {

// The largest image the finders search (1280×720 and smaller are searched as they are).
inline constexpr double kSearchPixels = 1.0e6;

// An image the finders search: `factor` × `factor` full-resolution pixels averaged into each of
// its pixels. Its pixel (x, y) is centred on full-resolution pixel factor·(x, y) + (factor − 1)/2.
struct SearchImage {
  cv::Mat image;
  int factor = 1;
};

// The full-resolution position of position (x, y) in an image reduced by `factor` (pixel centres
// at integers in both).
inline Eigen::Vector2d ToFullResolution(int factor, double x, double y) {
  const double offset = 0.5 * (factor - 1);
  return Eigen::Vector2d(factor * x + offset, factor * y + offset);
}

// Whether an image of width × height can be reduced by `by` and keep a searchable strip (8 px a side).
bool CanShrink(int width, int height, int by);

// The smallest integer factor that brings width × height to at most kSearchPixels.
int SearchFactor(int width, int height);

// `from` reduced by `by` more (the block average of each by × by block, cropped to whole blocks).
SearchImage Shrink(const SearchImage& from, int by);

// The image reduced by SearchFactor (the image itself, not a copy, at 1 MP or less).
SearchImage ReduceForSearch(const cv::Mat& full);

}  // namespace vstcal
