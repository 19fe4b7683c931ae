// An image's size in pixels. An image of W × H pixels covers u ∈ [−0.5, W − 0.5], v ∈ [−0.5, H − 0.5]
// (docs/conventions.md#camera-frame-and-pixels).
#pragma once

namespace vstcal {

struct ImageSize {
  int width = 0;   // px
  int height = 0;  // px
  bool operator==(const ImageSize&) const = default;
};

}  // namespace vstcal
