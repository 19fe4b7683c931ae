// The --times file of calib-capture detect (docs/formats.md#image-times): the reader over a fixed set
// of image names, then every time it gave checked finite and its image one of those names.
#include <cmath>

#include "harness.h"
#include "vstcal/core/error.h"
#include "vstcal/formats/capture/image_times.h"

VSTCAL_FUZZ_TARGET(image_times, text) {
  using namespace vstcal;
  const std::vector<std::string> names = {"a.png", "b.jpg", "1403636579763555584.png"};
  for (const TimeUnit unit : {TimeUnit::kSecond, TimeUnit::kNanosecond}) {
    for (const auto& [name, time] : ImageTimesFromText(text, "fuzz.txt", names, unit)) {
      VSTCAL_CHECK(std::isfinite(time), "a time is finite");
      VSTCAL_CHECK(name == names[0] || name == names[1] || name == names[2], "a time belongs to a given image");
    }
  }
}
