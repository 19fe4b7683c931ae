// The table of functions the codecs plugin (image/codecs/codecs_plugin.cc, libvstcal_codecs.so)
// gives the library: OpenCV's image codecs and video input, which the library reaches only through
// it (image/codecs.h says why). Both sides are built from this header by the same compiler, so
// the table passes C++ types; its version changes whenever a field does.
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

namespace vstcal {

struct CodecsTable {
  static constexpr int kVersion = 1;
  int version;
  // cv::imdecode(encoded, IMREAD_GRAYSCALE); false when OpenCV cannot decode it.
  bool (*decode_gray)(const cv::Mat& encoded, cv::Mat* gray);
  // cv::imencode(".png", image); false when encoding fails.
  bool (*encode_png)(const cv::Mat& image, std::vector<unsigned char>* png);
  // A cv::VideoCapture: opened on a camera or a file with one backend (nullptr: not opened), then
  // grab, read, get and close as cv::VideoCapture's.
  void* (*video_open_camera)(int index);
  void* (*video_open_file)(const char* path, int api);
  bool (*video_grab)(void* video);
  bool (*video_read)(void* video, cv::Mat* frame);
  double (*video_get)(void* video, int property);
  void (*video_close)(void* video);
};

}  // namespace vstcal

// The plugin's one exported symbol.
extern "C" const vstcal::CodecsTable* vstcal_codecs_table();
