#include "vstcal/formats/capture/image_times.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>

#include "vstcal/core/error.h"
#include "vstcal/json/reader_common.h"

namespace vstcal {
namespace {

[[noreturn]] void FailLine(const std::string& name, size_t line, const std::string& reason, const std::string& fix) {
  throw InputError(name + ": line " + std::to_string(line) + ": " + reason + "; " + fix);
}

bool ParseNumber(const std::string& word, double* out) {
  errno = 0;
  char* end = nullptr;
  *out = std::strtod(word.c_str(), &end);
  return end != word.c_str() && *end == '\0' && errno != ERANGE && std::isfinite(*out);
}

double SecondsPer(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kSecond: return 1;
    case TimeUnit::kMillisecond: return 1e-3;
    case TimeUnit::kMicrosecond: return 1e-6;
    case TimeUnit::kNanosecond: return 1e-9;
  }
  return 1;
}

// The first 40 bytes of a field, for a message.
std::string Quoted(const std::string& word) {
  std::string out = "\"";  // appended, not concatenated: GCC 12's -Wrestrict misfires on the temporaries
  out.append(word, 0, 40);
  out += "\"";
  return out;
}

}  // namespace

std::map<std::string, double> ImageTimesFromText(const std::string& text, const std::string& name, const std::vector<std::string>& image_names,
                                                 TimeUnit unit) {
  const std::set<std::string> images(image_names.begin(), image_names.end());
  std::map<std::string, double> times;
  size_t number = 0;
  for (size_t begin = 0; begin < text.size();) {
    size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(begin, end - begin);
    begin = end + 1;
    ++number;
    std::vector<std::string> fields;
    std::string field;
    for (const char c : line) {
      if (c == ' ' || c == '\t' || c == '\r' || c == ',') {
        if (!field.empty()) fields.push_back(std::move(field));
        field.clear();
      } else {
        field += c;
      }
    }
    if (!field.empty()) fields.push_back(std::move(field));
    if (fields.empty() || fields[0][0] == '#') continue;
    if (fields.size() != 2) {
      FailLine(name, number, std::to_string(fields.size()) + " fields where a line has 2 (the image's file name and its time)",
               "write one image a line, or comment the line out with #");
    }
    // Which field is the name: the one an image has (EuRoC's names are their times in ns).
    const bool first_is_name = images.count(fields[0]) > 0;
    if (!first_is_name && images.count(fields[1]) == 0) {
      FailLine(name, number, "neither " + Quoted(fields[0]) + " nor " + Quoted(fields[1]) + " is the file name of an image given",
               "give the images' file names as they are on disk (without folders), or drop the line");
    }
    const std::string& image = first_is_name ? fields[0] : fields[1];
    const std::string& word = first_is_name ? fields[1] : fields[0];
    double time = 0;
    if (!ParseNumber(word, &time)) FailLine(name, number, Quoted(word) + " is not a finite number", "give the image's time");
    if (times.count(image)) FailLine(name, number, Quoted(image) + " has a time already", "give each image one time");
    if (times.size() == kMaxImageTimes) {
      FailLine(name, number, "more than " + std::to_string(kMaxImageTimes) + " images (docs/reliability.md#limits)", "split the recording");
    }
    times[image] = time * SecondsPer(unit);
  }
  return times;
}

std::map<std::string, double> ReadImageTimes(const std::filesystem::path& path, const std::vector<std::string>& image_names, TimeUnit unit) {
  return ImageTimesFromText(ReadInputFile(path, "an image-times file"), path.string(), image_names, unit);
}

}  // namespace vstcal
