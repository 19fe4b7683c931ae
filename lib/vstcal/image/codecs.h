// OpenCV's image codecs (decoding photographs, encoding PNG) and video input, loaded on first use
// from the codecs plugin, libvstcal_codecs.so. Linking them into every program cost each start
// ~0.25 s of CPU and 60 MB: OpenCV's imgcodecs and videoio bring 240 shared libraries (GDAL, HDF5,
// FFmpeg, GStreamer …), loaded by every tool run and every test process whether or not it reads
// an image (docs/performance.md#startup). The plugin is found at the path the build wrote
// (kCodecsPluginPath), or at $VSTCAL_CODECS_PLUGIN.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

namespace vstcal {

// An encoded image (PNG, JPEG, BMP, TIFF, PGM …) as 8-bit gray; empty when OpenCV cannot decode it.
cv::Mat DecodeGrayImage(const cv::Mat& encoded);

// The PNG bytes of an 8-bit gray, BGR or BGRA image; InternalError when encoding fails.
std::vector<unsigned char> PngBytes(const cv::Mat& image, const char* what);

// A video file or a camera, read frame by frame (a cv::VideoCapture in the plugin).
class VideoSource {
 public:
  VideoSource() = default;
  VideoSource(const VideoSource&) = delete;
  VideoSource& operator=(const VideoSource&) = delete;
  ~VideoSource();

  bool OpenCamera(int index);
  // With one backend, `api` (cv::CAP_FFMPEG …).
  bool OpenFile(const std::string& path, int api);
  bool IsOpened() const { return video_ != nullptr; }
  bool Grab();
  bool Read(cv::Mat* frame);
  double Get(int property) const;  // cv::CAP_PROP_…

 private:
  void* video_ = nullptr;
};

}  // namespace vstcal
