// When each image was taken (docs/formats.md#image-times): calib-capture detect --times gives every
// view the time its image was taken, for hand-eye calibration (a video's frames have theirs from
// the container). A text file, a line per image, two fields separated by spaces, tabs or a comma:
// the image's file name and its time, in either order ("left01.jpg 12.345" or EuRoC's
// "1403636579763555584,1403636579763555584.png"); '#' starts a comment line. The name is matched
// against the images' file names (without folders).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vstcal/core/enum_names.h"

namespace vstcal {

enum class TimeUnit { kSecond, kMillisecond, kMicrosecond, kNanosecond };
inline constexpr EnumNames<TimeUnit, 4> kTimeUnitNames = {
    {{TimeUnit::kSecond, "s"}, {TimeUnit::kMillisecond, "ms"}, {TimeUnit::kMicrosecond, "us"}, {TimeUnit::kNanosecond, "ns"}}};

// At most this many lines with a time (a 1 kHz camera for 16 minutes).
inline constexpr size_t kMaxImageTimes = 1'000'000;

// Image file name → time in seconds (`unit`: the file's). `image_names` are the file names the
// detection reads: a line names one of them by either field, the other field is its time. Throws
// InputError naming the file and line: not two fields, neither field an image's name, a time that
// is not a finite number, one image named twice, more than kMaxImageTimes lines.
std::map<std::string, double> ImageTimesFromText(const std::string& text, const std::string& name, const std::vector<std::string>& image_names,
                                                 TimeUnit unit);
std::map<std::string, double> ReadImageTimes(const std::filesystem::path& path, const std::vector<std::string>& image_names, TimeUnit unit);

}  // namespace vstcal
