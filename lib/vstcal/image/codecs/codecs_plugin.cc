// libvstcal_codecs.so: OpenCV's image codecs and video input behind CodecsTable (image/codecs.h).
// Every OpenCV exception stops here: the library sees false or nullptr.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "vstcal/image/codecs_table.h"

namespace vstcal {
namespace {

bool DecodeGray(const cv::Mat& encoded, cv::Mat* gray) {
  try {
    *gray = cv::imdecode(encoded, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception&) {
    gray->release();
  }
  return !gray->empty();
}

bool EncodePng(const cv::Mat& image, std::vector<unsigned char>* png) {
  try {
    return cv::imencode(".png", image, *png);
  } catch (const cv::Exception&) {
    return false;
  }
}

cv::VideoCapture* Opened(cv::VideoCapture* video) {
  if (video->isOpened()) return video;
  delete video;
  return nullptr;
}

void* VideoOpenCamera(int index) {
  try {
    auto* video = new cv::VideoCapture();
    video->open(index);
    return Opened(video);
  } catch (const cv::Exception&) {
    return nullptr;
  }
}

void* VideoOpenFile(const char* path, int api) {
  try {
    auto* video = new cv::VideoCapture();
    video->open(path, api);
    return Opened(video);
  } catch (const cv::Exception&) {
    return nullptr;
  }
}

bool VideoGrab(void* video) {
  try {
    return static_cast<cv::VideoCapture*>(video)->grab();
  } catch (const cv::Exception&) {
    return false;
  }
}

bool VideoRead(void* video, cv::Mat* frame) {
  try {
    return static_cast<cv::VideoCapture*>(video)->read(*frame);
  } catch (const cv::Exception&) {
    return false;
  }
}

double VideoGet(void* video, int property) {
  try {
    return static_cast<cv::VideoCapture*>(video)->get(property);
  } catch (const cv::Exception&) {
    return 0;
  }
}

void VideoClose(void* video) { delete static_cast<cv::VideoCapture*>(video); }

constexpr CodecsTable kTable = {CodecsTable::kVersion, DecodeGray,  EncodePng, VideoOpenCamera, VideoOpenFile,
                                VideoGrab,             VideoRead,   VideoGet,  VideoClose};

}  // namespace
}  // namespace vstcal

extern "C" __attribute__((visibility("default"))) const vstcal::CodecsTable* vstcal_codecs_table() { return &vstcal::kTable; }
